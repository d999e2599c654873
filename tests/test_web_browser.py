"""The page in a real browser (headless Chromium driven by selenium): the
paper's conductor example explored end to end, as a person would, and the
layout at 1280 pixels: no element's content runs out of its box (the trolley
model and the care PDDL model, whose plans, pictures and reasons are long),
history, undo and save in view wherever the page is scrolled, and errors
shown where the user acted and scrolled into view.

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

import execution_work
import pytest
from busy_model import MAX_HORIZON, SLOW_QUESTION, busy_model
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
from ethasp.interfaces.web.workspace import Options, Workspace  # noqa: E402

BROWSER = next(
    (
        shutil.which(name)
        for name in ("chromium", "chromium-browser", "google-chrome")
        if shutil.which(name)
    ),
    None,
)
DRIVER = shutil.which("chromedriver")
MISSING = "headless Chromium is not installed (apt-get install chromium chromium-driver)"
if BROWSER is None or DRIVER is None:
    if os.environ.get("ETHASP_REQUIRE_BROWSER") == "1":  # CI installs them (.ci/run)
        raise RuntimeError(MISSING)
    pytest.skip(MISSING, allow_module_level=True)

OUTPUT = Path(os.environ.get("ETHASP_TEST_OUTPUT", ROOT / "tests" / "output"))
README_SCREENSHOT = ROOT / "docs" / "page.png"
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",
    "--hide-scrollbars",
    "--window-size=1400,1000",
]
WAIT = 120  # seconds the page may take for a step (a slow, shared machine)

CONDUCTOR = (
    "The man could refrain from action. This would be permissible under the do-no-harm "
    "principle because this way the death of the five persons is not caused by his action. "
    "Alternatively, the man could pull the lever. Doing so is impermissible under the "
    "do-no-harm principle because this way the death of the one person is caused by his "
    "action."
)
UTILITARIAN_CONTRAST = (
    "Alternatively, the man could pull the lever. Doing so is permissible "
    "under the utilitarianism principle because five saved lives is "
    "better than one saved life."
)


@pytest.fixture(scope="module")
def server():
    workspace = Workspace(
        Model.load([MODELS / "trolley.lp"]), [str(MODELS / "trolley.lp")], "do-no-harm"
    )
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


# Boxes whose content must stay inside them, and what runs out of them: a
# descendant drawn beyond a box's edges (outside a scrolling part of it), or
# text wider than the box (scrollWidth beyond clientWidth).
LAYOUT = """
const boxes = document.querySelectorAll(
  "header, section, .card, .side, .picture, .menu, .notice, #messages p, table.glance, li");
const scrolls = (node, axis) => ["auto", "scroll"].includes(
  getComputedStyle(node)[axis === "x" ? "overflowX" : "overflowY"]);
const name = (node) => node.id ? "#" + node.id : node.tagName.toLowerCase() +
  (node.className && node.className.baseVal === undefined
    ? "." + node.className.split(" ").join(".") : "") +
  " '" + (node.textContent || "").trim().slice(0, 40) + "'";
const problems = [];
for (const box of boxes) {
  if (!box.getClientRects().length) continue;                      // not shown
  if (!scrolls(box, "x") && box.scrollWidth > box.clientWidth + 1) {
    problems.push(`${name(box)}: content ${box.scrollWidth}px wide in ${box.clientWidth}px`);
  }
  const outer = box.getBoundingClientRect();
  for (const child of box.querySelectorAll("*")) {
    if (child.closest("svg") && child.tagName.toLowerCase() !== "svg") continue;
    if (child.closest(".visually-hidden") || !child.getClientRects().length) continue;
    const folded = child.closest("details:not([open])");     // laid out, but not shown
    if (folded && !(folded.querySelector("summary") || folded).contains(child)) continue;
    let scroller = child.parentElement, clipped = false;
    while (scroller && scroller !== box) {
      if (scrolls(scroller, "x") || scrolls(scroller, "y")) { clipped = true; break; }
      scroller = scroller.parentElement;
    }
    if (clipped) continue;
    const rect = child.getBoundingClientRect();
    if (rect.width === 0 && rect.height === 0) continue;
    const sideways = !scrolls(box, "x")
      && (rect.left < outer.left - 1 || rect.right > outer.right + 1);
    const below = !scrolls(box, "y")
      && (rect.top < outer.top - 1 || rect.bottom > outer.bottom + 1);
    if (sideways || below) {
      problems.push(`${name(child)} runs out of ${name(box)} ` +
        `(${Math.round(rect.left)}..${Math.round(rect.right)} x ${Math.round(rect.top)}..` +
        `${Math.round(rect.bottom)} in ${Math.round(outer.left)}..${Math.round(outer.right)} x ` +
        `${Math.round(outer.top)}..${Math.round(outer.bottom)})`);
    }
  }
}
return problems;
"""


def layout_problems(driver) -> list[str]:
    """What runs out of its box on the page as it is (see LAYOUT)."""
    return driver.execute_script(LAYOUT)


def open_everything(driver) -> None:
    """Open every folded section (the model's tables, the reasons), as a
    curious user would, so that the layout check sees them too."""
    driver.execute_script("for (const d of document.querySelectorAll('details')) d.open = true;")


def in_view(driver, element) -> bool:
    """Is the element wholly in the window, below the sticky header?"""
    return driver.execute_script(
        """
        const rect = arguments[0].getBoundingClientRect();
        const header = document.querySelector("header").getBoundingClientRect();
        return rect.height > 0 && rect.top >= header.bottom - 1 &&
               rect.bottom <= window.innerHeight + 1;""",
        element,
    )


def screenshot(driver, name: str) -> Path:
    """The whole page, as wide as the window (then the window as it was)."""
    OUTPUT.mkdir(parents=True, exist_ok=True)
    size = driver.get_window_size()
    driver.execute_script("window.scrollTo(0, 0)")
    height = driver.execute_script("return document.documentElement.scrollHeight")
    driver.set_window_size(size["width"], height + 20)
    path = OUTPUT / name
    driver.save_screenshot(str(path))
    driver.set_window_size(size["width"], size["height"])
    return path


def test_conductor_example_in_the_browser(server, browser):
    driver = browser
    driver.set_window_size(1280, 1000)
    driver.get(server.url)
    # The page starts a dialogue under do-no-harm: the plan refrain.
    wait_for(
        driver,
        lambda d: (
            "do-no-harm" in text(d, "current-summary")
            and d.find_elements(By.CSS_SELECTOR, "#judgements .card")
        ),
        "the first plan",
    )
    assert text(driver, "model-name") == "trolley.lp"
    footer = driver.find_element(By.CSS_SELECTOR, "footer #version").text
    assert footer == f"ethasp {package_version()}"
    glance = text(driver, "model")
    assert "pull the lever" in glance and "the death of the five persons" in glance
    assert "Agent: the man" in glance
    assert [e.text for e in driver.find_elements(By.CSS_SELECTOR, "#current-actions button")] == [
        "refrain"
    ]
    cards = {
        card.get_attribute("data-principle"): card.text
        for card in driver.find_elements(By.CSS_SELECTOR, "#judgements .card")
    }
    assert set(cards) == {"deontology", "do-no-harm", "utilitarianism"}
    assert "permissible" in cards["do-no-harm"] and "impermissible" in cards["utilitarianism"]
    assert (
        "Doing so is permissible because this way the death of the five persons is not "
        "caused by the man's action."
    ) in cards["do-no-harm"]
    assert "not Caused(five_will_die)" in cards["do-no-harm"]

    # Click the action in the plan's picture and ask "why this rather than pull?".
    wait_for(
        driver,
        lambda d: d.find_elements(By.CSS_SELECTOR, "#current-picture g.action"),
        "the plan's picture",
    )
    click(driver, driver.find_element(By.CSS_SELECTOR, "#current-picture g.action"))
    wait_for(driver, lambda d: d.find_element(By.ID, "action-menu").is_displayed(), "the menu")
    Select(driver.find_element(By.ID, "rather-other")).select_by_visible_text("pull")
    click(driver, driver.find_element(By.ID, "why-rather"))
    wait_for(
        driver,
        lambda d: (
            idle(d)
            and d.find_element(By.ID, "answer-panel").is_displayed()
            and CONDUCTOR in text(d, "answer-text")
        ),
        "the conductor's answer",
    )
    assert (
        driver.find_element(By.ID, "question").get_attribute("value")
        == "why refrain rather than pull"
    )
    assert "Principle dropped" in text(driver, "answer-notes")
    highlighted = {
        e.text for e in driver.find_elements(By.CSS_SELECTOR, "#answer-panel .literal.diff")
    }
    assert highlighted == {"not Caused(five_will_die)", "Caused(one_will_die)"}
    assert "Plan asked about" in text(driver, "side-original")
    assert "Contrast plan" in text(driver, "side-contrast") and "impermissible" in text(
        driver, "side-contrast"
    )
    wait_for(
        driver,
        lambda d: "the plans part at step 1" in text(d, "answer-picture"),
        "the contrast picture",
    )
    assert "why refrain rather than pull" in text(driver, "history")
    open_everything(driver)
    assert layout_problems(driver) == []
    screenshot(driver, "page-conductor.png")

    # Switch to utilitarianism, take the question back and ask it again.
    Select(driver.find_element(By.ID, "under")).select_by_visible_text("utilitarianism")
    wait_for(
        driver,
        lambda d: "contrast plans must now satisfy utilitarianism" in text(d, "note"),
        "the switch",
    )
    click(driver, driver.find_element(By.ID, "undo"))
    wait_for(
        driver,
        lambda d: (
            idle(d)
            and "took back" in text(d, "note")
            and not d.find_element(By.ID, "answer-panel").is_displayed()
        ),
        "the undo",
    )
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why refrain rather than pull\n")
    wait_for(
        driver,
        lambda d: idle(d) and UTILITARIAN_CONTRAST in text(d, "answer-text"),
        "the answer under utilitarianism",
    )
    assert "Principle dropped" not in text(driver, "answer-notes")
    assert "permissible" in text(driver, "side-contrast")
    assert "under utilitarianism" in text(driver, "history")

    # A reload finds the same dialogue.
    driver.refresh()
    wait_for(driver, lambda d: UTILITARIAN_CONTRAST in text(d, "answer-text"), "the reloaded state")
    assert (
        Select(driver.find_element(By.ID, "under")).first_selected_option.text == "utilitarianism"
    )
    assert len(driver.find_elements(By.CSS_SELECTOR, "#history li")) == 1
    wait_for(
        driver,
        lambda d: "the plans part at step 1" in text(d, "answer-picture"),
        "the picture after the reload",
    )
    path = screenshot(driver, "page.png")
    assert path.stat().st_size > 10_000
    if os.environ.get("ETHASP_UPDATE_SCREENSHOT") == "1":
        README_SCREENSHOT.parent.mkdir(exist_ok=True)
        shutil.copyfile(path, README_SCREENSHOT)

    # An action that the current plan (pull) does not use: "why not this?".
    click(
        driver, driver.find_element(By.CSS_SELECTOR, '#model-actions button[data-term="refrain"]')
    )
    wait_for(driver, lambda d: d.find_element(By.ID, "action-menu").is_displayed(), "the menu")
    assert "(not in the current plan)" in text(driver, "action-menu")
    assert driver.find_elements(By.ID, "why-not") and not driver.find_elements(By.ID, "why-this")

    # Errors show the command line's one-line messages, in the Ask panel.
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why not jump\n")
    wait_for(driver, lambda d: idle(d) and text(d, "error"), "the error")
    assert text(driver, "error") == (
        "error: question 'why not jump': unknown action jump (nor a state variable)"
    )
    error = driver.find_element(By.ID, "error")
    assert driver.execute_script("return arguments[0].closest('#ask-panel') !== null", error)
    assert in_view(driver, error)
    assert layout_problems(driver) == []
    screenshot(driver, "page-error.png")
    severe = [entry["message"] for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
    assert severe == [], severe


@pytest.fixture
def slow_server(tmp_path):
    """A server whose model has a question that searches long (in a worker
    process, reporting progress), to see a long request on the page."""
    path = busy_model(tmp_path)
    workspace = Workspace(
        Model.load([path]), [str(path)], "deontology", Options(max_horizon=MAX_HORIZON)
    )
    running = Server(workspace, None, 0)
    thread = threading.Thread(target=running.serve_forever, daemon=True)
    thread.start()
    yield running
    running.shutdown()
    thread.join(30)


def test_a_long_search_shows_progress_and_can_be_cancelled(slow_server, browser):
    driver = browser
    driver.get(slow_server.url)
    wait_for(
        driver, lambda d: "deontology" in text(d, "current-summary") and idle(d), "the first plan"
    )
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys(f"{SLOW_QUESTION}\n")
    wait_for(
        driver,
        lambda d: (
            d.find_element(By.ID, "status").is_displayed()
            and "plan search under deontology: horizon" in text(d, "status-progress")
        ),
        "the progress",
    )
    assert text(driver, "status-text") == f"answering '{SLOW_QUESTION}'\u2026"
    assert text(driver, "status-time").endswith(" s")
    assert not driver.find_element(By.ID, "ask").is_enabled()
    screenshot(driver, "page-running.png")
    process = slow_server.app.extensions["ethasp"].workers.pids()
    click(driver, driver.find_element(By.ID, "cancel"))
    wait_for(driver, lambda d: idle(d) and "cancelled" in text(d, "note"), "the cancellation")
    assert text(driver, "note") == "cancelled: the dialogue is unchanged"
    assert driver.find_elements(By.CSS_SELECTOR, "#history li") == []
    assert not driver.find_element(By.ID, "answer-panel").is_displayed()
    assert driver.find_element(By.ID, "ask").is_enabled()
    # The search's worker process was ended, and another took its place.
    assert len(set(process) - set(slow_server.app.extensions["ethasp"].workers.pids())) == 1


@pytest.fixture
def limited_server():
    """A server whose moves have a time limit of a few seconds."""
    workspace = Workspace(
        Model.load([MODELS / "trolley.lp"]),
        [str(MODELS / "trolley.lp")],
        "do-no-harm",
        Options(time_limit=LIMITED),
    )
    running = Server(workspace, None, 0)
    thread = threading.Thread(target=running.serve_forever, daemon=True)
    thread.start()
    yield running
    running.shutdown()
    thread.join(30)


LIMITED = 8.0  # seconds: long enough for the page to load and follow the move


def test_a_move_ended_at_the_time_limit_says_so_on_the_page(limited_server, browser):
    """A move that cannot stop (a grounding without end) is ended with its
    worker at the time limit; the page says so and the dialogue is as it was."""
    driver = browser
    driver.execute_script("localStorage.clear()")
    driver.get(limited_server.url)
    wait_for(driver, lambda d: "do-no-harm" in text(d, "current-summary") and idle(d), "the plan")
    workspace = limited_server.app.extensions["ethasp"]
    key = driver.execute_script(
        "return JSON.parse(localStorage.getItem(Object.keys(localStorage)[0])).session"
    )
    session = workspace.session(key)
    workspace.submit(session, "ask", "grounding without end", execution_work.ground_forever)
    driver.refresh()  # the page follows the session's running move
    wait_for(
        driver,
        lambda d: "grounding without end" in text(d, "status-text"),
        "the running move",
    )
    wait_for(driver, lambda d: idle(d) and text(d, "error"), "the end of the move")
    assert text(driver, "error") == (
        f"error: the time limit of {LIMITED:g} s was reached: the work was ended and the "
        "dialogue is unchanged"
    )
    assert driver.find_elements(By.CSS_SELECTOR, "#history li") == []
    assert driver.find_element(By.ID, "ask").is_enabled()


CARE = [
    str(MODELS / "pddl" / name)
    for name in ("care-domain.pddl", "care-problem.pddl", "care-utility.lp")
]


@pytest.fixture(scope="module")
def care_server():
    workspace = Workspace(Model.load(CARE), CARE, "do-no-harm")
    running = Server(workspace, None, 0)
    thread = threading.Thread(target=running.serve_forever, daemon=True)
    thread.start()
    yield running
    running.shutdown()
    thread.join(30)


def test_the_layout_of_a_long_pddl_task(care_server, browser):
    """The care robot: 122 variables, a plan of 10 steps, a GEq reason that
    compares two states of about 120 facts, a contrast plan of 13 steps."""
    driver = browser
    driver.set_window_size(1280, 900)
    driver.get(care_server.url)
    wait_for(
        driver,
        lambda d: (
            idle(d)
            and len(d.find_elements(By.CSS_SELECTOR, "#judgements .card")) == 3
            and d.find_elements(By.CSS_SELECTOR, "#current-picture svg")
        ),
        "the first plan",
    )
    assert "10 steps: the first plan, judged under do-no-harm" in text(driver, "current-summary")
    # Long sections are folded: the model's 32 actions and 122 variables.
    assert driver.execute_script(
        "return [...document.querySelectorAll('#model details')].map(d => d.open)"
    ) == [False, False]
    # The plan's picture fits its box; its boxes name facts whole (wrapped), with tooltips.
    picture = driver.find_element(By.ID, "current-picture")
    assert driver.execute_script(
        """
        const svg = arguments[0].querySelector("svg");
        return svg.getBoundingClientRect().width <= arguments[0].clientWidth + 1 &&
               svg.getBoundingClientRect().width < svg.viewBox.baseVal.width;""",
        picture,
    )
    names = [
        e.get_attribute("textContent")
        for e in driver.find_elements(By.CSS_SELECTOR, "#current-picture text")
    ]
    assert not any("\u2026" in name and "(not (robot-at" in name for name in names)
    # The long GEq reason is shortened, and can be shown whole.
    card = driver.find_element(
        By.CSS_SELECTOR, '#judgements .card[data-principle="utilitarianism"]'
    )
    chosen = card.find_element(By.CSS_SELECTOR, ".literal")
    assert chosen.text.startswith("not GEq((") and len(chosen.text) < 200
    assert layout_problems(driver) == []
    click(driver, chosen.find_element(By.CSS_SELECTOR, "button.more"))
    assert len(chosen.text) > 2000
    open_everything(driver)
    assert layout_problems(driver) == []
    click(driver, chosen.find_element(By.CSS_SELECTOR, "button.more"))
    assert len(chosen.text) < 200

    # History, undo and save stay in view at the bottom of the page.
    driver.execute_script("window.scrollTo(0, document.documentElement.scrollHeight)")
    for element_id in ("history-panel", "undo", "save"):
        assert in_view(driver, driver.find_element(By.ID, element_id)), element_id

    # A question with a long contrast plan; its picture fits, or is shown at its size.
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why not (pick-up pills-bob kitchen)\n")
    wait_for(
        driver,
        lambda d: (
            idle(d)
            and d.find_element(By.ID, "answer-panel").is_displayed()
            and d.find_elements(By.CSS_SELECTOR, "#answer-picture svg")
        ),
        "the answer",
    )
    assert "(pick-up pills-bob kitchen)" in text(driver, "side-contrast")
    open_everything(driver)
    assert layout_problems(driver) == []
    zoom = driver.find_element(By.CSS_SELECTOR, 'button.zoom[data-picture="answer-picture"]')
    click(driver, zoom)
    assert zoom.text == "Fit to width"
    assert driver.execute_script(
        "const p = arguments[0]; return p.scrollWidth > p.clientWidth + 100",
        driver.find_element(By.ID, "answer-picture"),
    )
    assert layout_problems(driver) == []
    click(driver, zoom)
    driver.execute_script("window.scrollTo(0, document.documentElement.scrollHeight)")
    for element_id in ("undo", "save"):
        assert in_view(driver, driver.find_element(By.ID, element_id)), element_id
    screenshot(driver, "page-care.png")

    # An error where the user asked, scrolled into view although the page was
    # at its top (a question chosen from the plan at the top of the page).
    driver.execute_script("window.scrollTo(0, 0)")
    driver.execute_script("""
        document.getElementById("question").value = "why not (fly kitchen)";
        document.getElementById("ask-form").requestSubmit();""")
    wait_for(driver, lambda d: idle(d) and text(d, "error"), "the error")
    error = driver.find_element(By.ID, "error")
    assert error.text == (
        "error: question 'why not (fly kitchen)': unknown action (fly kitchen) "
        "(nor a state variable)"
    )
    assert driver.execute_script("return arguments[0].closest('#ask-panel') !== null", error)
    wait_for(driver, lambda d: in_view(d, error), "the error in view")
    assert layout_problems(driver) == []
    # Undo's messages appear in the History panel.
    click(driver, driver.find_element(By.ID, "undo"))
    wait_for(driver, lambda d: idle(d) and "took back" in text(d, "note"), "the undo")
    note = driver.find_element(By.ID, "note")
    assert driver.execute_script("return arguments[0].closest('#history-panel') !== null", note)
    assert in_view(driver, note)


def test_steps_and_a_question_no_plan_can_meet_in_the_browser(server, browser):
    driver = browser
    driver.get(server.url)
    driver.execute_script("localStorage.clear()")
    driver.refresh()
    wait_for(
        driver,
        lambda d: idle(d) and "the first plan" in text(d, "current-summary"),
        "a new dialogue",
    )
    # The plan step by step, and "why step 1" typed.
    click(driver, driver.find_element(By.ID, "explain-plan"))
    wait_for(
        driver,
        lambda d: (
            d.find_element(By.ID, "explain-panel").is_displayed()
            and "Step 1, refrain from action" in text(d, "explain-lines")
        ),
        "the steps",
    )
    assert "Every step is needed" in text(driver, "explain-removable")
    wait_for(
        driver,
        lambda d: d.find_elements(By.CSS_SELECTOR, "#explain-picture svg"),
        "the picture with arrows",
    )
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why step 1\n")
    wait_for(
        driver,
        lambda d: text(d, "explain-step").startswith("Step 1, refrain from action"),
        "why step 1",
    )
    # The principle dropped on a proof: the summary says how the plan was made.
    box.clear()
    box.send_keys("why refrain rather than pull\n")
    wait_for(driver, lambda d: idle(d) and CONDUCTOR in text(d, "answer-text"), "the answer")
    assert "made without do-no-harm" in text(driver, "current-summary")
    assert not driver.find_element(By.ID, "explain-panel").is_displayed()  # a new plan
    # A question no plan can meet: say so, and offer to drop it.
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why pull rather than refrain\n")
    wait_for(
        driver,
        lambda d: idle(d) and d.find_elements(By.ID, "drop-question"),
        "the conflict and its button",
    )
    assert "No contrast plan (proven)" in text(driver, "answer-notes")
    assert "question 2 has no contrast plan" in text(driver, "current-summary")
    click(driver, driver.find_element(By.ID, "drop-question"))
    wait_for(
        driver,
        lambda d: idle(d) and "dropped: why pull rather than refrain" in text(d, "note"),
        "the question dropped",
    )
    assert len(driver.find_elements(By.CSS_SELECTOR, "#history li")) == 1
    severe = [entry["message"] for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
    assert severe == [], severe
