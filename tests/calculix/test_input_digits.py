"""Numbers in the Abaqus/CalculiX inputs (issue 13, item 7): CalculiX reads a real from the first 20
characters of its field (f20.0, nodes.f) and drops the rest without a word. tools/calculix/make_inputs.py
writes the most significant digits that fit (up to 15) and checks that the text reads back, as that
Fortran read would, to the value within the rounding of the digits written.

Independent facts used: the decimal exponent range of IEEE doubles (subnormals down to 4.9e-324, the
largest 1.8e308), so that the digits that fit a 20-character field follow from counting characters:
sign + d + '.' + (n - 1) digits + 'e-300' gives n = 13 with a 3-digit negative exponent."""
import math
import os
import random

import pytest
from camclay9 import calculix_inputs
from camclay9.calculix_inputs import fmt, fortran_real

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def digits(text):
    """Significant digits in a written number."""
    mant = text.lstrip("+-").split("e")[0].replace(".", "").strip("0")   # %g strips trailing zeros
    return len(mant) or 1


def test_issue_number():
    """The number of the issue: 15 digits need 21 characters; the old text was read as -0.311."""
    v = -3.11060286983428e-15
    old = f"{v:.15g}"
    assert len(old) == 21 and fortran_real(old) == pytest.approx(-0.311060286983428, rel=1e-14)
    text = fmt(v)
    assert text == "-3.1106028698343e-15" and len(text) <= 20
    assert abs(fortran_real(text) - v) <= 0.5e-13 * abs(v)


@pytest.mark.parametrize("v, n", [
    (5e-324, 14),                         # smallest subnormal: '4.9406564584125e-324'
    (2.2250738585072014e-308, 14),        # smallest normal; .15g strips a trailing zero: 14 digits left
    (-1.2345678901234567e-300, 13),       # negative, 3-digit negative exponent: 20 = 1 + 1 + 1 + 12 + 5
    (1.2345678901234567e-100, 14),
    (-1.7976931348623157e308, 13),        # the most negative double
    (1.7976931348623157e308, 14),         # the largest double
    (-9.87654321098765e-15, 14),
    (12.7, 3), (-35.0, 2), (0.25, 2), (1.3e13, 2), (0.0, 1),
])
def test_extremes(v, n):
    text = fmt(v)
    assert len(text) <= calculix_inputs.FIELD
    assert digits(text) == n, text
    back = fortran_real(text)
    assert abs(back - v) <= (0.5 * 10.0 ** (1 - n) + 2.0 ** -52) * abs(v)
    assert math.copysign(1, back) == math.copysign(1, v) or v == 0


def test_most_digits_that_fit():
    """Random doubles over the whole exponent range: read back to 13 digits at least, and no text with more digits
    (up to 15) that fits 20 characters would have given another number; every text reads back within
    its rounding."""
    rng = random.Random(13)
    for _ in range(20000):
        v = rng.choice([-1, 1]) * rng.uniform(1, 10) * 10.0 ** rng.randint(-323, 307)
        text = fmt(v)
        n = digits(text)
        assert n <= 15 and len(text) <= 20, (v, text)
        assert abs(fortran_real(text) - v) <= (0.5e-12 + 2.0 ** -52) * abs(v), (v, text)   # 13 digits at least
        for k in range(n + 1, 16):
            longer = f"{v:.{k}g}"
            assert len(longer) > 20 or float(longer) == float(text), (v, text, longer)
        assert abs(fortran_real(text) - v) <= (0.5 * 10.0 ** (1 - n) + 2.0 ** -52) * abs(v), (v, text)


def test_fortran_read_forms():
    """The reader follows F editing: an exponent letter e/E/d/D or a signed exponent alone, an empty
    field reads 0, and only the first `width` characters count."""
    assert fortran_real("1.5d3") == 1500.0 and fortran_real("1.5-3") == 1.5e-3 and fortran_real("") == 0.0
    assert fortran_real("2.") == 2.0 and fortran_real(".5E+1") == 5.0
    assert fortran_real("123456", width=3) == 123.0
    with pytest.raises(ValueError, match="not a Fortran real"):
        fortran_real("1.2.3")


def test_clear_errors():
    for bad in (math.nan, math.inf, -math.inf):
        with pytest.raises(ValueError, match="expected a finite number"):
            fmt(bad)
    # No text fits a 4-character field for this value ('-1e-300' has 7 characters).
    with pytest.raises(ValueError, match=r"does not fit a 4-character field"):
        fmt(-1.234e-300, width=4)
    # A field that fits only a few digits still reads back within their rounding.
    assert fmt(-1.234e-300, width=7) == "-1e-300"
