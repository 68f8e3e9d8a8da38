"""The named coordinates a problem declares: what a fit moves, how the user names it, what
values it accepts and how its profile is searched.

A coordinate is a value in its own units v (R0 in um, sigma, lambda, ...) moved by the
optimiser as z = ln v (`log`) or z = v. Everything that treats coordinates by name reads it
from here: the user's specification (parameters.py: which names exist, their accepted
ranges and units in refusals, fixed values and bounds carried into z, priors in own units),
local fits (`stretched`: the fit moves asinh z), and the profile walks (optimum.py: the
search window around a centre and the first step). A new nuisance parameter of a problem
(a cut time inside a frame interval, an outline offset, a noise level) enters the fit by
one more `Coordinate` in its problem's `coordinates`.

    WINDOWS                  search limits of a profile walk around a centre c (in z)
    factor(f)                c -/+ ln f           (a log coordinate: a factor f either way)
    span()                   c -/+ (10 |c| + 1)
    between(lo, hi)          [lo, hi]
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

#: A profile walk's search limits (lower, upper in z) around a centre (z of the problem) for
#: coordinate i, with the optimum z_hat: an end that reaches one is open.
Window = Callable[[np.ndarray, np.ndarray, int], tuple[float, float]]


def factor(f: float) -> Window:
    """A factor f either way of a log coordinate's centre."""
    step = math.log(f)
    return lambda centre, z_hat, i: (centre[i] - step, centre[i] + step)


def span() -> Window:
    """10 |c| + 1 either way of the centre c (sigma: a pre-stress of either sign)."""

    def window(centre, z_hat, i):
        width = 10 * abs(centre[i]) + 1
        return centre[i] - width, centre[i] + width

    return window


def between(lo: float, hi: float) -> Window:
    """A fixed range (lambda from its bound 0 to LAMBDA_MAX)."""
    return lambda centre, z_hat, i: (lo, hi)


@dataclass(frozen=True)
class Coordinate:
    """One coordinate of a problem.

    `name` and `unit` are the user's (specification, refusals, results); values are
    accepted in (lower, upper), and at `lower` too where `closed` (lambda = 0); `note`
    follows a refusal of a value outside them. `window` and `step` (a number, or a function
    of the optimum z_hat) set its profile walk's search limits and first step where the
    Jacobian gives none; `stretched`: the user's fit moves asinh z (local.py: the valley
    along lambda^2 T = const is straight in asinh lambda for lambda >> 1)."""

    name: str
    unit: str
    log: bool = False
    lower: float = -math.inf
    upper: float = math.inf
    closed: bool = False
    window: Window = span()
    step: float | Callable[[np.ndarray], float] = 0.1
    stretched: bool = False
    note: str = ""

    def to_z(self, v: float) -> float:
        """z of the value v (own units)."""
        return math.log(v) if self.log else v

    def bound_z(self, v: float) -> float:
        """z of a bound v (own units): a non-positive bound of a log coordinate is -inf."""
        if not self.log:
            return v
        return math.log(v) if v > 0 else -math.inf

    def own(self, z: float) -> float:
        """The value (own units) at z."""
        return math.exp(z) if self.log else z

    def d_own(self, z: float) -> float:
        """d value / d z at z."""
        return math.exp(z) if self.log else 1.0

    def accepts(self, v: float) -> bool:
        return self.lower < v < self.upper or (self.closed and v == self.lower)

    def first_step(self, z_hat: np.ndarray) -> float:
        return float(self.step(z_hat) if callable(self.step) else self.step)

    def range_text(self) -> str:
        return f"({self.lower:g}, {self.upper:g}) {self.unit}"


class Coordinates(tuple):
    """A problem's coordinates in order (z[i] is coordinate i), found by name; `aliases` maps
    further names to an index (a wound's R0 by its number), `unknown(name)` says why a name
    is none of them (default: the names accepted, and G_pa)."""

    def __new__(cls, items: Sequence[Coordinate], aliases=None, unknown=None):
        self = super().__new__(cls, items)
        self.aliases = dict(aliases or {})
        self.unknown = unknown or self._unknown
        return self

    def _unknown(self, name: str) -> str:
        return f"parameter {name!r} is unknown: expected one of {', '.join(self.names + (G_NAME,))}"

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(c.name for c in self)

    def index(self, name: str) -> int:
        """The index of `name` (or an alias); ValueError saying why it is unknown."""
        for i, c in enumerate(self):
            if c.name == name:
                return i
        if name in self.aliases:
            return self.aliases[name]
        raise ValueError(self.unknown(name))

    def stretched(self) -> tuple[int, ...]:
        return tuple(i for i, c in enumerate(self) if c.stretched)

    def own(self, z) -> tuple[float, ...]:
        """Every coordinate's value in own units at z."""
        return tuple(c.own(v) for c, v in zip(self, z))


#: G, which only scales the absolute material values: a name every fit accepts (fixed or a
#: prior), not a coordinate (the data do not depend on it).
G_NAME = "G_pa"
