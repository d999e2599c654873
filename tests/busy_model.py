"""A model whose questions about late steps search long and take memory: a
lever to pull or not, and a control room of buttons that can be pressed
again and again, each only while every lamp is lit.  A question such as
"why not refrain at 200" asks for a plan of 200 steps, and every step of
every horizon searched is large to ground; questions about the lever are
answered at once."""

from __future__ import annotations

from pathlib import Path

SLOW_QUESTION = "why not refrain at 200"
MAX_HORIZON = 300


def busy_model(folder: Path, size: int = 30) -> Path:
    """The model, written into ``folder``, with ``size`` buttons and lamps."""
    path = folder / f"busy-{size}.lp"
    path.write_text(
        f"""% A lever, and a control room of {size} buttons and {size} lamps.
variable(done).
action(pull; refrain).
eff(pull, done, true).
eff(refrain, done, true).
goal(done, true).
utility(pull, -1).
variable(lamp(1..{size})).
init(lamp(1..{size})).
action(press(1..{size})).
pre(press(B), lamp(L), true) :- B = 1..{size}, L = 1..{size}.
"""
    )
    return path
