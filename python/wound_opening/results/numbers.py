"""Numbers as the figures and reports print them: an interval's ends to the digits that decide
whether a value is inside.

An end is rounded outward (a lower end down, an upper end up), so that the printed interval
contains the computed one, to at least `digits` significant digits, and with more digits
until

- its last printed digit is not a 0 that rounding produced: an end at 2.4977 prints 2.498,
  not 2.50 or 2.5, so a round number just outside never reads as the end itself (an end that
  is exactly 2.5 prints 2.50);
- it differs from the estimate printed to the same digits (an interval [2.31, 2.31] around
  2.31 says nothing).

An interval with both ends closed prints each to its own precision too (`own_digits`):
down to a tenth of its width, so that the outward rounding never widens it by more.

At most MAX_DIGITS significant digits: beyond, the end is printed as computed (repr).
"""

from __future__ import annotations

import math
from decimal import ROUND_CEILING, ROUND_FLOOR, ROUND_HALF_EVEN, Decimal

#: Significant digits an end is printed to at most.
MAX_DIGITS = 12


def _round(x: float, n: int, rounding) -> Decimal:
    """x to n significant digits (decimal, exact: the float's own digits via repr)."""
    d = Decimal(repr(float(x)))
    if d == 0:
        return Decimal(0)
    exponent = d.adjusted() - n + 1
    r = d.quantize(Decimal(1).scaleb(exponent), rounding=rounding)
    if r.adjusted() > d.adjusted():  # 9.99 -> 10.0: one digit more than asked for
        r = r.quantize(Decimal(1).scaleb(exponent + 1), rounding=rounding)
    return r


def _text(d: Decimal) -> str:
    """A decimal as printed: plain between 1e-4 and 1e6, else with an exponent, its digits
    (trailing zeros included) kept."""
    if d == 0:
        return "0"
    if -4 <= d.adjusted() < 6:
        return format(d, "f")
    digits = len(d.as_tuple().digits)
    return format(d, f".{max(digits - 1, 0)}e")


def number(x, digits: int = 4) -> str:
    """A value to `digits` significant digits (nearest); "open" for None, "nan" and "inf"
    as such."""
    if x is None:
        return "open"
    x = float(x)
    if not math.isfinite(x):
        return str(x)
    return _text(_round(x, digits, ROUND_HALF_EVEN).normalize() if x != 0 else Decimal(0))


def end(x, side: int, estimate=None, digits: int = 3) -> str:
    """An interval end (side -1 lower, +1 upper) rounded outward to the digits that decide
    whether a value is inside (module docstring); "open" for None."""
    if x is None:
        return "open"
    x = float(x)
    if not math.isfinite(x):
        return str(x)
    rounding = ROUND_FLOOR if side < 0 else ROUND_CEILING
    exact = Decimal(repr(x))
    for n in range(max(digits, 1), MAX_DIGITS + 1):
        r = _round(x, n, rounding)
        if r == 0 and exact != 0:
            continue
        made_zero = r != exact and r.as_tuple().digits[-1] == 0
        same = (
            estimate is not None
            and math.isfinite(float(estimate))
            and r == _round(float(estimate), n, ROUND_HALF_EVEN)
            and exact != Decimal(repr(float(estimate)))
        )
        if not made_zero and not same:
            return _text(r)
    return repr(x)


def own_digits(x, width, digits: int = 3) -> int:
    """The significant digits of an end `x` of an interval `width` wide: at least `digits`,
    and down to a tenth of the width (two digits of the width), so that rounding outward
    widens the interval by at most a tenth: [12.155, 12.203] prints [12.155, 12.203], not
    [12.1, 12.3]."""
    if x is None or width is None or not (math.isfinite(x) and math.isfinite(width)):
        return digits
    if x == 0 or width <= 0:
        return digits
    quantum = math.floor(math.log10(width / 10))
    return min(max(digits, Decimal(repr(float(x))).adjusted() - quantum + 1), MAX_DIGITS)


def interval(lower, upper, estimate=None, digits: int = 3) -> str:
    """ "[lower, upper]" with each end as `end` prints it, to the interval's own precision
    (own_digits) where both ends are closed."""
    return "[{}, {}]".format(*ends(lower, upper, estimate, digits))


def ends(lower, upper, estimate=None, digits: int = 3) -> tuple[str, str]:
    """The ends as `interval` prints them."""
    width = None if lower is None or upper is None else float(upper) - float(lower)
    lo = end(lower, -1, estimate, own_digits(lower, width, digits))
    return lo, end(upper, 1, estimate, own_digits(upper, width, digits))


#: The material values' symbols and units as figures print them.
SYMBOLS = {
    "eta_over_G_s": ("η/G", " s"),
    "zeta_over_G_s_per_um2": ("ζ/G", " s/µm²"),
    "tension_over_G": ("tension/G", ""),
    "viscous_length_um": ("viscous length", " µm"),
    "G_pa": ("G", " Pa"),
    "eta_pa_s": ("η", " Pa s"),
    "zeta_pa_s_per_um2": ("ζ", " Pa s/µm²"),
    "tension_pa": ("tension", " Pa"),
}


def material_lines(material: dict) -> list:
    """One line per material value (FitResult.material, TissueFitResult.material): its
    estimate, unit and 95 % interval (ends as `end` prints them), "not identified" where so."""
    lines = []
    for name, m in material.items():
        symbol, unit = SYMBOLS.get(name, (name, ""))
        if name == "G_pa":
            given = "fixed" if m["fixed"] else f"prior ± {number(m['sd'], 3)}"
            lines.append(f"{symbol} = {number(m['estimate'])}{unit} ({given})")
            continue
        if not m.get("interval_computed", True):
            ci = "(interval not computed)"
        else:
            lo, hi = m["ci95"]
            ci = interval(lo, hi, m["estimate"]) + ("" if m["identifiable"] else " not identified")
        lines.append(f"{symbol} = {number(m['estimate'])}{unit}  {ci}")
    return lines
