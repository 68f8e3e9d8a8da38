"""The global stage of `fit`: a dense grid that cannot miss the basin of the optimum.

With no edge stress the radius is linear in (R0, R0 sigma) at fixed lambda, T and R_inf:
R_um(t) = R0 + R0 sigma h(t / T; lambda, R_inf) (objective.py). On a grid of lambda
(0 and 0.02 .. 50, 14 values) x s = T (1 + lambda^2) (the time scale of the opening, 5 per
decade from below the first sampled time, and below the diffusive time t_last / R_inf^2, to
10 times the last time), R0 and sigma are the weighted linear least squares solution of the
radii (variable projection, R_inf updated from R0 twice); every grid point is then scored by
the full cost (radius and profile). The best distinct points start the local fits.
"""

from __future__ import annotations

import math

import numpy as np

from . import _native
from .objective import Objective, to_z

LAMBDAS = (0.0, 0.02, 0.05, 0.1, 0.2, 0.35, 0.6, 1.0, 1.7, 3.0, 5.0, 10.0, 20.0, 50.0)


def _linear(obj: Objective, lam: float, T: float, w: np.ndarray):
    """(R0, sigma) of the weighted linear fit at (lambda, T), or None."""
    y = obj.radius
    R0 = float(np.min(y)) / 1.05
    for _ in range(3):
        r_inf = obj.outer / R0
        if not r_inf > 1.001:
            return None
        h, _ = obj._h(lam, r_inf, obj.t_sorted / T)
        a = np.column_stack([np.ones_like(h), h]) * w[:, None]
        (c0, c1), *_ = np.linalg.lstsq(a, y * w, rcond=None)
        if not (c0 > 0 and math.isfinite(c1)):
            return None
        R0 = float(c0)
    return R0, float(c1) / R0


def grid_starts(obj: Objective, cost, count: int = 4) -> list[np.ndarray]:
    """The `count` best distinct grid points (not neighbours on the grid) by `cost(z)`."""
    t = obj.t_sorted
    positive = t[t > 0]
    t_last = float(t[-1]) if t[-1] > 0 else 1.0
    r_inf = obj.outer / float(np.min(obj.radius))
    low = min(float(positive[0]) if positive.size else t_last, t_last / r_inf**2) / 10
    s_grid = np.logspace(math.log10(low), math.log10(10 * t_last), int(5 * math.log10(100 * t_last / low)) + 1)
    w = 1.0 / obj.sd[: obj.n_radius]
    scored = []
    for i, lam in enumerate(LAMBDAS):
        for j, s in enumerate(s_grid):
            T = s / (1 + lam**2)
            try:
                lin = _linear(obj, lam, T, w)
                if lin is None:
                    continue
                z = to_z((lin[0], lin[1], lam, T))
                scored.append((cost(z), i, j, z))
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
