"""Test-suite settings.

Under CI (the environment variable CI is set, as `.ci/run` runs) hypothesis draws its examples
deterministically, so a submission's result does not depend on luck; everywhere else it
explores new random examples on every run.
"""

import os

from hypothesis import settings

settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")


import pytest


@pytest.fixture(autouse=True)
def _english_locale(monkeypatch):
    """The CLI's --lang default follows the locale: every test starts from an English one, so
    the suite gives the same result on any machine (a test that wants another sets it)."""
    monkeypatch.setenv("LC_ALL", "en_US.UTF-8")
