"""The fit's parameters by name, and what the user knows of them.

**Coordinates.** Each problem declares its coordinates (`Coordinate`, `Coordinates`): what
a fit moves, how the user names it, what values it accepts and how its profile is
searched. A coordinate is a value in its own units v (R0 in um, sigma, lambda, ...) moved
by the optimiser as z = ln v (`log`) or z = v. Everything that treats coordinates by name
reads them: the user's specification below (which names exist, their accepted ranges and
units in refusals, fixed values and bounds carried into z, priors in own units), local fits
(`stretched`: the fit moves asinh z), and the profile walks (optimum.py: the search window
around a centre and the first step). A new nuisance parameter of a problem (a cut time
inside a frame interval, an outline offset, a noise level) enters the fit by one more
`Coordinate` in its problem's `coordinates`; docs/layout.md shows one.

    windows                  search limits of a profile walk around a centre c (in z)
    factor(f)                c -/+ ln f           (a log coordinate: a factor f either way)
    span()                   c -/+ (10 |c| + 1)
    between(lo, hi)          [lo, hi]

**What the user knows**: parameters held fixed, bounded, or given a Gaussian prior,
lmfit-style.

    params = Parameters()
    params.add("R0_um", value=10, vary=False)           # fixed (the radius of the cut)
    params.add("lambda", min=0, max=5)                  # bounded
    params.add("T_s", prior=(8.0, 2.0))                 # Gaussian prior: mean, standard deviation
    params.add("G_pa", prior=(1200, 200))               # for absolute eta, zeta, tension only
    fit(radius, outer_radius_um=100, params=params)

The names and attributes are lmfit's (`Parameters.add(name, value=, vary=, min=, max=)`,
`params[name].value`, `.vary`, `.min`, `.max`), with `prior=(mean, sd)` added; an
`lmfit.Parameters` is accepted too (its `expr` constraints are refused).

A prior enters the likelihood as one more residual (theta - mean) / sd, so that

    chi^2(theta) = sum over the data of ((model - data) / noise)^2 + sum over priors of ((theta
        - mean) / sd)^2

and the profile intervals, the standard errors, the Jacobian's rank check and the degrees of
freedom (n + priors - free parameters) all count it. A fixed parameter leaves every stage
(the global grid, the local fits, the rank check, the degrees of freedom, the profiles). A
bound is a box constraint of the optimiser and a limit of the profile walks; an interval
that reaches a bound ends there (`Profile.bounded`).

The same specification serves one wound (`fit`: R0_um, sigma, lambda, T_s) and several
(`fit_wounds`: viscous_length_um, tension_over_G, zeta_over_G_s_per_um2, R0_um[NAME]): the
names, accepted ranges and units are the coordinates the problem declares
(parameters.py), and every form of the user's knowledge (Parameters, lmfit.Parameters, a
dict or a list of Parameter objects) is read and refused alike.

G_pa does not enter the model (R(t) and the velocities depend on G only through lambda,
sigma and T): it takes a fixed value or a prior and serves the absolute eta, zeta and
tension (material.py).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from .problem import Problem

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
    #: Where a fit starts it (own units) when no stage estimates it: a nuisance's neutral
    #: value (a zero offset).
    start: float = 0.0

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


@dataclass
class Parameter:
    """One parameter's specification, lmfit's attribute names plus `prior` = (mean, sd)."""

    name: str
    value: float | None = None
    vary: bool = True
    min: float = -math.inf
    max: float = math.inf
    prior: tuple[float, float] | None = None


class Parameters(dict):
    """name -> Parameter, filled by `add` as lmfit's Parameters is. `value` of a varied
    parameter is not needed: the global stage finds the start (it is ignored)."""

    def add(
        self,
        name: str,
        value: float | None = None,
        vary: bool = True,
        min: float = -math.inf,
        max: float = math.inf,
        prior: tuple[float, float] | None = None,
    ) -> Parameter:
        self[name] = Parameter(name, value, vary, min, max, prior)
        return self[name]


def _number(option: str, text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"{option}: {text!r} is not a number") from None


def from_options(coordinates: Coordinates, fix=(), bound=(), prior=()) -> Parameters:
    """Parameters from the command line's NAME=VALUE (--fix), NAME=MIN:MAX (--bound, either
    side may be empty) and NAME=MEAN:SD (--prior) strings, whose names are the problem's
    `coordinates` (objective.wound_coordinates, wounds.tissue_coordinates) and G_pa; the
    values are checked by `specification`."""
    params = Parameters()

    def entry(option: str, text: str) -> tuple[Parameter, str]:
        name, sep, rest = text.partition("=")
        name = name.strip()
        if not sep or not rest.strip():
            raise ValueError(
                f"{option} {text!r}: expected NAME="
                + {"--fix": "VALUE", "--bound": "MIN:MAX", "--prior": "MEAN:SD"}[option]
            )
        if name != G_NAME:
            try:
                coordinates.index(name)
            except ValueError as e:
                raise ValueError(f"{option} {text!r}: {e}") from None
        return params.get(name) or params.add(name), rest.strip()

    for text in fix:
        p, rest = entry("--fix", text)
        p.value, p.vary = _number("--fix", rest), False
    for text in bound:
        p, rest = entry("--bound", text)
        lo, sep, hi = rest.partition(":")
        if not sep:
            raise ValueError(f"--bound {text!r}: expected NAME=MIN:MAX (either side may be empty)")
        p.min = _number("--bound", lo) if lo.strip() else -math.inf
        p.max = _number("--bound", hi) if hi.strip() else math.inf
    for text in prior:
        p, rest = entry("--prior", text)
        mean, sep, sd = rest.partition(":")
        if not sep:
            raise ValueError(f"--prior {text!r}: expected NAME=MEAN:SD")
        p.prior = (_number("--prior", mean), _number("--prior", sd))
    return params


def checked_finite(name: str, what: str, x) -> float:
    try:
        x = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: {what} = {x!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}: {what} = {x} must be finite")
    return x


@dataclass
class Spec:
    """The checked specification in own units, by coordinate index: values held fixed,
    bounds (lo, hi), priors (mean, sd); G fixed or with a prior, or None; `n` coordinates."""

    fixed: dict
    bounds: dict
    priors: dict
    G: tuple[float, float] | None = None  # (value or mean, sd; sd = 0 when fixed)
    n: int = 4

    @property
    def free(self) -> list[int]:
        return [i for i in range(self.n) if i not in self.fixed]

    def clip(self, i: int, x: float) -> float:
        """x moved into coordinate i's bounds (its fixed value if fixed)."""
        if i in self.fixed:
            return self.fixed[i]
        lo, hi = self.bounds.get(i, (-math.inf, math.inf))
        return min(max(x, lo), hi)

    def describe(self, i: int) -> dict:
        """Coordinate i's specification for the result: fixed, bounds, prior."""
        out = {}
        if i in self.fixed:
            out["fixed"] = True
        if i in self.bounds:
            out["bounds"] = list(self.bounds[i])
        if i in self.priors:
            out["prior"] = list(self.priors[i])
        return out

    def prior_chi2(self, theta) -> float:
        return float(sum(((theta[i] - m) / sd) ** 2 for i, (m, sd) in self.priors.items()))


def g_modulus(p, lo: float, hi: float, prior) -> tuple:
    """(value, sd) of G from its parameter `p` (fixed: sd 0; or a prior (mean, sd)), its bounds
    (refused: the data do not depend on G) and its checked prior, or ValueError."""
    if math.isfinite(lo) or math.isfinite(hi):
        raise ValueError(
            f"{G_NAME}: bounds are not supported (the data do not depend on G): give a fixed "
            "value or a prior"
        )
    if not p.vary:
        if prior is not None:
            raise ValueError(f"{G_NAME}: fixed and with a prior: give one of them")
        G = (checked_finite(G_NAME, "value", p.value), 0.0)
    elif prior is not None:
        G = prior
    else:
        raise ValueError(
            f"{G_NAME}: give a fixed value (vary=False) or a prior (the data do not depend on G)"
        )
    if not G[0] > 0:
        raise ValueError(f"{G_NAME}: {G[0]:g} Pa: a shear modulus must be > 0")
    return G


def _items(params) -> list:
    """The Parameter-like objects of `params`: a mapping's values, or a sequence's items."""
    if params is None:
        return []
    return (
        list(params.values())
        if isinstance(params, dict) or hasattr(params, "values")
        else list(params)
    )


def names(params) -> set:
    """The names `params` (any form `specification` reads) gives."""
    return {getattr(p, "name", None) for p in _items(params)}


def _prior(name: str, prior) -> tuple[float, float] | None:
    if prior is None:
        return None
    if not (isinstance(prior, (tuple, list)) and len(prior) == 2):
        raise ValueError(f"{name}: prior = {prior!r}: expected (mean, sd)")
    mean = checked_finite(name, "prior mean", prior[0])
    sd = checked_finite(name, "prior sd", prior[1])
    if not sd > 0:
        raise ValueError(f"{name}: prior sd = {sd:g}: a standard deviation must be > 0")
    return mean, sd


def specification(params, coordinates: Coordinates) -> Spec:
    """Check `params` (Parameters, an lmfit.Parameters, a dict name -> Parameter, a list of
    Parameter objects, or None) against the problem's `coordinates` and return a Spec;
    ValueError naming the parameter and the reason otherwise."""
    fixed, bounds, priors, G = {}, {}, {}, None
    for p in _items(params):
        name = getattr(p, "name", None)
        i = None if name == G_NAME else coordinates.index(name)
        if getattr(p, "expr", None):
            raise ValueError(
                f"{name}: expressions (expr = {p.expr!r}) are not supported: fix, bound or give a "
                f"prior"
            )
        lo = -math.inf if p.min is None else float(p.min)
        hi = math.inf if p.max is None else float(p.max)
        if math.isnan(lo) or math.isnan(hi):
            raise ValueError(f"{name}: a bound is NaN")
        if not lo < hi:
            raise ValueError(f"{name}: min = {lo:g} is not below max = {hi:g}")
        prior = _prior(name, getattr(p, "prior", None))
        if i is None:
            G = g_modulus(p, lo, hi, prior)
            continue
        c = coordinates[i]
        if not p.vary:
            if prior is not None or math.isfinite(lo) or math.isfinite(hi):
                raise ValueError(f"{name}: a fixed parameter takes no bounds and no prior")
            v = checked_finite(name, "value", p.value)
            if not c.accepts(v):
                raise ValueError(
                    f"{name} = {v:g}: outside the accepted range {c.range_text()}{c.note}"
                )
            fixed[i] = v
            continue
        if math.isfinite(lo) or math.isfinite(hi):
            if not max(lo, c.lower) < min(hi, c.upper):
                raise ValueError(
                    f"{name}: bounds [{lo:g}, {hi:g}] leave nothing of the accepted range "
                    f"{c.range_text()}"
                )
            bounds[i] = (lo, hi)
        if prior is not None:
            priors[i] = prior
    if len(fixed) == len(coordinates):
        raise ValueError(
            f"every fit parameter is fixed: leave at least one of {', '.join(coordinates.names)} "
            "free"
        )
    return Spec(fixed, bounds, priors, G, len(coordinates))


class Constrained(Problem):
    """A problem with the user's specification: residuals and Jacobian with one row per
    prior appended, bounds narrowed to the user's, coordinates held fixed (`fixed`, in z,
    honoured by local.local_fit). The problem's own objective is `inner`, its coordinates
    are its declared ones (`coordinates`); the fits move asinh of those declared
    `stretched`."""

    def __init__(self, inner: Problem, spec: Spec):
        self.inner, self.spec = inner, spec
        self.coordinates = inner.coordinates
        self.fixed = {i: self.coordinates[i].to_z(v) for i, v in spec.fixed.items()}
        self.user_bounded = frozenset(spec.bounds)
        self.stretched = self.coordinates.stretched()
        self.wound_maps = inner.wound_maps

    @property
    def size(self) -> int:
        return self.inner.size + len(self.spec.priors)

    @property
    def free(self) -> list[int]:
        return self.spec.free

    def prior_residuals(self, z) -> np.ndarray:
        c = self.coordinates
        return np.array([(c[i].own(z[i]) - m) / sd for i, (m, sd) in self.spec.priors.items()])

    def residuals(self, z) -> np.ndarray:
        return np.concatenate([self.inner.residuals(z), self.prior_residuals(z)])

    def jacobian(self, z, columns=None) -> np.ndarray:
        """The data's Jacobian and, per prior, d value_i / d z_i / sd in column i."""
        n = len(self.coordinates)
        wanted = range(n) if columns is None else columns
        rows = np.zeros((len(self.spec.priors), n))
        for k, (i, (_, sd)) in enumerate(self.spec.priors.items()):
            if i in wanted:
                rows[k, i] = self.coordinates[i].d_own(z[i]) / sd
        return np.vstack([self.inner.jacobian(z, columns), rows])

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """The data's bounds narrowed to the user's, in z."""
        lower, upper = self.inner.bounds()
        for i, (lo, hi) in self.spec.bounds.items():
            c = self.coordinates[i]
            lower[i], upper[i] = max(lower[i], c.bound_z(lo)), min(upper[i], c.bound_z(hi))
        return lower, upper

    def vanishing(self, z) -> list:
        return self.inner.vanishing(z)

    def user_bound(self, i: int, side: int) -> bool:
        """Whether the limit of coordinate i on `side` (-1 lower, +1 upper) is the user's."""
        if i not in self.spec.bounds:
            return False
        k = 0 if side < 0 else 1
        return bool(self.bounds()[k][i] != self.inner.bounds()[k][i])
