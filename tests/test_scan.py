"""The quick scan of program texts (regular expressions) agrees with the
exact scan (character by character): whatever it clears, the exact scan
clears too, with the same included files."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from ethasp.errors import InputError
from ethasp.planning.terms import _quick_scan, _scan_exactly

PIECES = [
    "p(1).",
    "q(X) :- p(X).",
    "% a (comment\n",
    "%* block ( *%",
    '"a ( string"',
    '#include "a.lp".',
    "(",
    ")",
    "1+2*3",
    "-5",
    "2147483647",
    "2147483648",
    "0x10",
    "#script (python) x = 1 #end.",
    "\n",
    " ",
    "..",
    "r(1..3).",
    "é",
    "\x01",
    '#include "b.lp". % #include "c.lp"\n',
    "f(g(h(1))).",
    ":- not p(1).",
]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.sampled_from(PIECES), max_size=30))
def test_quick_scan_clears_only_what_the_exact_scan_clears(pieces):
    """(Where the quick scan leaves a text to the exact scan, that one decides:
    it clears the text or refuses it with an InputError.)"""
    text = "".join(pieces)
    quick = _quick_scan(text)
    try:
        exact, refused = _scan_exactly(text, "t.lp"), None
    except InputError as error:
        exact, refused = None, error
    if quick is not None:
        assert exact is not None, f"quick scan cleared {text!r}, exact scan: {refused}"
        assert quick.includes == exact.includes


def test_deep_nesting_and_long_numbers_go_to_the_exact_scan():
    assert _quick_scan("p(" * 20_000 + ")" * 20_000 + ".") is None
    assert _quick_scan("p(3000000000).") is None
    assert _quick_scan("p(1). % 3000000000\n") is not None
