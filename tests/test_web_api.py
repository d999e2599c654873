"""The page's HTTP API (ethasp serve), through Flask's test client: the
conductor example, every question form, undo, switching principle, save and
load, a state that survives a reload or a restart, cancelling, errors with
the command line's messages, length limits and the guards."""

import json
import os
import re
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import execution_work
import pytest
from busy_model import MAX_HORIZON, SLOW_QUESTION, busy_model
from conftest import MODELS, ROOT
from served import ended

from ethasp import InputError, Model, Plan
from ethasp.execution.limits import GB, tree_resident
from ethasp.interfaces.web import workers as workers_module
from ethasp.interfaces.web.app import MAX_BODY, create_app
from ethasp.interfaces.web.server import Server, is_loopback
from ethasp.interfaces.web.workspace import Limits, Options, Workspace
from ethasp.questions.dialogue import Dialogue
from ethasp.questions.question import Question

TROLLEY = str(MODELS / "trolley.lp")
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
def trolley():
    return Model.load([TROLLEY])


OPEN: list[Workspace] = []  # workspaces of the test running, closed after it


@pytest.fixture(autouse=True)
def close_workspaces():
    yield
    while OPEN:
        OPEN.pop().close()


def workspace_of(model, files, principle="do-no-harm", options=None, limits=None):
    """A workspace, its worker processes ended after the test."""
    workspace = Workspace(model, files, principle, options or Options(), limits or Limits())
    OPEN.append(workspace)
    return workspace


def make_client(model, principle="do-no-harm", limits=None, loopback=True):
    workspace = workspace_of(model, [TROLLEY], principle, limits=limits)
    return create_app(workspace, loopback=loopback).test_client()


@pytest.fixture
def client(trolley):
    return make_client(trolley)


def finish(client, reply):
    """Follow a move's job until it ends (bounded); return the job."""
    assert reply.status_code == 202, reply.json
    key = reply.json["session"]
    for _ in range(600):
        job = client.get(f"/api/sessions/{key}/job").json["job"]
        if job["state"] != "running":
            return job
        time.sleep(0.05)
    raise AssertionError("the job did not end")


def start(client, principle=None, plan=None):
    body = {} if principle is None else {"principle": principle}
    if plan is not None:
        body["plan"] = plan
    reply = client.post("/api/sessions", json=body)
    job = finish(client, reply)
    assert job["state"] == "done", job
    return reply.json["session"]


def state(client, key):
    reply = client.get(f"/api/sessions/{key}")
    assert reply.status_code == 200, reply.json
    return reply.json


def ask(client, key, question):
    return finish(client, client.post(f"/api/sessions/{key}/ask", json={"question": question}))


# -- the page and the model ------------------------------------------------------------------------


def test_page_and_its_assets_are_bundled(client):
    page = client.get("/")
    assert page.status_code == 200 and b"<title>ethasp</title>" in page.data
    assert "default-src 'self'" in page.headers["Content-Security-Policy"]
    for asset in re.findall(rb'(?:src|href)="(/static/[^"]+)"', page.data):
        reply = client.get(asset.decode())
        assert reply.status_code == 200, asset
        text = reply.data.decode().replace("http://www.w3.org/2000/svg", "")
        assert "http://" not in text and "https://" not in text and "@import" not in text
    assert b'src="http' not in page.data and b'href="http' not in page.data


def test_model_at_a_glance(client):
    data = client.get("/api/model").json
    assert data["name"] == "trolley.lp" and data["principle"] == "do-no-harm"
    assert {"deontology", "do-no-harm", "utilitarianism"} <= set(data["principles"])
    assert [a["term"] for a in data["model"]["actions"]] == ["pull", "refrain"]
    one = next(v for v in data["model"]["variables"] if v["term"] == "one_will_die")
    assert one["true"] == {
        "literal": "one_will_die",
        "shown": "one_will_die",
        "utility": -1,
        "moral": "bad",
        "label": "the death of the one person",
    }
    assert data["limits"]["question"] == Limits().question
    assert re.fullmatch(r"[0-9a-f]{16}", data["key"])


# -- the conductor example -------------------------------------------------------------------------


def test_conductor_example_end_to_end(client):
    key = start(client)
    first = state(client, key)
    assert first["current"]["plan"] == ["refrain"] and first["steps"] == []
    verdicts = {j["principle"]: j["permissible"] for j in first["current"]["judgements"]}
    assert verdicts == {"deontology": True, "do-no-harm": True, "utilitarianism": False}
    harm = next(j for j in first["current"]["judgements"] if j["principle"] == "do-no-harm")
    assert harm["chosen_reason"] == ["not Caused(five_will_die)"]
    assert harm["explanation"].startswith("The man can refrain from action.")
    assert harm["necessary_reasons"] and harm["sufficient_reasons"]

    job = ask(client, key, "why refrain rather than pull")
    assert job["state"] == "done" and job["note"] == "answered: why refrain rather than pull"
    after = state(client, key)
    step = after["steps"][0]
    answer = step["answer"]
    assert answer["explanation"] == CONDUCTOR
    assert answer["principle_dropped"] is True and answer["conflict"] == []
    assert answer["reason_difference"] == {
        "original_only": ["not Caused(five_will_die)"],
        "contrast_only": ["Caused(one_will_die)"],
    }
    assert answer["contrast"]["shown"] == [{"term": "pull", "shown": "pull"}]
    assert step["own_constraints"] == ["unused(refrain)", "used(pull)"]
    assert after["current"]["plan"] == ["pull"]

    picture = client.get(f"/api/sessions/{key}/steps/1.svg")
    assert picture.mimetype == "image/svg+xml"
    assert b"the plans part at step 1" in picture.data and CONDUCTOR[:30].encode() in picture.data
    bare = client.get(f"/api/sessions/{key}/steps/1.svg?words=0")
    assert CONDUCTOR[:30].encode() not in bare.data
    assert client.get(f"/api/sessions/{key}/steps/2.svg").status_code == 404
    current = client.get(f"/api/sessions/{key}/current.svg")
    assert b"current plan: pull" in current.data

    switched = client.post(f"/api/sessions/{key}/principle", json={"principle": "utilitarianism"})
    assert switched.status_code == 200 and switched.json["under"] == "utilitarianism"
    job = finish(client, client.post(f"/api/sessions/{key}/undo", json={}))
    assert job["note"] == "took back: why refrain rather than pull"
    assert state(client, key)["current"]["plan"] == ["refrain"]
    job = ask(client, key, "why refrain rather than pull")
    answer = state(client, key)["steps"][0]["answer"]
    assert answer["principle_dropped"] is False and UTILITARIAN_CONTRAST in answer["explanation"]


@pytest.mark.parametrize(
    "plan,question,contrast",
    [
        ("pull", "why pull", ["refrain"]),  # clicked "why this?"
        ("pull", "why not refrain", ["refrain"]),  # "why not this?"
        ("pull", "why pull rather than refrain", ["refrain"]),  # "why this rather than ...?"
        # "why this before ...?": refrain, and no pull before it
        ("pull refrain", "why pull before refrain", ["refrain"]),
        ("pull", "Why not refrain?", ["refrain"]),  # typed, any case, a final ?
    ],
)
def test_every_question_form(client, plan, question, contrast):
    key = start(client, "deontology", plan)
    assert state(client, key)["current"]["plan"] == plan.split()
    job = ask(client, key, question)
    assert job["state"] == "done", job
    answer = state(client, key)["steps"][0]["answer"]
    assert answer["contrast"]["plan"] == contrast
    assert answer["questions"] == [str(Question.parse(question))]


def test_a_minimal_conflict_is_shown(client):
    key = start(client)
    ask(client, key, "why refrain rather than pull")
    ask(client, key, "why pull rather than refrain")
    answer = state(client, key)["steps"][1]["answer"]
    assert answer["contrast"] is None and answer["status"] == "none"
    assert set(answer["conflict"]) in (
        {"used(pull)", "unused(pull)"},
        {"unused(refrain)", "used(refrain)"},
    )
    assert b"none (none:" in client.get(f"/api/sessions/{key}/steps/2.svg").data


def test_a_dropped_principle_shows_the_conflicts_and_the_repaired_plan(tmp_path):
    alarm = tmp_path / "alarm.lp"
    alarm.write_text(
        Path(TROLLEY).read_text()
        + "creative(alarm,2). eff(alarm,done,true). eff(alarm,five_will_die,false).\n"
    )
    model = Model.load([alarm])
    workspace = Workspace(model, [str(alarm)], "do-no-harm", Options(), Limits())
    client = create_app(workspace, loopback=True).test_client()
    key = start(client, plan="refrain")
    ask(client, key, "why five_will_die")
    answer = state(client, key)["steps"][0]["answer"]
    assert answer["principle_dropped"]
    assert answer["conflicts"] == [["ends(five_will_die,false)"]]
    assert "The cheapest change" in answer["conflicts_explanation"]
    assert answer["repair"]["repairs"][0]["plan"] == ["alarm"]
    assert answer["repair"]["shown"] == [{"term": "alarm", "shown": "alarm"}]
    picture = client.get(f"/api/sessions/{key}/steps/1/repair.svg")
    assert picture.status_code == 200 and picture.mimetype == "image/svg+xml"
    assert b"cheapest repair (cost 2)" in picture.data and b"repaired plan: alarm" in picture.data
    # an answer without a repair has no repaired plan to draw
    ask(client, key, "why not pull")
    assert client.get(f"/api/sessions/{key}/steps/2/repair.svg").status_code == 404


# -- errors: the command line's one-line messages --------------------------------------------------


def message_of(call):
    with pytest.raises(InputError) as error:
        call()
    return str(error.value)


def test_errors_have_the_command_line_messages(client, trolley):
    key = start(client)
    reply = client.post(f"/api/sessions/{key}/ask", json={"question": "how pull"})
    assert reply.status_code == 400
    assert reply.json == {"error": message_of(lambda: Question.parse("how pull"))}
    job = ask(client, key, "why not jump")
    assert job["state"] == "failed" and job["error"] == (
        "question 'why not jump': unknown action jump (nor a state variable)"
    )
    job = ask(client, key, "why not refrain")
    assert job["state"] == "failed" and "already meets its contrast" in job["error"]
    reply = client.post(f"/api/sessions/{key}/principle", json={"principle": "kindness"})
    assert reply.status_code == 400
    assert reply.json["error"] == message_of(lambda: Dialogue.start(trolley, "kindness"))
    reply = client.post(f"/api/sessions/{key}/undo", json={})
    assert (
        reply.status_code == 400 and reply.json["error"] == "nothing to undo: no question asked yet"
    )
    assert state(client, key)["steps"] == []  # failed moves change nothing

    reply = client.post("/api/sessions", json={"plan": "jump"})
    job = finish(client, reply)
    assert job["state"] == "failed" and job["error"] == "plan: unknown action jump at step 1"
    assert state(client, reply.json["session"])["dialogue"] is None
    reply = client.post("/api/sessions", json={"principle": "kindness"})
    assert reply.status_code == 400 and reply.json["error"].startswith("unknown principle")

    assert client.get("/api/sessions/0123").status_code == 404
    assert "unknown session" in client.get("/api/sessions/0123").json["error"]
    reply = client.post(f"/api/sessions/{key}/ask", data="why pull")
    assert reply.status_code == 415 and "JSON" in reply.json["error"]
    reply = client.post(f"/api/sessions/{key}/ask", json=["why pull"])
    assert reply.status_code == 400 and reply.json["error"] == "the request must be a JSON object"
    reply = client.post(f"/api/sessions/{key}/ask", json={"question": 3})
    assert reply.status_code == 400 and reply.json["error"] == "question: expected text"
    assert client.get("/api/nothing").status_code == 404


def test_length_limits(trolley):
    client = make_client(trolley, limits=Limits(questions=1))
    key = start(client)
    long = "why " + "pull " * 200
    reply = client.post(f"/api/sessions/{key}/ask", json={"question": long})
    assert reply.status_code == 400 and "question: too long" in reply.json["error"]
    reply = client.post("/api/sessions", json={"plan": "pull " * 3000})
    assert reply.status_code == 400 and "plan: too long" in reply.json["error"]
    reply = client.post(f"/api/sessions/{key}/principle", json={"principle": "x" * 1000})
    assert reply.status_code == 400 and "principle: too long" in reply.json["error"]
    reply = client.post(
        f"/api/sessions/{key}/load", json={"dialogue": "x" * (MAX_BODY + 10), "name": "big.json"}
    )
    assert reply.status_code == 413 and "too large" in reply.json["error"]
    assert ask(client, key, "why refrain rather than pull")["state"] == "done"
    reply = client.post(f"/api/sessions/{key}/ask", json={"question": "why pull"})
    assert reply.status_code == 400 and "at most 1 questions" in reply.json["error"]


# -- save, load, reload ----------------------------------------------------------------------------


def test_save_and_load_the_files_of_ethasp_dialogue(client, trolley, tmp_path):
    key = start(client)
    ask(client, key, "why refrain rather than pull")
    client.post(f"/api/sessions/{key}/principle", json={"principle": "utilitarianism"})
    saved = client.get(f"/api/sessions/{key}/dialogue.json")
    assert "attachment" in saved.headers["Content-Disposition"]
    data = saved.json
    assert data["format"] == "ethasp-dialogue" and data["under"] == "utilitarianism"
    # The same file as ethasp dialogue writes: Dialogue.load reads it.
    path = tmp_path / "saved.json"
    path.write_text(json.dumps(data))
    again = Dialogue.load(path, trolley)
    assert again.steps[0].answer.explanation == CONDUCTOR and again.under == "utilitarianism"

    other = start(client)
    job = finish(
        client,
        client.post(
            f"/api/sessions/{other}/load",
            json={"dialogue": saved.data.decode(), "name": "saved.json"},
        ),
    )
    assert job["state"] == "done" and job["note"] == "loaded saved.json (1 questions)"
    loaded = state(client, other)
    assert loaded["under"] == "utilitarianism"
    assert loaded["steps"][0]["answer"]["explanation"] == CONDUCTOR

    # A file written by ethasp dialogue itself (Dialogue.save) loads too.
    written = Dialogue.start(trolley, "deontology", Plan.parse("pull"), model_files=[TROLLEY])
    written.ask("why pull")
    written.save(path)
    job = finish(
        client,
        client.post(
            f"/api/sessions/{other}/load", json={"dialogue": path.read_text(), "name": "d.json"}
        ),
    )
    assert job["state"] == "done"
    assert [s["question"] for s in state(client, other)["steps"]] == ["why pull"]


def test_load_errors_and_the_served_model_only(client, monkeypatch):
    key = start(client)
    reply = client.post(f"/api/sessions/{key}/load", json={"dialogue": "{oops", "name": "x.json"})
    assert reply.status_code == 400
    assert reply.json["error"].startswith("x.json: not a saved dialogue (")
    job = finish(
        client, client.post(f"/api/sessions/{key}/load", json={"dialogue": "{}", "name": "x.json"})
    )
    assert job["state"] == "failed" and "not a saved ethasp dialogue" in job["error"]
    # A saved dialogue naming other model files is replayed with the served
    # model: no file it names is read.
    data = {
        "format": "ethasp-dialogue",
        "version": 1,
        "model": ["/etc/passwd"],
        "principle": "do-no-harm",
        "plan": ["refrain"],
        "under": "do-no-harm",
        "steps": [
            {
                "question": {"kind": "rather-than", "action": "refrain", "other": "pull"},
                "under": "do-no-harm",
            }
        ],
    }

    def refuse(*args, **kwargs):
        raise AssertionError("a model was loaded from a request")

    monkeypatch.setattr(Model, "load", refuse)
    job = finish(
        client,
        client.post(
            f"/api/sessions/{key}/load", json={"dialogue": json.dumps(data), "name": "x.json"}
        ),
    )
    assert job["state"] == "done" and "replayed with the served model trolley.lp" in job["note"]
    assert state(client, key)["steps"][0]["answer"]["explanation"] == CONDUCTOR


def test_state_survives_a_reload_and_a_restart(trolley):
    client = make_client(trolley)
    key = start(client)
    ask(client, key, "why refrain rather than pull")
    before = state(client, key)
    # A reload asks for the same session again: the server kept it.
    assert state(client, key) == before
    # After a restart the session is gone; the page sends its copy of the dialogue.
    restarted = make_client(trolley)
    assert restarted.get(f"/api/sessions/{key}").status_code == 404
    reply = restarted.post(
        "/api/sessions",
        json={"dialogue": json.dumps(before["dialogue"]), "name": "the page's saved dialogue"},
    )
    assert finish(restarted, reply)["state"] == "done"
    after = state(restarted, reply.json["session"])
    assert after["steps"] == before["steps"] and after["current"] == before["current"]


# -- long requests: progress, busy, cancel ---------------------------------------------------------


def test_a_running_search_shows_progress_blocks_moves_and_can_be_cancelled(tmp_path):
    path = busy_model(tmp_path)
    workspace = workspace_of(
        Model.load([path]), [str(path)], "deontology", Options(max_horizon=MAX_HORIZON)
    )
    client = create_app(workspace).test_client()
    key = start(client, plan="pull")
    reply = client.post(f"/api/sessions/{key}/ask", json={"question": SLOW_QUESTION})
    assert reply.status_code == 202
    job = reply.json["job"]
    for _ in range(1200):  # until the search reports a horizon (bounded)
        if job["progress"].startswith("plan search under deontology: horizon"):
            break
        time.sleep(0.05)
        job = client.get(f"/api/sessions/{key}/job").json["job"]
    assert job["state"] == "running" and job["description"] == f"answering '{SLOW_QUESTION}'"
    assert job["progress"].startswith("plan search under deontology: horizon"), job
    assert job["process"] in workspace.workers.pids()
    for path, body in (
        (f"/api/sessions/{key}/ask", {"question": "why pull"}),
        (f"/api/sessions/{key}/undo", {}),
        (f"/api/sessions/{key}/principle", {"principle": "deontology"}),
    ):
        reply = client.post(path, json=body)
        assert reply.status_code == 409 and reply.json["error"].startswith("busy")
    cancelled = client.post(f"/api/sessions/{key}/cancel", json={}).json["job"]
    assert cancelled["state"] == "cancelled" and "unchanged" in cancelled["note"]
    assert ended(job["process"]), "the cancelled search's worker process still runs"
    data = state(client, key)
    assert data["steps"] == [] and data["job"]["state"] == "cancelled"
    # The dialogue is free again at once, and another worker answers.
    job = ask(client, key, "why pull rather than refrain")
    assert job["state"] == "done" and job["process"] != cancelled["process"]
    assert state(client, key)["steps"][0]["question"] == "why pull rather than refrain"
    # A new worker took the place of the one ended.
    assert len(workspace.workers.pids()) == Limits().running
    assert cancelled["process"] not in workspace.workers.pids()


@pytest.mark.parametrize("work, limit", [("ground_forever", "time"), ("hog", "memory")])
def test_a_move_ended_at_a_limit_says_so(trolley, work, limit):
    """A move that cannot stop in time (a grounding) or takes memory without
    end is ended with its worker; the job says which limit ended it."""
    own = tree_resident(os.getpid()) / GB
    options = Options(time_limit=3.0) if limit == "time" else Options(memory_limit=own + 1.0)
    workspace = workspace_of(trolley, [TROLLEY], options=options)
    client = create_app(workspace).test_client()
    key = start(client)
    before = state(client, key)
    session = workspace.session(key)
    move = getattr(execution_work, work)
    job = workspace.submit(session, "ask", "a move that does not end", move)
    job.wait(60)
    data = client.get(f"/api/sessions/{key}/job").json["job"]
    words = "the time limit of 3 s" if limit == "time" else "the memory limit of"
    assert data["state"] == limit and data["error"].startswith(words), data
    assert data["error"].endswith("was reached: the work was ended and the dialogue is unchanged")
    assert ended(data["process"])
    assert state(client, key)["steps"] == before["steps"]
    assert ask(client, key, "why refrain rather than pull")["state"] == "done"


def test_a_worker_grown_large_is_replaced_after_its_move(trolley, monkeypatch):
    monkeypatch.setattr(workers_module, "REPLACE", 1e-6)  # every worker is large
    workspace = workspace_of(trolley, [TROLLEY], options=Options(memory_limit=64.0))
    client = create_app(workspace).test_client()
    key = start(client)
    job = ask(client, key, "why refrain rather than pull")
    assert job["state"] == "done" and ended(job["process"])
    for _ in range(100):  # the new worker is started in a thread
        if len(workspace.workers.pids()) == Limits().running:
            break
        time.sleep(0.05)
    assert job["process"] not in workspace.workers.pids()
    assert len(workspace.workers.pids()) == Limits().running
    # The dialogue goes on in a new worker, which grounds the model anew.
    assert ask(client, key, "why pull rather than refrain")["state"] == "done"
    assert len(state(client, key)["steps"]) == 2


# -- guards ----------------------------------------------------------------------------------------


def test_guards_against_other_sites(trolley, client):
    assert client.get("/", headers={"Host": "attacker.example"}).status_code == 403
    assert client.get("/", headers={"Host": "127.0.0.1:8765"}).status_code == 200
    assert client.get("/", headers={"Host": "[::1]:8765"}).status_code == 200
    reply = client.post("/api/sessions", json={}, headers={"Origin": "http://attacker.example"})
    assert reply.status_code == 403 and "forbidden origin" in reply.json["error"]
    reply = client.post("/api/sessions", json={}, headers={"Origin": "http://localhost"})
    assert reply.status_code == 202
    remote = make_client(trolley, loopback=False)
    assert remote.get("/", headers={"Host": "ethics.example:80"}).status_code == 200


def test_loopback_names():
    assert is_loopback("127.0.0.1") and is_loopback("localhost") and is_loopback("::1")
    assert is_loopback("[::1]") and is_loopback("127.0.0.2")
    assert not is_loopback("0.0.0.0") and not is_loopback("192.0.2.1")
    assert not is_loopback("::")


def test_server_binds_loopback_by_default(trolley):
    server = Server(workspace_of(trolley, [TROLLEY], "deontology"), None, 0)
    try:
        assert server.loopback and server.url == f"http://127.0.0.1:{server.port}/"
        assert server.httpd.server_address[0] == "127.0.0.1"
    finally:
        server.httpd.server_close()


def test_cli_serve_prints_its_url_and_serves_the_model(tmp_path):
    process = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "serve",
            "trolley",
            "--principle",
            "do-no-harm",
            "--port",
            "0",
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
    )
    try:
        line = process.stdout.readline()
        match = re.fullmatch(
            r"ethasp: serving \S*trolley\.lp at (http://127\.0\.0\.1:\d+/)\n", line
        )
        assert match, line + process.stderr.read()
        with urllib.request.urlopen(match.group(1) + "api/model", timeout=30) as reply:
            assert json.load(reply)["principle"] == "do-no-harm"
    finally:
        process.terminate()
        process.wait(timeout=30)


def test_cli_serve_errors_are_one_line(tmp_path):
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "ethasp.interfaces.cli",
            "serve",
            "trolley",
            "--principle",
            "kindness",
            "--port",
            "0",
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert run.returncode == 2 and run.stderr.startswith("ethasp: error: unknown principle")
    run = subprocess.run(
        [sys.executable, "-m", "ethasp.interfaces.cli", "serve", "trolley", "--port", "70000"],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert run.returncode == 2 and "must be 0 to 65535" in run.stderr


def test_a_pddl_model_is_shown_and_asked_in_pddl_form():
    files = [
        str(MODELS / "pddl" / name)
        for name in ("trolley-domain.pddl", "trolley-problem.pddl", "trolley-utility.lp")
    ]
    client = create_app(workspace_of(Model.load(files), files, "do-no-harm")).test_client()
    glance = client.get("/api/model").json["model"]
    assert [(a["term"], a["shown"]) for a in glance["actions"]] == [
        ("pull", "(pull)"),
        ("refrain", "(refrain)"),
    ]
    key = start(client)
    assert state(client, key)["current"]["shown"] == [{"term": "refrain", "shown": "(refrain)"}]
    # The page builds clicked questions from the shown names.
    assert ask(client, key, "why (refrain) rather than (pull)")["state"] == "done"
    answer = state(client, key)["steps"][0]["answer"]
    assert answer["contrast"]["shown"] == [{"term": "pull", "shown": "(pull)"}]
    assert b"(pull)" in client.get(f"/api/sessions/{key}/steps/1.svg").data


# -- the whole question language on the page -------------------------------------------------------


def test_a_better_plan_is_named_and_drawn(client):
    """refrain is impermissible under utilitarianism: a better reachable state
    exists, and the better plan (pull) that reaches it is shown and drawn as a
    contrast to the current plan."""
    key = start(client, "do-no-harm", plan="refrain")
    judgements = {j["principle"]: j for j in state(client, key)["current"]["judgements"]}
    utilitarian = judgements["utilitarianism"]
    assert utilitarian["better_plan"] == ["pull"]
    assert utilitarian["compared_with"]["plan"] == ["pull"]
    assert [a["shown"] for a in utilitarian["better_plan_shown"]] == ["pull"]
    assert "better_plan" not in judgements["do-no-harm"]
    picture = client.get(f"/api/sessions/{key}/better/utilitarianism.svg")
    assert picture.status_code == 200 and picture.mimetype == "image/svg+xml"
    drawn = picture.get_data(as_text=True)
    assert "the better plan: pull" in drawn and "plan: refrain" in drawn
    for principle in ("do-no-harm", "nonsense"):
        missing = client.get(f"/api/sessions/{key}/better/{principle}.svg")
        assert missing.status_code == 404 and "no better plan" in missing.json["error"]


def test_model_offers_the_principles_that_can_restrict(client):
    data = client.get("/api/model").json
    assert "kantian-humanity" in data["principles"]
    assert "kantian-humanity" not in data["restricting"]
    assert {"deontology", "do-no-harm", "utilitarianism"} <= set(data["restricting"])
    key = start(client)
    reply = client.post(f"/api/sessions/{key}/principle", json={"principle": "kantian-humanity"})
    assert reply.status_code == 400 and "cannot restrict plan search" in reply.json["error"]
    reply = client.post(f"/api/sessions/{key}/principle", json={"principle": "all"})
    assert reply.status_code == 400 and "names a group" in reply.json["error"]
    reply = client.post("/api/sessions", json={"principle": "double-effect"})
    assert reply.status_code == 400 and "cannot restrict plan search" in reply.json["error"]


@pytest.mark.parametrize(
    "plan,question,constraints",
    [
        ("refrain pull", "why pull at 2", ["not_at(pull,2)"]),
        ("refrain pull", "why refrain within 1..1", ["not_within(refrain,1,1)"]),
        ("refrain pull", "why pull after refrain", ["before(pull,refrain)"]),
        ("pull", "why one_will_die", ["ends(one_will_die,false)"]),
        ("pull", "why not five_will_die at 1", ["fact_at(five_will_die,true,1)"]),
        ("refrain pull", "why not in 1 step", ["at_most(1)"]),
    ],
)
def test_the_new_forms_on_the_page(client, plan, question, constraints):
    key = start(client, "deontology", plan)
    job = ask(client, key, question)
    assert job["state"] == "done", job
    step = state(client, key)["steps"][0]
    assert step["own_constraints"] == constraints and step["answer"]["contrast"] is not None


def test_why_step_and_the_plan_step_by_step(client):
    key = start(client, "deontology", "refrain pull")
    data = client.get(f"/api/sessions/{key}/explain?step=2").json
    assert data["step"] == 2 and data["step_text"].startswith(
        "Step 2, pull the lever, brings about the goal (the decision)."
    )
    assert [s["removable"] for s in data["steps"]] == [True, True]
    assert data["lines"][0].startswith("Step 1, refrain from action, is not needed")
    assert client.get(f"/api/sessions/{key}/explain?step=3").status_code == 400
    assert client.get(f"/api/sessions/{key}/explain?step=x").status_code == 400
    # The step's E-links and D-links, in words, and all of them.
    assert data["step_text"].endswith("it results in the decision, which fulfils the goal.")
    assert data["link_lines"][1].startswith("Step 2, pull the lever:")
    assert {"from": 2, "variable": "done", "value": True, "to": "goal"} in data["e_links"]
    picture = client.get(f"/api/sessions/{key}/explain.svg")
    assert picture.mimetype == "image/svg+xml" and b"arrowhead" in picture.data
    # "why step T" typed into the question box is no contrastive question.
    reply = client.post(f"/api/sessions/{key}/ask", json={"question": "why step 1"})
    assert reply.status_code == 400 and "explain?step=1" in reply.json["error"]


def test_what_the_current_plan_is_and_a_question_no_plan_can_meet(client):
    key = start(client)  # do-no-harm: refrain
    current = state(client, key)["current"]
    assert current["from_question"] == 0 and current["made_without_principle"] is False
    ask(client, key, "why refrain rather than pull")  # the principle is dropped
    data = state(client, key)
    assert data["current"]["from_question"] == 1
    assert data["current"]["made_without_principle"] is True and not data["unmeetable"]
    ask(client, key, "why pull rather than refrain")  # no plan meets both
    data = state(client, key)
    assert data["unmeetable"] and data["current"]["from_question"] == 1
    assert data["current"]["plan"] == ["pull"]
    # The page's button drops it (the undo move).
    assert finish(client, client.post(f"/api/sessions/{key}/undo", json={}))["state"] == "done"
    assert not state(client, key)["unmeetable"]


def test_a_situation_starts_from_its_own_plan():
    files = [str(MODELS / "hera" / "robot-and-frank.yaml")]
    client = create_app(workspace_of(Model.load(files), files, "deontology")).test_client()
    key = start(client)
    assert state(client, key)["current"]["plan"] == ["lie_to_frank"]


def test_a_model_with_action_costs_on_the_page():
    files = [str(MODELS / "errand.lp")]
    client = create_app(Workspace(Model.load(files), files, "deontology")).test_client()
    key = start(client, "deontology")
    current = state(client, key)["current"]
    assert current["plan"] == ["bus(depot,market)", "bus(market,house)", "hand_over"]
    assert current["cost"] == 5
    job = ask(client, key, "why not a cheaper plan")
    assert job["state"] == "done", job
    step = state(client, key)["steps"][0]
    assert step["own_constraints"] == ["cheaper_than(5)"]
    assert step["answer"]["contrast"]["cost"] == 2


def test_inus_reasons_of_a_choice_and_of_the_answers_sides():
    files = [str(ROOT / "tests" / "data" / "cam" / "switch.json")]
    client = create_app(workspace_of(Model.load(files), files, "hera-do-no-harm")).test_client()
    key = start(client, "hera-do-no-harm", "wait")
    current = state(client, key)["current"]
    assert current["plan"] == ["wait"]
    judged = {j["principle"]: j for j in current["judgements"]}
    assert judged["hera-do-no-harm"]["inus_reasons"] == [["not Caused(main_hit)"]]
    job = ask(client, key, "why wait rather than switch")
    assert job["state"] == "done", job
    answer = state(client, key)["steps"][0]["answer"]
    assert answer["original"]["inus_reasons"] == [["not Caused(main_hit)"]]
    assert answer["contrast"]["plan"] == ["switch"]
    assert answer["contrast"]["inus_reasons"] == [["Bad(side_hit)"], ["Caused(side_hit)"]]
    assert answer["principle_dropped"] is True and "conflicts" not in answer
