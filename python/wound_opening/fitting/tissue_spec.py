"""What the user knows before a fit of several wounds (wounds.py): the shared material values
and each wound's R0 held fixed, bounded or given a Gaussian prior, and G for the absolute
material values, with the single fit's `Parameters` (parameters.py).

    params = Parameters()
    params.add("tension_over_G", min=0)                     # bounded
    params.add("zeta_over_G_s_per_um2", prior=(0.1, 0.03))  # a prior [s/um^2]
    params.add("R0_um[A]", value=5, vary=False)             # wound A's cut radius, fixed
    params.add("G_pa", prior=(1200, 200))                   # AFM: absolute eta, zeta, tension
    fit_wounds(wounds, params=params)

Names: the coordinates of the tissue fit, in their own units,

    viscous_length_um       l = lambda R0 = 2 sqrt(eta / zeta) [um]      coordinate y0
    tension_over_G          sigma                                          y1
    zeta_over_G_s_per_um2   zeta / G [s/um^2]                              y2 = ln zeta/G
    R0_um[NAME] or R0_um[K] wound NAME's (or the K-th wound's, from 1) R0   y(2+K) = ln R0

and G_pa (fixed or a prior only; the data do not depend on G). eta_over_G_s is l^2 zeta/G / 4,
not a coordinate: constrain l or zeta/G instead (refused with that message). A prior is one
more residual (value - mean) / sd, a bound a box of the optimiser and a limit of the profile
walks, a fixed value leaves the fit and the profiles (parameters.py says how each enters).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from ..results.names import ETA, SHARED
from .parameters import G_NAME, Parameters, checked_finite, g_modulus
from .problem import Problem

UNITS = {SHARED[0]: "um", SHARED[1]: "1 (tension / G)", SHARED[2]: "s/um^2", "R0_um": "um"}
SINGLE_ONLY = ("sigma", "lambda", "T_s", "R0_um")


def accepted(names) -> tuple:
    """The names a tissue fit of wounds `names` accepts (module docstring)."""
    return (
        SHARED
        + (G_NAME,)
        + tuple(f"R0_um[{n}]" for n in names)
        + tuple(f"R0_um[{k + 1}]" for k in range(len(names)))
    )


def _index(name: str, names) -> int:
    """The coordinate of y a name constrains; ValueError naming the accepted ones."""
    if name in SHARED:
        return SHARED.index(name)
    m = re.fullmatch(r"R0_um\[(.+)\]", name or "")
    if m:
        key = m.group(1)
        if key in names:
            return 3 + list(names).index(key)
        if key.isdigit() and 1 <= int(key) <= len(names):
            return 2 + int(key)
    if name == ETA:
        raise ValueError(
            f"{ETA} is not a coordinate of the fit of several wounds (eta/G = l^2 zeta/G / 4): "
            f"constrain {SHARED[0]} or {SHARED[2]} instead"
        )
    hint = (
        f" ({name} is one wound's parameter: with several wounds use "
        f"{', '.join(SHARED)} or R0_um[NAME])"
        if name in SINGLE_ONLY
        else ""
    )
    raise ValueError(
        f"parameter {name!r} is unknown for several wounds{hint}: expected one of "
        f"{', '.join(SHARED + (G_NAME,))}, R0_um[NAME] or R0_um[K] with NAME one of "
        f"{', '.join(names)} (K from 1 to {len(names)})"
    )


def _own(i: int, y: float) -> float:
    """Coordinate i of y in its own units (l, sigma as they are; zeta/G, R0 from logs)."""
    return y if i < 2 else math.exp(y)


def _coordinate(i: int, v: float) -> float:
    return v if i < 2 else math.log(v)


@dataclass
class TissueSpec:
    """Checked, in own units by coordinate of y: fixed values, bounds, priors; G or None."""

    fixed: dict
    bounds: dict
    priors: dict
    G: tuple | None = None

    def describe(self, i: int) -> dict:
        out = {}
        if i in self.fixed:
            out["fixed"] = True
        if i in self.bounds:
            out["bounds"] = list(self.bounds[i])
        if i in self.priors:
            out["prior"] = list(self.priors[i])
        return out


def _allowed(i: int) -> tuple[float, float, bool]:
    """(lower, upper, lower included) of coordinate i's values in own units."""
    return (
        (0.0, math.inf, True)
        if i == 0
        else (-math.inf, math.inf, False)
        if i == 1
        else (
            0.0,
            math.inf,
            False,
        )
    )


def tissue_specification(params, names) -> TissueSpec:
    """Check `params` (Parameters, lmfit.Parameters, dict or None) against the wounds `names`."""
    fixed, bounds, priors, G = {}, {}, {}, None
    items = [] if params is None else list(params.values()) if hasattr(params, "values") else []
    for p in items:
        name = getattr(p, "name", None)
        if getattr(p, "expr", None):
            raise ValueError(f"{name}: expressions (expr = {p.expr!r}) are not supported")
        lo = -math.inf if p.min is None else float(p.min)
        hi = math.inf if p.max is None else float(p.max)
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            raise ValueError(f"{name}: min = {lo:g} is not below max = {hi:g}")
        prior = getattr(p, "prior", None)
        if prior is not None:
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
        i = _index(name, names)
        a, b, closed = _allowed(i)
        unit = UNITS.get(name, "um")
        if not p.vary:
            if prior is not None or math.isfinite(lo) or math.isfinite(hi):
                raise ValueError(f"{name}: a fixed parameter takes no bounds and no prior")
            v = checked_finite(name, "value", p.value)
            if not (a < v < b or (closed and v == a)):
                raise ValueError(
                    f"{name} = {v:g}: outside the accepted range ({a:g}, {b:g}) {unit}"
                )
            fixed[i] = v
            continue
        if math.isfinite(lo) or math.isfinite(hi):
            if not max(lo, a) < min(hi, b):
                raise ValueError(
                    f"{name}: bounds [{lo:g}, {hi:g}] leave nothing of the accepted range "
                    f"({a:g}, {b:g}) {unit}"
                )
            bounds[i] = (lo, hi)
        if prior is not None:
            priors[i] = prior
    if sum(1 for i in fixed if i < 3) == 3 and len(fixed) == 3 + len(names):
        raise ValueError("every coordinate of the fit is fixed: leave at least one free")
    return TissueSpec(fixed, bounds, priors, G)


class ConstrainedTissue(Problem):
    """A Tissue (wounds.py) with the user's specification: one residual per prior appended,
    bounds narrowed to the user's, coordinates held fixed (`fixed`, in y)."""

    def __init__(self, tissue, spec: TissueSpec):
        self.tissue, self.spec = tissue, spec
        self.parts, self.n = tissue.parts, tissue.n
        self.fixed = {i: _coordinate(i, v) for i, v in spec.fixed.items()}
        self.user_bounded = frozenset(spec.bounds)

    @property
    def size(self) -> int:
        return self.tissue.size + len(self.spec.priors)

    @property
    def evaluations(self) -> int:
        return self.tissue.evaluations

    @property
    def free(self) -> list:
        return [i for i in range(self.n) if i not in self.fixed]

    def z(self, y, k):
        return self.tissue.z(y, k)

    def theta(self, y, k):
        return self.tissue.theta(y, k)

    def prior_residuals(self, y) -> np.ndarray:
        return np.array([(_own(i, y[i]) - m) / sd for i, (m, sd) in self.spec.priors.items()])

    def residuals(self, y) -> np.ndarray:
        return np.concatenate([self.tissue.residuals(y), self.prior_residuals(y)])

    def jacobian(self, y, columns=None) -> np.ndarray:
        rows = np.zeros((len(self.spec.priors), self.n))
        for k, (i, (_, sd)) in enumerate(self.spec.priors.items()):
            rows[k, i] = (1.0 if i < 2 else math.exp(y[i])) / sd
        return np.vstack([self.tissue.jacobian(y), rows])

    def bounds(self):
        lower, upper = self.tissue.bounds()
        for i, (lo, hi) in self.spec.bounds.items():
            if i >= 2:
                lo = math.log(lo) if lo > 0 else -math.inf
                hi = math.log(hi) if hi > 0 else -math.inf
            lower[i], upper[i] = max(lower[i], lo), min(upper[i], hi)
        return lower, upper

    def user_bound(self, i: int, side: int) -> bool:
        if i not in self.spec.bounds:
            return False
        k = 0 if side < 0 else 1
        return bool(self.bounds()[k][i] != self.tissue.bounds()[k][i])


def from_tissue_options(fix, bound, prior, names) -> Parameters:
    """Parameters from the command line's --fix, --bound, --prior for wounds `names`."""
    from .parameters import from_options

    for option, texts in (("--fix", fix), ("--bound", bound), ("--prior", prior)):
        for text in texts:
            name = text.partition("=")[0].strip()
            if name != G_NAME and "=" in text:
                try:
                    _index(name, names)
                except ValueError as e:
                    raise ValueError(f"{option} {text!r}: {e}") from None
    return from_options(fix, bound, prior, accepted=accepted(names))
