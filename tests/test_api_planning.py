"""The Python API of the planning core: models, plan search, validation."""

import pytest
from conftest import MODELS

from ethasp import InputError, Model, Plan, find_plan, validate
from ethasp.planning import search as search_module
from ethasp.principles.restriction import plan_with_principles


def trolley() -> Model:
    return Model.load([MODELS / "trolley.lp"])


def test_trolley_has_shortest_plans_of_length_one():
    result = find_plan(trolley())
    assert result.status == "found" and len(result.plan) == 1
    assert str(result.plan) in {"pull", "refrain"}
    every = find_plan(trolley(), all_plans=True)
    assert sorted(map(str, every.plans)) == ["pull", "refrain"]


@pytest.mark.parametrize("name,length", [("footbridge", 1), ("heist", 3), ("rescue", 4)])
def test_bundled_models_have_plans(name, length):
    result = find_plan(Model.load([MODELS / f"{name}.lp"]))
    assert result.status == "found" and len(result.plan) == length
    assert validate(Model.load([MODELS / f"{name}.lp"]), result.plan).valid


def test_model_from_string_and_empty_plan():
    model = Model.from_string("variable(a). init(a). goal(a,true).")
    result = find_plan(model)
    assert result.status == "found" and len(result.plan) == 0 and result.horizon == 0


def test_none_is_proven_by_relaxed_reachability():
    model = Model.from_string(
        "variable(a;b). action(x). pre(x,a,true). eff(x,b,true). goal(b,true)."
    )
    result = find_plan(model)
    assert result.status == "none" and result.horizon == 0
    assert "unreachable" in result.proof


def test_none_is_proven_by_the_loop_free_threshold():
    # Each action blocks the other: the goal is relaxed reachable but not reachable.
    model = Model.from_string(
        "variable(a;b). action(x;y). pre(x,b,false). eff(x,a,true). "
        "pre(y,a,false). eff(y,b,true). goal(a,true). goal(b,true)."
    )
    result = find_plan(model)
    assert result.status == "none" and "an exhaustive search proved it" in result.proof


def test_bounded_when_the_horizon_is_cut():
    model = Model.load([MODELS / "rescue.lp"])
    result = find_plan(model, max_horizon=2)
    assert result.status == "bounded" and result.plan is None and result.horizon == 2


def test_bounded_when_the_time_limit_is_cut():
    # A counter of 12 bits: the goal needs 4095 steps; nothing is found in no time.
    bits = 12
    lines = [f"variable(b{i}). action(inc({i}))." for i in range(bits)]
    for i in range(bits):
        lines.append(f"pre(inc({i}),b{i},false). eff(inc({i}),b{i},true).")
        lines += [f"pre(inc({i}),b{j},true). eff(inc({i}),b{j},false)." for j in range(i)]
    lines += [f"goal(b{i},true)." for i in range(bits)]
    result = find_plan(Model.from_string("\n".join(lines)), max_horizon=5000, time_limit=0.5)
    assert result.status == "bounded" and "time limit" in result.proof


def test_validation_pinpoints_the_failure():
    model = Model.load([MODELS / "heist.lp"])
    check = validate(model, Plan.parse("steal give_jewels"))
    assert not check.valid and check.failure_step == 1 and check.failure_action == "steal"
    assert check.unmet_preconditions == ["scouted"]
    check = validate(model, Plan.parse("scout"))
    assert not check.valid and check.failure_step is None and check.unmet_goals == ["impressed"]
    assert validate(model, Plan.parse("scout steal give_jewels")).valid


def test_plans_with_compound_terms():
    model = Model.load([MODELS / "rescue.lp"])
    plan = Plan.parse("move(r1,r2) move(r2, r3) break_door move(r3,r4)")
    assert [str(a) for a in plan] == ["move(r1,r2)", "move(r2,r3)", "break_door", "move(r3,r4)"]
    assert validate(model, plan).valid


def test_unknown_action_in_plan_is_an_input_error():
    with pytest.raises(InputError, match="unknown action jump at step 2"):
        validate(trolley(), Plan.parse("pull jump"))


@pytest.mark.parametrize(
    "text,message",
    [
        ("variable(a). goal(a,true). action(x). eff(x,b,true).", "unknown variable b"),
        ("variable(a). goal(b,true).", "unknown variable b"),
        ("variable(a). goal(a,true). pre(x,a,true).", "unknown action x"),
        ("variable(a). goal(a,true). action(x). utility(x,high).", "must be an integer"),
        (
            "variable(a). goal(a,true). action(x). eff(x,a,true). eff(x,a,false).",
            "both to true and to false",
        ),
        ("% nothing", "the model is empty"),
        ("variable(a). goal(a,true) p.", "syntax error"),
    ],
)
def test_bad_models_are_input_errors(text, message):
    with pytest.raises(InputError, match=message):
        Model.from_string(text)


def test_scripts_are_refused(tmp_path):
    path = tmp_path / "evil.lp"
    path.write_text("variable(a). goal(a,true).\n#script (python)\nopen('x','w')\n#end.\n")
    with pytest.raises(InputError, match=r"evil.lp:2: .*#script"):
        Model.load([path])


def test_scripts_in_included_files_are_refused(tmp_path):
    (tmp_path / "inner.lp").write_text("#script (python)\nimport os\n#end.\n")
    path = tmp_path / "outer.lp"
    path.write_text('#include "inner.lp".\nvariable(a). goal(a,true).\n')
    with pytest.raises(InputError, match="#script"):
        Model.load([path])


def test_missing_file():
    with pytest.raises(InputError, match="no such file"):
        Model.load(["does/not/exist.lp"])


def test_searches_share_one_grounding(monkeypatch):
    """A model is grounded once; the HModel of a restriction is a model of its
    own, made and grounded once per model and restriction: searching again
    grounds nothing new."""
    from ethasp.principles.hmodel import Restriction, hmodel

    # The exact layers, which start once the solver has worked a while (soon on a
    # busy machine), may prove horizons without grounding them: keep them out.
    monkeypatch.setattr(search_module, "LAYERS_AFTER", float("inf"))
    model = Model.load([MODELS / "rescue.lp"])
    result = find_plan(model, max_horizon=10)
    planner = model.planner
    assert result.status == "found" and planner.grounded >= len(result.plan)
    control, grounded = planner.ctl, planner.grounded
    hplan = plan_with_principles(model, ["deontology"], max_horizon=10)
    assert hplan.status == "found" and model.planner is planner and planner.ctl is control
    restricted = hmodel(model, Restriction.of(["deontology"]))
    assert restricted is not model  # rescue's break_door is bad
    restricted_control, restricted_grounded = restricted.planner.ctl, restricted.planner.grounded
    # Asking again grounds nothing new, in either.
    assert find_plan(model, max_horizon=10).plan == result.plan
    assert plan_with_principles(model, ["deontology"], max_horizon=10).plan == hplan.plan
    assert hmodel(model, Restriction.of(["deontology"])) is restricted
    assert (planner.ctl, planner.grounded) == (control, grounded)
    assert (restricted.planner.ctl, restricted.planner.grounded) == (
        restricted_control,
        restricted_grounded,
    )


def test_the_ground_model_is_read_one_thread_at_a_time():
    """Reading the model's atoms waits while another thread holds the planner
    (a search grounding on its control): two sessions of the page at once
    read whole atoms, never half-grounded ones."""
    import threading

    from ethasp.resources import MODELS

    planner = Model.load([MODELS / "rescue.lp"]).planner
    read: list = []
    with planner.lock:
        reader = threading.Thread(target=lambda: read.append(planner.get("action_label", 3)))
        reader.start()
        reader.join(0.5)
        assert reader.is_alive() and read == []  # waits for the lock
    reader.join(30)
    assert len(read[0]) > 10
