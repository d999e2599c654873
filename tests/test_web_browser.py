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

import contextlib
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


@contextlib.contextmanager
def served(workspace: Workspace):
    """A server of the workspace on a free port, in a thread, for the test."""
    running = Server(workspace, None, 0)
    thread = threading.Thread(target=running.serve_forever, daemon=True)
    thread.start()
    try:
        yield running
    finally:
        running.shutdown()
        thread.join(30)


def trolley_workspace() -> Workspace:
    return Workspace(
        Model.load([MODELS / "trolley.lp"]), [str(MODELS / "trolley.lp")], "do-no-harm"
    )


@pytest.fixture(scope="module")
def server():
    with served(trolley_workspace()) as running:
        yield running


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
    # A better reachable state makes refrain impermissible under utilitarianism:
    # the better plan is named, and drawn as a contrast to the current plan.
    assert "The better plan: pull" in cards["utilitarianism"]
    wait_for(
        driver,
        lambda d: d.find_elements(By.CSS_SELECTOR, "#better-plans .picture svg"),
        "the better plan's picture",
    )
    better = driver.find_element(By.CSS_SELECTOR, '#better-plans [data-principle="utilitarianism"]')
    assert "The better plan under utilitarianism" in better.text
    assert "the better plan: pull" in better.find_element(By.CSS_SELECTOR, ".picture").text

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
    with served(Workspace(Model.load(CARE), CARE, "do-no-harm")) as running:
        yield running


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
    # The plan's picture keeps its size (its text readable) and scrolls sideways
    # in its box; its boxes name facts whole (wrapped), with tooltips.
    picture = driver.find_element(By.ID, "current-picture")
    assert driver.execute_script(
        """
        const svg = arguments[0].querySelector("svg");
        return Math.abs(svg.getBoundingClientRect().width - svg.viewBox.baseVal.width) < 1 &&
               arguments[0].scrollWidth > arguments[0].clientWidth + 100;""",
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

    # A question with a long contrast plan; its picture is shown at its size, or fits.
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
    assert zoom.text == "Fit to width"
    assert driver.execute_script(
        "const p = arguments[0]; return p.scrollWidth > p.clientWidth + 100",
        driver.find_element(By.ID, "answer-picture"),
    )
    click(driver, zoom)
    assert zoom.text == "Actual size"
    assert driver.execute_script(
        "const p = arguments[0]; return p.scrollWidth <= p.clientWidth + 1",
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
    reloaded(driver, server.url)
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


def test_the_batch_report_folds_its_lists_and_sorts_its_tables(browser, tmp_path):
    """The report of a batch: the lists of the cases on which two principles
    disagree are folded (a link from the table of agreement opens its list),
    and a table sorts by the column whose heading is clicked."""
    import json

    from ethasp.batch.report import write_report

    principles = [f"p{index}" for index in range(6)]
    lines = [
        {
            "case": f"case-{number:02d}",
            "principle": principle,
            "permissible": (number * (index + 1)) % 3 == 0,
            "status": "proven",
            "seconds": round(0.5 + (number * 7 % 11) / 10, 3),
            "hash": f"{number}-{principle}",
        }
        for number in range(30)
        for index, principle in enumerate(principles)
    ]
    results = tmp_path / "results.jsonl"
    results.write_text("".join(json.dumps(line) + "\n" for line in lines))
    page = write_report(results, tmp_path / "report.html")
    browser.get(page.as_uri())
    lists = browser.find_elements(By.CSS_SELECTOR, "details")
    assert len(lists) >= 5 and not any(item.get_attribute("open") for item in lists)
    assert not any(item.is_displayed() for item in browser.find_elements(By.CSS_SELECTOR, "li"))
    link = browser.find_element(By.CSS_SELECTOR, ".agree a")
    target = link.get_attribute("href").split("#")[1]
    click(browser, link)
    opened = browser.find_element(By.ID, target)
    wait_for(browser, lambda d: opened.get_attribute("open") is not None, "the list opened")
    assert opened.find_element(By.TAG_NAME, "li").is_displayed()
    assert browser.find_element(By.ID, "disagreements").get_attribute("open") is not None

    cases = browser.find_element(By.CSS_SELECTOR, "#cases + p + table")

    def times() -> list[float]:
        rows = cases.find_elements(By.CSS_SELECTOR, "tbody tr")
        return [
            float(row.find_elements(By.TAG_NAME, "td")[-1].get_attribute("data-sort"))
            for row in rows
        ]

    assert times() != sorted(times())
    heading = cases.find_elements(By.CSS_SELECTOR, "thead th")[-1]
    click(browser, heading)
    assert times() == sorted(times()) and heading.get_attribute("aria-sort") == "ascending"
    click(browser, heading)
    assert times() == sorted(times(), reverse=True)
    click(browser, cases.find_elements(By.CSS_SELECTOR, "thead th")[0])
    numbers = [row.get_attribute("id") for row in cases.find_elements(By.CSS_SELECTOR, "tbody tr")]
    assert numbers == [f"case-{number}" for number in range(1, 31)]


# -- long plans, suggestions, buttons, conflicts ---------------------------------------------

LONG = 46


def chain(steps: int) -> str:
    """A model whose only plan walks a chain of ``steps`` actions; step 7 is
    bad, and an action the plan never uses is good."""
    lines = [f"variable(v({i})). action(go({i}))." for i in range(1, steps + 1)]
    lines += ["variable(v(0)). init(v(0)). action(rest). pre(rest, v(0), false)."]
    lines += [
        f"pre(go({i}), v({i - 1}), true). eff(go({i}), v({i}), true)." for i in range(1, steps + 1)
    ]
    lines += [f"goal(v({steps}), true). utility(go(7), -1). utility(rest, 1)."]
    return "\n".join(lines)


@pytest.fixture(scope="module")
def long_server():
    workspace = Workspace(Model.from_string(chain(LONG)), ["chain.lp"], "do-no-harm")
    with served(workspace) as running:
        yield running


def reloaded(driver, url: str) -> None:
    """The page, loaded again with nothing kept from earlier tests (once the
    first load's dialogue has started, so that one session starts at a time)."""
    driver.get(url)
    wait_for(driver, lambda d: idle(d) and text(d, "model-name"), "the page loaded")
    driver.execute_script("localStorage.clear()")
    driver.refresh()


def fresh(driver, url: str) -> None:
    """The page with nothing kept from earlier tests, and its first plan shown."""
    reloaded(driver, url)
    wait_for(
        driver,
        lambda d: (
            idle(d)
            and "the first plan" in text(d, "current-summary")
            and d.find_elements(By.CSS_SELECTOR, "#current-picture svg")
        ),
        "the first plan",
    )


def test_a_long_plan_keeps_its_picture_readable_and_shows_the_step_under_the_pointer(
    long_server, browser
):
    driver = browser
    driver.set_window_size(1280, 900)
    fresh(driver, long_server.url)
    assert text(driver, "current-summary").startswith(f"{LONG} steps: the first plan")
    picture = driver.find_element(By.ID, "current-picture")
    # The picture is drawn at its own size: its step labels are as large as
    # drawn (11 px), and the box scrolls sideways through the 46 steps.
    sizes = driver.execute_script(
        """
        const box = arguments[0], svg = box.querySelector("svg");
        const label = [...svg.querySelectorAll("text")].find((t) => t.textContent === "step 1");
        return [svg.getBoundingClientRect().width / svg.viewBox.baseVal.width,
                label.getBoundingClientRect().height, box.scrollWidth, box.clientWidth];""",
        picture,
    )
    scale, height, wide, shown = sizes
    assert scale > 0.99 and height >= 10, sizes
    assert wide > 10 * shown, sizes
    # The pointer over a step's column highlights that step, in the picture
    # and in the plan above it; scrolled to step 40, the same.
    from selenium.webdriver.common.action_chains import ActionChains

    for step in (3, 40):
        band = driver.find_element(
            By.CSS_SELECTOR, f'#current-picture rect.column[data-step="{step}"]'
        )
        driver.execute_script(
            "const box = arguments[0], band = arguments[1];"
            "box.scrollLeft = band.getBoundingClientRect().left - box.getBoundingClientRect().left"
            " + box.scrollLeft - 100;",
            picture,
            band,
        )
        driver.execute_script("arguments[0].scrollIntoView({block: 'center'})", picture)
        ActionChains(driver).move_to_element(band).perform()
        wait_for(
            driver,
            lambda d, step=step: d.find_elements(
                By.CSS_SELECTOR, f'#current-picture rect.column.hover[data-step="{step}"]'
            ),
            f"step {step} highlighted",
        )
        assert len(driver.find_elements(By.CSS_SELECTOR, "#current-picture rect.column.hover")) == 1
        item = driver.find_element(By.CSS_SELECTOR, "#current-actions li.hover")
        assert item.get_attribute("data-step") == str(step)
    # Fitted to the width, the whole plan shows at once.
    zoom = driver.find_element(By.CSS_SELECTOR, 'button.zoom[data-picture="current-picture"]')
    click(driver, zoom)
    assert driver.execute_script(
        "return arguments[0].scrollWidth <= arguments[0].clientWidth + 1", picture
    )
    click(driver, zoom)
    assert layout_problems(driver) == []


def test_suggestions_and_buttons_come_from_the_plan(long_server, server, browser):
    driver = browser
    fresh(driver, long_server.url)
    # The question field suggests a question about this model's plan: its bad
    # step, rather than the action it leaves out.
    assert driver.find_element(By.ID, "question").get_attribute("placeholder") == (
        "why go(7) rather than rest"
    )
    assert text(driver, "shorter") == f"Why not in {LONG - 1} steps?"
    # A step's menu offers "why not this at step T" for a step whose action is
    # another one, and refuses the step where it already is.
    click(driver, driver.find_element(By.CSS_SELECTOR, '#current-actions button[data-step="1"]'))
    step = driver.find_element(By.ID, "not-at-step")
    assert step.get_attribute("value") == "2"
    assert driver.find_element(By.ID, "why-not-at").is_enabled()
    step.clear()
    step.send_keys("1")
    assert not driver.find_element(By.ID, "why-not-at").is_enabled()
    step.clear()
    step.send_keys("5")
    assert driver.find_element(By.ID, "why-not-at").is_enabled()

    # The trolley: a plan of one step offers no question about 0 steps, and
    # the plan's words appear once, above the judgements.
    fresh(driver, server.url)
    assert not driver.find_element(By.ID, "shorter").is_displayed()
    assert driver.find_element(By.ID, "question").get_attribute("placeholder") == (
        "why refrain rather than pull"
    )
    assert text(driver, "current-words") == "The man can refrain from action."
    cards = driver.find_elements(By.CSS_SELECTOR, "#judgements .card .explanation")
    assert len(cards) == 3
    for card in cards:
        assert "can refrain" not in card.text and card.text.startswith("Doing so is"), card.text
    assert driver.page_source.count("The man can refrain from action.") == 1


@pytest.fixture
def slow_start_server(monkeypatch):
    """A server whose dialogues take two seconds longer to start (the first
    plan is installed two seconds after its worker made it), to see the page
    loading."""
    from ethasp.interfaces.web.workspace import Session

    install = Session.install

    def slow_install(session, shown):
        if session.job is not None and session.job.kind == "start":
            threading.Event().wait(2.0)
        return install(session, shown)

    monkeypatch.setattr(Session, "install", slow_install)
    with served(trolley_workspace()) as running:
        yield running


def test_while_the_page_loads_no_empty_button_and_the_served_principle(slow_start_server, browser):
    driver = browser
    reloaded(driver, slow_start_server.url)
    wait_for(
        driver,
        lambda d: "trolley" in text(d, "model-name") and not idle(d),
        "the model, while the first plan is made",
    )
    empty = driver.execute_script(
        """return [...document.querySelectorAll("button")]
             .filter((b) => b.getClientRects().length && !b.textContent.trim())
             .map((b) => b.id || b.outerHTML.slice(0, 60));"""
    )
    assert empty == []
    under = Select(driver.find_element(By.ID, "under"))
    assert under.first_selected_option.text == "do-no-harm"
    wait_for(
        driver, lambda d: idle(d) and "the first plan" in text(d, "current-summary"), "the plan"
    )
    assert under.first_selected_option.text == "do-no-harm"
    assert driver.find_element(By.ID, "under").is_enabled()


@pytest.fixture(scope="module")
def rescue_server():
    workspace = Workspace(
        Model.load([MODELS / "rescue.lp"]), [str(MODELS / "rescue.lp")], "deontology"
    )
    with served(workspace) as running:
        yield running


def test_after_a_conflict_the_page_offers_to_drop_it_instead_of_stacking(rescue_server, browser):
    driver = browser
    fresh(driver, rescue_server.url)
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why take_key before unlock_door\n")
    wait_for(driver, lambda d: idle(d) and d.find_elements(By.ID, "drop-question"), "the conflict")
    assert len(driver.find_elements(By.CSS_SELECTOR, "#history li")) == 1
    # A further question would have no contrast plan: the page offers to drop
    # the conflicting question first, and asks nothing yet.
    box = driver.find_element(By.ID, "question")
    box.clear()
    box.send_keys("why not in 4 steps\n")
    offer = driver.find_element(By.ID, "drop-offer")
    assert offer.is_displayed() and "why take_key before unlock_door" in offer.text
    assert len(driver.find_elements(By.CSS_SELECTOR, "#history li")) == 1
    click(driver, driver.find_element(By.ID, "drop-and-ask"))
    wait_for(
        driver,
        lambda d: idle(d) and "why not in 4 steps" in text(d, "answer-question"),
        "the question asked after the drop",
    )
    entries = driver.find_elements(By.CSS_SELECTOR, "#history li")
    assert len(entries) == 1 and "why not in 4 steps" in entries[0].text
    assert "contrast: " in entries[0].text  # a contrast plan, not another "no contrast plan"
    assert not driver.find_elements(By.ID, "drop-offer")
