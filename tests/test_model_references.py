"""Models and clingo symbols sent to worker processes: a model travels as a
reference that a process resolves to the model it keeps (grounded once per
worker), symbols as their text; a model is the text read when it was loaded,
wherever it is grounded."""

from __future__ import annotations

import pickle

import model_work as work
import pytest
from conftest import MODELS

from ethasp import Model
from ethasp.execution.worker import DONE, Worker
from ethasp.planning import model as model_module
from ethasp.questions.dialogue import Dialogue

TROLLEY = MODELS / "trolley.lp"


def test_a_model_resolves_to_the_one_this_process_keeps():
    model = Model.load([TROLLEY])
    assert pickle.loads(pickle.dumps(model)) is model
    copy = Model(list(model.sources), model.allow_scripts, model.naming)
    assert copy.key == model.key and pickle.loads(pickle.dumps(copy)) is copy
    sent = pickle.dumps(model)  # the one sent last is kept
    assert pickle.loads(sent) is model and pickle.loads(pickle.dumps(copy)) is copy
    other = Model.load([MODELS / "heist.lp"])
    assert other.key != model.key and pickle.loads(pickle.dumps(other)) is other


def test_a_model_arriving_from_elsewhere_is_made_from_its_sources(monkeypatch):
    model = Model.load([TROLLEY])
    data = pickle.dumps(model)
    monkeypatch.setattr(model_module, "_kept", type(model_module._kept)())
    arrived = pickle.loads(data)
    assert arrived is not model and arrived.key == model.key
    assert arrived.sources == model.sources and not arrived.grounded()
    assert pickle.loads(data) is arrived  # kept from now on


def test_a_worker_grounds_the_model_once_and_answers_about_it():
    model = Model.load([TROLLEY])
    dialogue = Dialogue.start(model, "do-no-harm")
    worker = Worker()
    try:
        first = worker.call(work.grounded_before, dialogue)
        second = worker.call(work.grounded_before, dialogue)
        assert first.status == second.status == DONE
        assert second.value == (True, first.value[1])  # the same grounding, kept
        answered = worker.call(work.ask, dialogue, "why refrain rather than pull")
        assert answered.status == DONE
        back = answered.value
        assert back.model is model  # the model of this process again
        assert [str(c) for c in back.constraints] == ["unused(refrain)", "used(pull)"]
        assert back.current_plan.to_list() == ["pull"] and dialogue.steps == []
    finally:
        worker.kill()


def test_symbols_made_in_a_worker_arrive_whole():
    worker = Worker()
    try:
        outcome = worker.call(work.symbols)
    finally:
        worker.kill()
    assert outcome.status == DONE
    assert [str(symbol) for symbol in outcome.value] == [
        'f("caf\u00e9 \\"quoted\\" \\\\ back",-3)',
        "(a,)",
        "()",
        "-g(x)",
        "#inf",
        "#sup",
    ]
    assert outcome.value == work.symbols()


@pytest.mark.parametrize("changed", [False, True])
def test_a_model_is_the_text_read_when_it_was_loaded(tmp_path, changed):
    path = tmp_path / "trolley.lp"
    path.write_text(TROLLEY.read_text())
    model = Model.load([path])
    if changed:  # the five are no longer in danger
        path.write_text(TROLLEY.read_text().replace("init(five_will_die).", ""))
    fresh = Model(list(model.sources), model.allow_scripts, model.naming)
    assert Dialogue.start(fresh, "utilitarianism").plan.to_list() == ["pull"]
