"""The page in a real browser (headless Chromium driven by selenium): the
paper's conductor example explored end to end, as a person would.

Needs the Debian packages ``chromium`` and ``chromium-driver`` (``.ci/run``
installs them) and the test dependency selenium; skipped without them, unless
``ETHASP_REQUIRE_BROWSER=1`` (set by ``.ci/run``), when they must be there.  A
screenshot of the page is written to ``tests/output/page.png`` (or
``$ETHASP_TEST_OUTPUT``); with ``ETHASP_UPDATE_SCREENSHOT=1`` it also
replaces the README's ``docs/page.png``.
"""

from __future__ import annotations

import os
import shutil
import tempfile
import threading
from pathlib import Path

import pytest

from conftest import MODELS, ROOT

pytestmark = pytest.mark.slow  # a real browser, end to end

if os.environ.get("ETHASP_REQUIRE_BROWSER") == "1":
    from selenium import webdriver
else:
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed")
from selenium.common.exceptions import TimeoutException  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.support.ui import Select, WebDriverWait  # noqa: E402

from ethasp import Model  # noqa: E402
from ethasp.interfaces.version import package_version  # noqa: E402
from ethasp.interfaces.web.server import Server  # noqa: E402
from ethasp.interfaces.web.workspace import Workspace  # noqa: E402

BROWSER = next((shutil.which(name) for name in ("chromium", "chromium-browser", "google-chrome")
                if shutil.which(name)), None)
DRIVER = shutil.which("chromedriver")
MISSING = "headless Chromium is not installed (apt-get install chromium chromium-driver)"
if BROWSER is None or DRIVER is None:
    if os.environ.get("ETHASP_REQUIRE_BROWSER") == "1":  # CI installs them (.ci/run)
        raise RuntimeError(MISSING)
    pytest.skip(MISSING, allow_module_level=True)

OUTPUT = Path(os.environ.get("ETHASP_TEST_OUTPUT", ROOT / "tests" / "output"))
README_SCREENSHOT = ROOT / "docs" / "page.png"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-dev-shm-usage", "--hide-scrollbars", "--window-size=1400,1000"]
WAIT = 120  # seconds the page may take for a step (a slow, shared machine)

CONDUCTOR = (
    "The man could refrain from action. This would be permissible under the do-no-harm "
    "principle because this way the death of the five persons is not caused by his action. "
    "Alternatively, the man could pull the lever. Doing so is impermissible under the "
    "do-no-harm principle because this way the death of the one person is caused by his "
    "action.")
UTILITARIAN_CONTRAST = ("Alternatively, the man could pull the lever. Doing so is permissible "
                        "under the utilitarianism principle because five saved lives is "
                        "better than one saved life.")


@pytest.fixture(scope="module")
def server():
    workspace = Workspace(Model.load([MODELS / "trolley.lp"]), [str(MODELS / "trolley.lp")],
                          "do-no-harm")
    running = Server(workspace, None, 0)
    thread = threading.Thread(target=running.serve_forever, daemon=True)
    thread.start()
    yield running
    running.shutdown()
    thread.join(30)


@pytest.fixture(scope="module")
def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = BROWSER
    for flag in FLAGS:
        options.add_argument(flag)
    profile = tempfile.mkdtemp(prefix="ethasp-chromium-")
    options.add_argument(f"--user-data-dir={profile}")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = webdriver.ChromeService(executable_path=DRIVER)
    driver = webdriver.Chrome(options=options, service=service)
    yield driver
    driver.quit()
    shutil.rmtree(profile, ignore_errors=True)


def text(driver, element_id: str) -> str:
    return driver.find_element(By.ID, element_id).text


def wait_for(driver, condition, what: str):
    try:
        return WebDriverWait(driver, WAIT, poll_frequency=0.1).until(lambda d: condition(d))
    except TimeoutException:
        error = driver.find_element(By.ID, "error").text
        raise AssertionError(f"the page did not show {what} (error shown: {error!r})") from None


def click(driver, element) -> None:
    """Click as a person would, with the element scrolled to the middle of the
    window (not under the page's sticky header)."""
    driver.execute_script("arguments[0].scrollIntoView({block: 'center'})", element)
    element.click()


def idle(driver) -> bool:
    return not driver.find_element(By.ID, "status").is_displayed()


def screenshot(driver, name: str) -> Path:
    OUTPUT.mkdir(parents=True, exist_ok=True)
    driver.execute_script("window.scrollTo(0, 0)")
    height = driver.execute_script("return document.documentElement.scrollHeight")
    driver.set_window_size(1400, height + 20)
    path = OUTPUT / name
    driver.save_screenshot(str(path))
    driver.set_window_size(1400, 1000)
    return path


def test_conductor_example_in_the_browser(server, browser):
    driver = browser
    driver.get(server.url)
    # The page starts a dialogue under do-no-harm: the plan refrain.
    wait_for(driver, lambda d: "do-no-harm" in text(d, "current-summary")
             and d.find_elements(By.CSS_SELECTOR, "#judgements .card"), "the first plan")
    assert text(driver, "model-name") == "trolley.lp"
    footer = driver.find_element(By.CSS_SELECTOR, "footer #version").text
    assert footer == f"ethasp {package_version()}"
    glance = text(driver, "model")
    assert "pull the lever" in glance and "the death of the five persons" in glance
    assert "Agent: the man" in glance
    assert [e.text for e in driver.find_elements(By.CSS_SELECTOR, "#current-actions button")] == \
        ["refrain"]
    cards = {card.get_attribute("data-principle"): card.text
             for card in driver.find_elements(By.CSS_SELECTOR, "#judgements .card")}
    assert set(cards) == {"deontology", "do-no-harm", "utilitarianism"}
    assert "permissible" in cards["do-no-harm"] and "impermissible" in cards["utilitarianism"]
    assert ("Doing so is permissible because this way the death of the five persons is not "
            "caused by the man's action.") in cards["do-no-harm"]
    assert "not Caused(five_will_die)" in cards["do-no-harm"]

    # Click the action in the plan's picture and ask "why this rather than pull?".
    wait_for(driver, lambda d: d.find_elements(By.CSS_SELECTOR, "#current-picture g.action"),
             "the plan's picture")
    click(driver, driver.find_element(By.CSS_SELECTOR, "#current-picture g.action"))
    wait_for(driver, lambda d: d.find_element(By.ID, "action-menu").is_displayed(), "the menu")
    Select(driver.find_element(By.ID, "rather-other")).select_by_visible_text("pull")
    click(driver, driver.find_element(By.ID, "why-rather"))
    wait_for(driver, lambda d: idle(d) and d.find_element(By.ID, "answer-panel").is_displayed()
             and CONDUCTOR in text(d, "answer-text"), "the conductor's answer")
    assert driver.find_element(By.ID, "question").get_attribute("value") == \
        "why refrain rather than pull"
    assert "Principle dropped" in text(driver, "answer-notes")
    highlighted = {e.text for e in driver.find_elements(By.CSS_SELECTOR, "#answer-panel .literal.diff")}
    assert highlighted == {"not Caused(five_will_die)", "Caused(one_will_die)"}
    assert "Plan asked about" in text(driver, "side-original")
    assert "Contrast plan" in text(driver, "side-contrast") and "impermissible" in text(driver, "side-contrast")
    wait_for(driver, lambda d: "the plans part at step 1" in text(d, "answer-picture"),
             "the contrast picture")
    assert "why refrain rather than pull" in text(driver, "history")
    screenshot(driver, "page-conductor.png")

    # Switch to utilitarianism, take the question back and ask it again.
    Select(driver.find_element(By.ID, "under")).select_by_visible_text("utilitarianism")
    wait_for(driver, lambda d: "contrast plans must now satisfy utilitarianism" in text(d, "note"),
             "the switch")
    click(driver, driver.find_element(By.ID, "undo"))
    wait_for(driver, lambda d: idle(d) and "took back" in text(d, "note")
             and not d.find_element(By.ID, "answer-panel").is_displayed(), "the undo")
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why refrain rather than pull\n")
    wait_for(driver, lambda d: idle(d) and UTILITARIAN_CONTRAST in text(d, "answer-text"),
             "the answer under utilitarianism")
    assert "Principle dropped" not in text(driver, "answer-notes")
    assert "permissible" in text(driver, "side-contrast")
    assert "under utilitarianism" in text(driver, "history")

    # A reload finds the same dialogue.
    driver.refresh()
    wait_for(driver, lambda d: UTILITARIAN_CONTRAST in text(d, "answer-text"), "the reloaded state")
    assert Select(driver.find_element(By.ID, "under")).first_selected_option.text == "utilitarianism"
    assert len(driver.find_elements(By.CSS_SELECTOR, "#history li")) == 1
    wait_for(driver, lambda d: "the plans part at step 1" in text(d, "answer-picture"),
             "the picture after the reload")
    path = screenshot(driver, "page.png")
    assert path.stat().st_size > 10_000
    if os.environ.get("ETHASP_UPDATE_SCREENSHOT") == "1":
        README_SCREENSHOT.parent.mkdir(exist_ok=True)
        shutil.copyfile(path, README_SCREENSHOT)

    # An action that the current plan (pull) does not use: "why not this?".
    click(driver, driver.find_element(By.CSS_SELECTOR, '#model-actions button[data-term="refrain"]'))
    wait_for(driver, lambda d: d.find_element(By.ID, "action-menu").is_displayed(), "the menu")
    assert "(not in the current plan)" in text(driver, "action-menu")
    assert driver.find_elements(By.ID, "why-not") and not driver.find_elements(By.ID, "why-this")

    # Errors show the command line's one-line messages.
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why not jump\n")
    wait_for(driver, lambda d: idle(d) and text(d, "error"), "the error")
    assert text(driver, "error") == "error: question 'why not jump': unknown action jump"
    screenshot(driver, "page-error.png")
    severe = [entry["message"] for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
    assert severe == [], severe


@pytest.fixture
def slow_server(monkeypatch):
    """A server whose questions search until they are cancelled (reporting
    progress as the searches do), to see a long request on the page."""
    from ethasp.interfaces.web import workspace as workspace_module

    original = workspace_module.searching

    def slow(call, budget, *args, **kwargs):
        if getattr(call, "__name__", "") == "ask":
            budget.report("contrast plan search", horizon=2)
            for _ in range(2400):                # until cancelled (at most a minute)
                if budget.cancelled:
                    break
                threading.Event().wait(0.025)
        return original(call, budget, *args, **kwargs)

    monkeypatch.setattr(workspace_module, "searching", slow)
    workspace = Workspace(Model.load([MODELS / "trolley.lp"]), [str(MODELS / "trolley.lp")],
                          "do-no-harm")
    running = Server(workspace, None, 0)
    thread = threading.Thread(target=running.serve_forever, daemon=True)
    thread.start()
    yield running
    running.shutdown()
    thread.join(30)


def test_a_long_search_shows_progress_and_can_be_cancelled(slow_server, browser):
    driver = browser
    driver.get(slow_server.url)
    wait_for(driver, lambda d: "do-no-harm" in text(d, "current-summary") and idle(d),
             "the first plan")
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why refrain rather than pull\n")
    wait_for(driver, lambda d: d.find_element(By.ID, "status").is_displayed()
             and "contrast plan search: horizon 2" in text(d, "status-progress"), "the progress")
    assert text(driver, "status-text") == "answering 'why refrain rather than pull'\u2026"
    assert text(driver, "status-time").endswith(" s")
    assert not driver.find_element(By.ID, "ask").is_enabled()
    screenshot(driver, "page-running.png")
    click(driver, driver.find_element(By.ID, "cancel"))
    wait_for(driver, lambda d: idle(d) and "cancelled" in text(d, "note"), "the cancellation")
    assert text(driver, "note") == "cancelled: the dialogue is unchanged"
    assert driver.find_elements(By.CSS_SELECTOR, "#history li") == []
    assert not driver.find_element(By.ID, "answer-panel").is_displayed()
    assert driver.find_element(By.ID, "ask").is_enabled()
