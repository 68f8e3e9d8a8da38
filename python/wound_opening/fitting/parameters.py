"""What the user knows before the fit: parameters held fixed, bounded, or given a Gaussian
prior, lmfit-style.

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

G_pa does not enter the model (R(t) and the velocities depend on G only through lambda,
sigma and T): it takes a fixed value or a prior and serves the absolute eta, zeta and
tension (material.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..results.names import NAMES
from .objective import LAMBDA_MAX, Objective, from_z
from .problem import Problem

#: The fit parameters (NAMES) and G, which only scales the absolute material values.
G_NAME = "G_pa"
ACCEPTED = NAMES + (G_NAME,)
UNITS = {
    "R0_um": "um",
    "sigma": "1 (tension / G)",
    "lambda": "1 (viscous length / R0)",
    "T_s": "s",
    G_NAME: "Pa",
}


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


def from_options(fix=(), bound=(), prior=(), accepted=ACCEPTED) -> Parameters:
    """Parameters from the command line's NAME=VALUE (--fix), NAME=MIN:MAX (--bound, either
    side may be empty) and NAME=MEAN:SD (--prior) strings; checked by `specification`.
    `accepted`: the names allowed (one wound's by default; tissue_spec.accepted for several)."""
    params = Parameters()

    def entry(option: str, text: str) -> tuple[Parameter, str]:
        name, sep, rest = text.partition("=")
        name = name.strip()
        if not sep or not rest.strip():
            raise ValueError(
                f"{option} {text!r}: expected NAME="
                + {"--fix": "VALUE", "--bound": "MIN:MAX", "--prior": "MEAN:SD"}[option]
            )
        if name not in accepted:
            raise ValueError(
                f"{option} {text!r}: parameter {name!r} is unknown: expected one of "
                f"{', '.join(accepted)}"
            )
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


def _accepted_range(i: int, outer: float) -> tuple[float, float]:
    """The values the fit can represent: R0 in (0, outer / 1.001), sigma any, lambda in
    [0, LAMBDA_MAX], T > 0."""
    return ((0.0, outer / 1.001), (-math.inf, math.inf), (0.0, LAMBDA_MAX), (0.0, math.inf))[i]


@dataclass
class Spec:
    """The checked specification in theta units (index into NAMES): values held fixed,
    bounds (lo, hi), priors (mean, sd); G fixed or with a prior, or None."""

    fixed: dict
    bounds: dict
    priors: dict
    G: tuple[float, float] | None = None  # (value or mean, sd; sd = 0 when fixed)

    @property
    def free(self) -> list[int]:
        return [i for i in range(4) if i not in self.fixed]

    def clip(self, i: int, x: float) -> float:
        """x moved into parameter i's bounds (its fixed value if fixed)."""
        if i in self.fixed:
            return self.fixed[i]
        lo, hi = self.bounds.get(i, (-math.inf, math.inf))
        return min(max(x, lo), hi)

    def describe(self, i: int) -> dict:
        """Parameter i's specification for the result: fixed, bounds, prior."""
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


def specification(params, outer_radius_um: float) -> Spec:
    """Check `params` (Parameters, an lmfit.Parameters, a dict name -> Parameter, or None)
    and return a Spec; ValueError naming the parameter and the reason otherwise."""
    fixed, bounds, priors, G = {}, {}, {}, None
    items = (
        []
        if params is None
        else list(params.values())
        if hasattr(params, "values")
        else list(params)
    )
    for p in items:
        name = getattr(p, "name", None)
        if name not in ACCEPTED:
            raise ValueError(
                f"parameter {name!r} is unknown: expected one of {', '.join(ACCEPTED)}"
            )
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
        prior = getattr(p, "prior", None)
        if prior is not None:
            if not (isinstance(prior, (tuple, list)) and len(prior) == 2):
                raise ValueError(f"{name}: prior = {prior!r}: expected (mean, sd)")
            mean, sd = (
                checked_finite(name, "prior mean", prior[0]),
                checked_finite(name, "prior sd", prior[1]),
            )
            if not sd > 0:
                raise ValueError(f"{name}: prior sd = {sd:g}: a standard deviation must be > 0")
            prior = (mean, sd)
        if name == G_NAME:
            G = g_modulus(p, lo, hi, prior)
            continue
        i = NAMES.index(name)
        a, b = _accepted_range(i, outer_radius_um)
        if not p.vary:
            if prior is not None or math.isfinite(lo) or math.isfinite(hi):
                raise ValueError(f"{name}: a fixed parameter takes no bounds and no prior")
            v = checked_finite(name, "value", p.value)
            if not (a < v < b or (i == 2 and v == 0.0)):
                raise ValueError(
                    f"{name} = {v:g}: outside the accepted range ({a:g}, {b:g}) {UNITS[name]}"
                    + (" (R0 below the outer radius / 1.001)" if i == 0 else "")
                )
            fixed[i] = v
            continue
        if math.isfinite(lo) or math.isfinite(hi):
            lo_in, hi_in = max(lo, a), min(hi, b)
            if not lo_in < hi_in:
                raise ValueError(
                    f"{name}: bounds [{lo:g}, {hi:g}] leave nothing of the accepted range "
                    f"({a:g}, {b:g}) {UNITS[name]}"
                )
            bounds[i] = (lo, hi)
        if prior is not None:
            priors[i] = prior
    if len(fixed) == 4:
        raise ValueError(
            "every fit parameter is fixed: leave at least one of R0_um, sigma, lambda, T_s free"
        )
    return Spec(fixed, bounds, priors, G)


def _z(i: int, x: float) -> float:
    """Coordinate i of z = (ln R0, sigma, lambda, ln T) for parameter value x."""
    return math.log(x) if i in (0, 3) else x


class Constrained(Problem):
    """The objective of the data with the specification: residuals and Jacobian with one row
    per prior appended, bounds narrowed to the user's, coordinates held fixed (`fixed`, in z,
    honoured by local.local_fit). The data's own objective is `obj`."""

    stretched = (1, 2)  # sigma and lambda: its fits move asinh of them (local.py)

    def __init__(self, obj: Objective, spec: Spec):
        self.obj, self.spec = obj, spec
        self.fixed = {i: _z(i, v) for i, v in spec.fixed.items()}
        self.user_bounded = frozenset(spec.bounds)
        self.t_sorted, self.radius, self.outer = obj.t_sorted, obj.radius, obj.outer
        self.n_radius, self.n_profile = obj.n_radius, obj.n_profile

    @property
    def size(self) -> int:
        return self.obj.size + len(self.spec.priors)

    @property
    def sd(self):
        return self.obj.sd

    def prior_residuals(self, z) -> np.ndarray:
        theta = from_z(z)
        return np.array([(theta[i] - m) / sd for i, (m, sd) in self.spec.priors.items()])

    def residuals(self, z) -> np.ndarray:
        return np.concatenate([self.obj.residuals(z), self.prior_residuals(z)])

    def jacobian(self, z, columns=None) -> np.ndarray:
        """The data's Jacobian and, per prior, d theta_i / d z_i / sd in column i."""
        columns = (0, 1, 2, 3) if columns is None else columns
        theta = from_z(z)
        rows = np.zeros((len(self.spec.priors), 4))
        for k, (i, (_, sd)) in enumerate(self.spec.priors.items()):
            if i in columns:
                rows[k, i] = (theta[i] if i in (0, 3) else 1.0) / sd
        return np.vstack([self.obj.jacobian(z, columns), rows])

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """The accepted bounds (Objective.bounds) narrowed to the user's, in z."""
        lower, upper = self.obj.bounds()
        for i, (lo, hi) in self.spec.bounds.items():
            if i in (0, 3):
                lo, hi = (
                    (math.log(lo) if lo > 0 else -math.inf),
                    (math.log(hi) if hi > 0 else -math.inf),
                )
            lower[i], upper[i] = max(lower[i], lo), min(upper[i], hi)
        return lower, upper

    def user_bound(self, i: int, side: int) -> bool:
        """Whether the limit of coordinate i on `side` (-1 lower, +1 upper) is the user's."""
        if i not in self.spec.bounds:
            return False
        default = self.obj.bounds()[0 if side < 0 else 1][i]
        mine = self.bounds()[0 if side < 0 else 1][i]
        return bool(mine != default)
