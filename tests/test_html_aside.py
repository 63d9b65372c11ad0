"""The page's plans and a share of its scheme drawn by a fork (`velplan.html.aside`): the same
page, and the part built here wherever the fork cannot give it."""

from __future__ import annotations

import os

import pytest

from velplan.html import aside, page
from velplan.study import Study

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the fork is Linux's")


def _forks(monkeypatch) -> list[int]:
    """Count the forks made from now on."""
    made: list[int] = []
    fork = os.fork

    def counted():
        pid = fork()
        if pid:
            made.append(pid)
        return pid

    monkeypatch.setattr(aside.os, "fork", counted)
    return made


def test_the_page_built_beside_a_fork_is_the_same(monkeypatch):
    study = Study("press", n=12)
    alone = page.page_html(study, "ru")
    made = _forks(monkeypatch)
    monkeypatch.setattr(aside, "core_free", lambda **_: True)
    with aside.building_aside():
        beside = page.page_html(Study("press", n=12), "ru")
    assert len(made) == 1
    assert beside == alone
    with pytest.raises(ChildProcessError):
        os.waitpid(made[0], os.WNOHANG)  # the fork was waited for


def test_no_fork_outside_the_block_or_on_a_busy_machine(monkeypatch):
    made = _forks(monkeypatch)
    assert aside.Aside(lambda: 7).result() == 7
    monkeypatch.setattr(aside, "core_free", lambda **_: False)
    with aside.building_aside():
        assert aside.Aside(lambda: 8).result() == 8
    assert made == []


def test_a_part_the_fork_fails_on_is_built_here_and_its_error_raised_here(monkeypatch):
    made = _forks(monkeypatch)
    monkeypatch.setattr(aside, "core_free", lambda **_: True)
    here = os.getpid()

    def only_here():
        if os.getpid() != here:
            raise RuntimeError("the fork fails")
        return "built here"

    with aside.building_aside():
        assert aside.Aside(only_here).result() == "built here"
        part = aside.Aside(lambda: 1 / 0)
        with pytest.raises(ZeroDivisionError):
            part.result()
    assert len(made) == 2


def test_a_fork_that_cannot_start_leaves_the_part_here(monkeypatch):
    def refused():
        raise OSError("no fork")

    monkeypatch.setattr(aside, "core_free", lambda **_: True)
    monkeypatch.setattr(aside.os, "fork", refused)
    with aside.building_aside():
        part = aside.Aside(lambda: [1, 2])
        assert part.pid is None
        assert part.result() == [1, 2]


def test_a_core_is_free_now_where_the_average_still_says_busy(monkeypatch):
    from velplan import io

    monkeypatch.setattr(io.os, "getloadavg", lambda: (3.0, 3.0, 3.0))
    monkeypatch.setattr(io, "running_now", lambda: 1)  # this process alone
    assert io.core_free(2, now=True) and not io.core_free(2)
    monkeypatch.setattr(io, "running_now", lambda: 3)
    assert not io.core_free(2, now=True)
    monkeypatch.setattr(io, "running_now", lambda: None)  # not said: the average decides
    assert not io.core_free(2, now=True)
    monkeypatch.setattr(io.os, "getloadavg", lambda: (1.2, 3.0, 3.0))
    assert io.core_free(2, now=True) and io.core_free(2)
    assert not io.core_free(1, now=True)
    running = io.running_now()
    assert running is None or running >= 1
