"""``ethasp ask``: contrastive questions about a plan, answered with a contrast plan."""

from __future__ import annotations

import argparse

from ethasp.interfaces.cli.models import load_model, model_options
from ethasp.interfaces.cli.options import (
    budget,
    default_reasons_limit,
    given_plan,
    inherit,
    max_horizon,
    plan_options,
    reasons_option,
    satisficing_option,
    search_options,
)
from ethasp.interfaces.cli.output import checkpoint, emit, svg_option, write_picture


def add_parser(commands) -> None:
    contrast = commands.add_parser(
        "ask",
        help="answer a contrastive question 'why A rather than B?' about a plan",
        description="Answer contrastive questions about a plan: the plan of --plan, or else "
        "the plan the model comes with, or else the plan that 'ethasp plan "
        "--principle P' makes. The question's constraints and the principle Q "
        "(--under, default P; one that can restrict plan search) restrict the "
        "model; its plan (the contrast) is judged and explained beside the "
        "original. The principle is dropped only when no plan meeting the "
        "question is proven permissible under Q; a search cut short answers "
        "bounded. Questions (A, B actions, F a state variable, T, T1, T2, N whole "
        "numbers, steps from 1): 'why A', 'why not A', 'why A rather than B', "
        "'why A before B', 'why A after B', 'why A at T', 'why not A at T', "
        "'why A within T1..T2', 'why not A within T1..T2', 'why F', 'why not F' "
        "(the final state), 'why F at T', 'why not F at T' (the state after step "
        "T), 'why not in N steps', 'why not a cheaper plan' (a model with action "
        "costs); 'why action X' / 'why fact X' for a name that "
        "is both. See docs/questions.md.",
    )
    inherit(contrast, model_options())
    contrast.add_argument(
        "--question",
        action="append",
        required=True,
        metavar='"why ..."',
        help="the question (repeatable: all are imposed together)",
    )
    inherit(contrast, plan_options(required=False, what="the plan asked about"))
    contrast.add_argument(
        "--principle",
        default="deontology",
        metavar="P",
        help="the principle the plan is made and judged under (default deontology)",
    )
    contrast.add_argument(
        "--under",
        default=None,
        metavar="Q",
        help="the principle the contrast plan must satisfy (default P)",
    )
    inherit(contrast, search_options(satisficing=True))
    inherit(
        contrast,
        satisficing_option(
            "the plans searched (the contrast plan, and the plan asked about when "
            "--plan is not given)"
        ),
    )
    inherit(contrast, reasons_option(answers=True))
    inherit(contrast, svg_option("the contrast plan aligned with the plan asked about"))
    contrast.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    from ethasp.interfaces.answer_words import answer_text
    from ethasp.questions.contrast import ask

    default_reasons_limit(args)
    model = load_model(args)
    plan = (
        given_plan(args)
        if (args.plan is not None or args.plan_file is not None)
        else model.own_plan()
    )
    limits = budget(args)
    if plan is not None:
        _checkpoint(args, model, plan, limits)
    answer = ask(
        model,
        args.question,
        plan,
        args.principle,
        args.under,
        max_horizon(args),
        reasons_limit=args.reasons_limit,
        budget=limits,
        satisficing=args.satisficing,
    )
    write_picture(args, model, lambda pictures: pictures.answer(answer))
    emit(args, answer.to_json(), answer_text(answer, model.naming))
    return 0


def _checkpoint(args: argparse.Namespace, model, plan, limits) -> None:
    """The plan asked about and its verdict, printed if the contrast does not
    come within the limits (the verdict is kept for the answer)."""
    from ethasp.questions.contrast import one_principle
    from ethasp.reasons.reasons import judge

    principle = one_principle(args.principle)
    verdict = judge(model, plan, [principle], max_horizon(args), reasons_limit=0, budget=limits)
    judgement = verdict.judgements[0]
    shown = model.naming.actions(plan) or "(empty plan)"
    data = {
        "questions": list(args.question),
        "original": {
            "plan": plan.to_list(),
            "principle": principle,
            "permissible": judgement.permissible,
            "status": judgement.status,
        },
        "contrast": None,
        "status": "bounded",  # (no contrast plan yet: the front end says why)
    }
    verdict_words = "permissible" if judgement.permissible else "impermissible"
    text = f"  plan asked about: {shown} ({principle}: {verdict_words}, {judgement.status})"
    checkpoint(data, text, "the contrast plan was found and explained")
