"""The interactive page in a real browser: Debian's headless Chromium, offline, from file://.

The page is loaded, the crank-angle slider moved with the keyboard, the plans built step by
step with the buttons, and what is visible checked: the readouts, the caption, the number of
construction steps drawn, the table of values. A screenshot is written (to
``$VELPLAN_SCREENSHOTS`` when set, else the test's temporary directory) to be looked at.
Skipped, saying why, where /usr/bin/chromium, its driver or selenium is missing.
"""

from __future__ import annotations

import re

import os
import time
from pathlib import Path

import numpy as np
import pytest

from velplan.html import Page
from velplan.study import Study
from velplan.views.base import number
from velplan.html.frames import readable  # whole indices marked (v_{A4}), set as <sub> by the page
from velplan.render.shapes import plain_text

CHROMIUM = Path("/usr/bin/chromium")
DRIVER = Path("/usr/bin/chromedriver")

pytestmark = [
    pytest.mark.skipif(not CHROMIUM.exists(), reason="no /usr/bin/chromium: apt-get install chromium chromium-driver "
                                                     "(.ci/run does) to run the page in a browser"),
    pytest.mark.skipif(not DRIVER.exists(), reason="no /usr/bin/chromedriver: apt-get install chromium-driver"),
]


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed (pip install '.[test]')")
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = str(CHROMIUM)
    profile = tmp_path_factory.mktemp("chromium-profile")
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--disable-background-networking", "--disable-component-update", "--no-first-run",
                "--disable-sync", "--disable-extensions", "--host-resolver-rules=MAP * ~NOTFOUND",
                f"--user-data-dir={profile}", "--window-size=1500,1250", "--lang=ru"):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(str(DRIVER)), options=options)
    driver.set_page_load_timeout(20)
    yield driver
    driver.quit()


def _text(driver, element_id: str) -> str:
    return driver.find_element("id", element_id).text


def _steps_shown(driver, plan: str) -> list[int]:
    """Construction steps with something drawn on the plan, and the number of those emphasised."""
    return driver.execute_script(
        "var s = {}; document.querySelectorAll('#plan-' + arguments[0] + ' [data-s]')"
        ".forEach(function (e) { s[e.getAttribute('data-s')] = 1; });"
        "return Object.keys(s).map(Number).sort(function (a, b) { return a - b; });", plan)


def test_the_page_plays_and_builds_the_plans_step_by_step(browser, tmp_path):
    from selenium.webdriver.common.keys import Keys

    started = time.perf_counter()
    study = Study("shaper", n=72)
    page = Page(study, lang="ru")
    path = page.save(tmp_path / "shaper.html")
    d = browser
    d.get(path.resolve().as_uri())

    # loaded offline: nothing fetched besides the file itself, no script error
    assert d.execute_script("return performance.getEntriesByType('resource').length") == 0
    assert d.execute_script("return document.getElementById('plan-v').childElementCount") > 10
    assert _text(d, "readout-pos") == "Положение 1/72"
    assert _text(d, "mu-v") == "μv = 0,05 (м/с)/мм" and _text(d, "mu-a").startswith("μa = 0,5 (м/с²)/мм")
    assert _text(d, "step-readout") == "Планы целиком"

    # the slider, moved with the keyboard as a user does
    slider = d.find_element("id", "pos")
    slider.click()
    for _ in range(3):
        slider.send_keys(Keys.ARROW_RIGHT)
    k = int(d.execute_script("return document.getElementById('pos').value"))
    assert k > 1 and _text(d, "readout-pos") == f"Положение {k}/72"
    phi = round(float(np.degrees(study.phi[k - 1])) % 360.0, 2)
    assert _text(d, "readout-phi") == f"φ = {number(phi, 'ru', 5)}°"
    assert _text(d, "rates").startswith("ω₂ = 8,378 рад/с")

    # step by step: the first step draws the pole only, the acceleration plan is empty
    d.find_element("id", "first").click()
    assert _steps_shown(d, "v") == [1] and _steps_shown(d, "a") == []
    res = study.plan("velocity")
    total = len(res.describe(k, "ru"))
    for step in range(2, 5):
        d.find_element("id", "next").click()
        assert _steps_shown(d, "v") == list(range(1, step + 1))
    sentence = readable(res.describe(k, "ru")[3])
    assert _text(d, "caption") == f"Шаг 4/{total}. {plain_text(sentence)}"  # the index below the line
    subs = d.execute_script("return Array.from(document.querySelectorAll('#caption sub')).map(e => e.textContent)")
    assert subs == [m.group(1) for m in re.finditer(r"_\{([^{}]*)\}", sentence)] and subs
    assert _text(d, "step-readout") == f"План скоростей · Шаг 4/{total}"
    assert d.execute_script("return document.querySelectorAll('#plan-v .now').length") >= 1
    # the intersection's step: its rows in the table, highlighted, with the analytic values
    d.find_element("id", "next").click()
    rows = d.find_elements("css selector", "#values-body tr.now")
    assert rows and all(r.text.split()[0] == "v5" for r in rows)
    assert "vA4" in " ".join(r.text for r in rows)  # the course writes velocities in lowercase v
    assert d.execute_script("return document.querySelectorAll('#values-body sub').length") > 0

    # on into the acceleration plan: the velocity plan stays whole, the acceleration plan grows
    for _ in range(total - 5 + 2):
        d.find_element("id", "next").click()
    assert _steps_shown(d, "v") == list(range(1, total + 1)) and _steps_shown(d, "a") == [1, 2]
    assert _text(d, "caption").startswith("Шаг 2/") and "π" in _text(d, "caption")
    d.find_element("id", "prev").click()
    assert _steps_shown(d, "a") == [1]
    d.find_element("id", "next").click()
    d.find_element("id", "next").click()
    screenshot = Path(os.environ.get("VELPLAN_SCREENSHOTS", tmp_path))
    screenshot.mkdir(parents=True, exist_ok=True)
    png = screenshot / "html-page-shaper-ru.png"
    assert d.save_screenshot(str(png))
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 50_000
    _check_screenshot(png)

    # play and pause: the crank turns by itself
    d.find_element("id", "play").click()
    time.sleep(0.5)
    d.find_element("id", "play").click()
    assert int(d.execute_script("return document.getElementById('pos').value")) != k
    assert _text(d, "play").endswith("Пуск")
    d.find_element("id", "all").click()
    assert len(_steps_shown(d, "a")) == len(study.plan("acceleration").describe(1, "ru"))
    assert time.perf_counter() - started < 20


def _check_screenshot(png: Path) -> None:
    """The picture shows ink in all three panels and the current step in red."""
    from matplotlib.image import imread

    rgb = imread(str(png))[..., :3]
    dark = (rgb.sum(axis=2) < 1.0)
    red = (rgb[..., 0] > 0.6) & (rgb[..., 1] < 0.3) & (rgb[..., 2] < 0.3)
    h, w = dark.shape
    panels = dark[int(0.15 * h):int(0.6 * h)]
    thirds = [panels[:, j * w // 3:(j + 1) * w // 3].mean() for j in range(3)]
    assert min(thirds) > 3e-4, thirds
    assert red.sum() > 30



def test_the_notebook_frame_plays_on_its_own(browser, tmp_path):
    """What Jupyter shows (`Page._repr_html_`) runs in its sandboxed frame with no kernel."""
    page = Page("four-bar", positions=12, lang="en")
    host = tmp_path / "notebook.html"
    host.write_text(f"<!DOCTYPE html><html><body>{page._repr_html_()}</body></html>", "utf-8")
    browser.get(host.resolve().as_uri())
    browser.switch_to.frame(browser.find_element("tag name", "iframe"))
    try:
        assert _text(browser, "readout-pos") == "Position 1/12"
        browser.find_element("id", "next").click()
        assert _steps_shown(browser, "v") == [1]
        assert _text(browser, "caption").startswith("Step 1/")
    finally:
        browser.switch_to.default_content()
