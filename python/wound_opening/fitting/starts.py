"""The global stage of `fit`: a dense grid that cannot miss the basin of the optimum.

With no edge stress the radius is linear in (R0, R0 sigma) at fixed lambda, T and R_inf:
R_um(t) = R0 + R0 sigma h(t / T; lambda, R_inf) (objective.py). On a grid of lambda
(0 and 0.02 .. 50, 14 values) x s = T (1 + lambda^2) (the time scale of the opening, 5 per
decade from below the first sampled time, and below the diffusive time t_last / R_inf^2, to
10 times the last time), R0 and sigma are the weighted linear least squares solution of the
radii (variable projection, R_inf held at its value for R0 = the smallest radius / 1.05);
with a profile, the RESCORED best are scored again by the full cost (radius and profile,
exact R_inf). The best distinct points start the local fits.

With a specification (parameters.py) the grid honours it: a fixed lambda or T is the only
value of its axis, bounds clip the axes (and the linear R0, sigma), a fixed R0 or sigma
leaves the other one of the linear pair to solve,

    R0 fixed:     R - R0 = (R0 sigma) h          (one column)
    sigma fixed:  R = R0 (1 + sigma h)           (one column)

and the priors' chi^2 is added to each point's score.
"""

from __future__ import annotations

import math

import numpy as np

from .. import _native
from .objective import Objective, to_z

#: Accuracy of the grid's curves (relative to the opening): far below any noise that matters
#: for finding the basin; the local fits use the finest.
GRID_TOLERANCE = 1e-8
#: Grid points re-scored with the full cost (radius and profile, exact R_inf).
RESCORED = 24
LAMBDAS = (0.0, 0.02, 0.05, 0.1, 0.2, 0.35, 0.6, 1.0, 1.7, 3.0, 5.0, 10.0, 20.0, 50.0)


def _linear(obj: Objective, lam: float, T: float, r_inf: float, w: np.ndarray, spec=None):
    """(R0, sigma, weighted residual sum of squares) of the linear fit at (lambda, T), R_inf
    held (the grid only has to find the basin), or None. `spec`: fixed R0 or sigma and
    bounds (parameters.Spec)."""
    h, _ = _native.series(
        lam, 1.0, r_inf, obj.t_sorted / T, velocity=False, tolerance=GRID_TOLERANCE
    )
    h = h - 1.0
    fixed = {} if spec is None else spec.fixed
    y = (obj.radius - _offset(obj, spec)) * w
    if 0 in fixed and 1 in fixed:
        c0, c1 = fixed[0], fixed[0] * fixed[1]
    elif 0 in fixed:
        c0 = fixed[0]
        c1 = float(np.dot(h * w, y - c0 * w) / max(np.dot(h * w, h * w), 1e-300))
    elif 1 in fixed:
        b = (1 + fixed[1] * h) * w
        c0 = float(np.dot(b, y) / max(np.dot(b, b), 1e-300))
        c1 = c0 * fixed[1]
    else:
        a = np.column_stack([np.ones_like(h), h]) * w[:, None]
        (c0, c1), *_ = np.linalg.lstsq(a, y, rcond=None)
    if not (c0 > 0 and math.isfinite(c1)):
        return None
    R0, sigma = float(c0), float(c1) / float(c0)
    if spec is not None:
        R0, sigma = spec.clip(0, R0), spec.clip(1, sigma)
    return R0, sigma, float(np.sum((R0 * (1 + sigma * h) * w - y) ** 2))


def _nuisances(obj: Objective, spec) -> list[float]:
    """The nuisances' starts (own units, after the four parameters): each its declared start
    or fixed value, in its bounds."""
    return [
        c.start if spec is None else spec.clip(4 + k, c.start)
        for k, c in enumerate(obj.coordinates[4:])
    ]


def _offset(obj: Objective, spec) -> float:
    """The outline offset the grid's radii are taken to carry (its start or fixed value)."""
    return 0.0 if obj.offset is None else _nuisances(obj, spec)[obj.offset - 4]


def grid_starts(obj: Objective, cost, count: int = 4, spec=None) -> list[np.ndarray]:
    """The `count` best distinct grid points (not neighbours on the grid) by `cost(z)`;
    `spec` (parameters.Spec): fixed values, bounds and priors to honour. A nuisance starts
    at its declared start (or fixed value)."""
    tail = _nuisances(obj, spec)
    tail_z = [c.to_z(v) for c, v in zip(obj.coordinates[4:], tail)]
    t = obj.t_sorted
    positive = t[t > 0]
    t_last = float(t[-1]) if t[-1] > 0 else 1.0
    r_inf = obj.outer / float(np.min(obj.radius))
    low = min(float(positive[0]) if positive.size else t_last, t_last / r_inf**2) / 10
    s_grid = np.logspace(
        math.log10(low), math.log10(10 * t_last), int(5 * math.log10(100 * t_last / low)) + 1
    )
    w = 1.0 / obj.sd[: obj.n_radius]
    r_inf0 = obj.outer / (float(np.min(obj.radius)) / 1.05)
    lambdas = LAMBDAS if spec is None else sorted({spec.clip(2, lam) for lam in LAMBDAS})
    ranked, seen = [], set()
    for i, lam in enumerate(lambdas):
        for j, s in enumerate(s_grid):
            T = s / (1 + lam**2) if spec is None else spec.clip(3, s / (1 + lam**2))
            if (lam, T) in seen:  # a fixed or bounded T repeats itself
                continue
            seen.add((lam, T))
            try:
                lin = _linear(obj, lam, T, r_inf0, w, spec)
            except _native.SolverError:
                continue
            if lin is not None and obj.outer / lin[0] > 1.001:
                theta = (lin[0], lin[1], lam, T)
                prior = 0.0 if spec is None else spec.prior_chi2(theta + tuple(tail))
                ranked.append((lin[2] + prior, i, j, np.append(to_z(theta), tail_z)))
    ranked.sort(key=lambda s: s[0])
    scored = []
    for _, i, j, z in ranked[:RESCORED] if obj.n_profile else ranked:
        try:
            scored.append((cost(z) if obj.n_profile else _, i, j, z))
        except _native.SolverError:
            continue
    scored.sort(key=lambda s: s[0])
    chosen = []
    for c, i, j, z in scored:
        if not math.isfinite(c):
            continue
        if all(abs(i - ci) > 1 or abs(j - cj) > 2 for _, ci, cj, _ in chosen):
            chosen.append((c, i, j, z))
        if len(chosen) == count:
            break
    return [z for *_, z in chosen]
