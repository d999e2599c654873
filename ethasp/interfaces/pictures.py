"""The pictures of plans, judgements and answers, for the command line's
``--svg FILE`` and for the page: a timeline of a plan with its verdicts, an
answer's contrast plan aligned with the plan asked about, and a plan that a
better reachable state makes impermissible aligned with the better plan
(:mod:`ethasp.interfaces.svg` draws them)."""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from ethasp.errors import InputError
from ethasp.interfaces.svg import Arrow, contrast_svg, plan_svg
from ethasp.planning.model import Model
from ethasp.planning.plan import Plan
from ethasp.planning.timeline import Timeline, Valuation, timeline

if TYPE_CHECKING:
    from ethasp.principles.judgement import Judgement, JudgementReport
    from ethasp.questions.contrast import Answer, Side
    from ethasp.questions.steps import StepsExplanation

# Timelines kept per plan (a server draws the same plans again and again).
CACHED = 128


def verdict(judgement: Judgement) -> str:
    """``permissible (proven)`` or ``impermissible as far as searched (bounded)``."""
    word = "permissible" if judgement.permissible else "impermissible"
    return (
        f"{word} (proven)"
        if judgement.status == "proven"
        else f"{word} as far as searched (bounded)"
    )


def write(path: str | Path, svg: str) -> None:
    """Write a picture; InputError if the file cannot be written."""
    try:
        Path(path).write_text(svg, encoding="utf-8")
    except OSError as error:
        raise InputError(f"{path}: cannot be written ({error.strerror or error})") from None


class Pictures:
    """Draws the plans of one model; keeps their timelines (thread-safe).

    Given the model's ``valuation`` and the ``timelines`` of the plans to
    draw (made where the model is grounded), it draws without clingo, and
    only those plans (a plan without its timeline is a LookupError).
    """

    def __init__(
        self,
        model: Model,
        valuation: Valuation | None = None,
        timelines: Mapping[tuple[str, ...], Timeline] | None = None,
    ):
        self.model = model
        self._valuation = valuation
        self._timelines: OrderedDict[tuple[str, ...], Timeline] = OrderedDict(timelines or {})
        self._given = timelines is not None
        self._lock = threading.Lock()

    @property
    def valuation(self) -> Valuation:
        if self._valuation is None:
            self._valuation = Valuation.of_model(self.model)
        return self._valuation

    def timeline(self, plan: Plan, reach_goal: bool = True) -> Timeline:
        """The timeline of a plan (kept); ``reach_goal``: see
        :func:`ethasp.planning.timeline.timeline`."""
        key = tuple(plan.to_list())
        with self._lock:
            if key in self._timelines:
                self._timelines.move_to_end(key)
                return self._timelines[key]
        if self._given:
            raise LookupError(f"no timeline of the plan {' '.join(key) or '(empty)'}")
        drawn = timeline(self.model, plan, self.valuation, reach_goal)
        with self._lock:
            self._timelines[key] = drawn
            while len(self._timelines) > CACHED:
                self._timelines.popitem(last=False)
        return drawn

    def _actions(self, plan: Plan) -> str:
        return self.model.naming.actions(plan) or "(empty plan)"

    def plan(self, plan: Plan, title: str = "", notes: list[str] | None = None) -> str:
        """A plan as a timeline."""
        return plan_svg(
            self.timeline(plan), self.model.naming, title or f"plan: {self._actions(plan)}", notes
        )

    def report(self, report: JudgementReport, title: str = "", words: bool = True) -> str:
        """A judged plan: its timeline under its verdicts and (``words``) explanations."""
        notes = []
        for judgement in report.judgements if words else []:
            notes.append((f"{judgement.principle}: {verdict(judgement)}", True))
            if judgement.explanation is not None and judgement.explanation.text:
                notes.append(judgement.explanation.text)
        return self.plan(report.plan, title, notes)

    def better(self, report: JudgementReport, judgement: Judgement, words: bool = True) -> str:
        """A plan that a better reachable state makes impermissible
        (utilitarianism), drawn above the better plan that reaches that
        state, their steps aligned (as a contrast); InputError where the
        judgement has no better plan."""
        better = judgement.better_plan
        if better is None or judgement.compared is None:
            raise InputError(f"{judgement.principle}: the plan has no better plan to draw")
        principle = judgement.principle
        notes = [judgement.proof] if words else []
        if words and judgement.explanation is not None and judgement.explanation.text:
            notes.append(judgement.explanation.text)
        return contrast_svg(
            self.timeline(report.plan),
            self.timeline(better, reach_goal=False),
            self.model.naming,
            title=f"{principle}: a better reachable state, and a plan that reaches it",
            notes=notes,
            original_title=(
                f"plan: {self._actions(report.plan)} \u2014 {principle}: {verdict(judgement)} "
                f"(final state: utility {report.utility})"
            ),
            contrast_title=(
                f"the better plan: {self._actions(better)} \u2014 final state: utility "
                f"{judgement.compared.utility}"
            ),
        )

    def explained(self, explanation: StepsExplanation, title: str = "", words: bool = True) -> str:
        """A plan with its E-links (arrows from the producer, the start column
        for the initial state, to the step enabled, or to the final state for
        the goal) and its D-links (drawn in another colour, dashed: from the
        producer to the step required), under its explanation in words."""
        naming = self.model.naming
        arrows = []
        for link in explanation.e_links + explanation.d_links:
            target = link.consumer.step if link.consumer.kind != "goal" else None
            label = naming.fact(link.literal())
            if link.consumer.kind == "goal":
                label += " (goal)"
            elif link.demand:
                label += " (requires)"
            arrows.append(
                Arrow(link.producer.step, target, label, link.producer.kind == "event", link.demand)
            )
        notes = explanation.lines() + explanation.link_lines() if words else []
        return plan_svg(
            self.timeline(explanation.plan),
            naming,
            title or f"plan: {self._actions(explanation.plan)}, step by step",
            notes,
            list(dict.fromkeys(arrows)),
        )

    def _side_title(self, role: str, side: Side) -> str:
        return (
            f"{role}: {self._actions(side.plan)} \u2014 {side.principle}: {verdict(side.judgement)}"
        )

    def repair(
        self, answer: Answer, words: bool = True, repaired: Timeline | None = None
    ) -> str | None:
        """An answer whose principle was dropped: the cheapest repair's plan,
        in the repaired model, aligned with the plan asked about (None without
        a repair's plan); ``repaired``: that plan's timeline, if drawn already
        (:func:`repaired_timeline`)."""
        impasse = answer.impasse
        result = impasse.repair if impasse is not None else None
        if result is None or not result.repairs or result.repairs[0].plan is None:
            return None
        best = result.repairs[0]
        naming = self.model.naming
        changes = "; ".join(change.text(naming) for change in best.changes)
        repaired = repaired or repaired_timeline(answer)
        verdicts = ", ".join(f"{j.principle}: {verdict(j)}" for j in best.judgements)
        notes = [impasse.text] if words and impasse is not None else []
        return contrast_svg(
            self.timeline(answer.original.plan),
            repaired,
            naming,
            title=f"cheapest repair (cost {best.cost}): {changes}",
            notes=notes,
            original_title=self._side_title("plan asked about", answer.original),
            contrast_title=f"repaired plan: {self._actions(best.plan)} \u2014 {verdicts}",
        )

    def answer(self, answer: Answer, words: bool = True) -> str:
        """An answer: the contrast plan drawn aligned with the plan asked about,
        under the contrastive explanation (``words``)."""
        questions = "; ".join(str(question) for question in answer.questions)
        notes = [answer.explanation] if words else []
        if answer.impasse is not None and words:
            notes.append(answer.impasse.text)
        if answer.principle_dropped and words:
            notes.append(
                f"The principle {answer.under} was dropped for the contrast: "
                f"{answer.dropped_because}"
            )
        if answer.conflict and words:
            notes.append(
                "Conflicting constraints: "
                + ", ".join(self.model.naming.constraint(c.term) for c in answer.conflict)
            )
        contrast = answer.contrast
        return contrast_svg(
            self.timeline(answer.original.plan),
            self.timeline(contrast.plan) if contrast is not None else None,
            self.model.naming,
            title=questions,
            notes=notes,
            original_title=self._side_title("plan asked about", answer.original),
            contrast_title=(
                self._side_title("contrast plan", contrast)
                if contrast is not None
                else "contrast plan"
            ),
            missing=f"none ({answer.status}: {answer.proof})",
        )


def repaired_timeline(answer: Answer) -> Timeline | None:
    """The timeline of the cheapest repair's plan of an answer, in the repaired
    model (None without one)."""
    impasse = answer.impasse
    result = impasse.repair if impasse is not None else None
    if result is None or not result.repairs or result.repairs[0].plan is None:
        return None
    best = result.repairs[0]
    return timeline(best.model, best.plan, Valuation.of_model(best.model))
