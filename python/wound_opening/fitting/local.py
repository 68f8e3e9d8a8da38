"""Local fits: bounded least squares from a start, with the objective's Jacobian.

scipy.optimize.least_squares (trust region reflective) in z = (ln R0, sigma, lambda, ln T)
with lambda >= 0 as a bound and x_scale from the Jacobian. The tolerances (1e-12 on the
cost, the step and the gradient) are far below the data's precision: a change of chi^2 of
1e-12 chi^2 is invisible at any noise level, so the fit stops at the optimum, not on a
plateau of a coarse criterion. `loss` is least_squares' (linear, soft_l1, cauchy) on the
residuals in units of their uncertainty (f_scale = 1).

The coordinates a problem calls `stretched` (lambda) are moved as x = asinh(lambda), with
d r / d x = cosh(x) d r / d lambda: linear near the bound 0 (kept at x = 0), ln(2 lambda)
beyond 1. Where R(t) depends on tau = lambda^2 T only (lambda >> 1, the tissue moving as one)
the valley ln T = ln tau - 2 ln lambda is then a straight line, which the trust region
follows in a few steps; in lambda it is curved, and fits held at a value of another
parameter crawled along it for their 200 evaluations (the intervals' walks).
"""

from __future__ import annotations

import numpy as np
from scipy import optimize

from .problem import Problem


def cost(res: np.ndarray, loss: str = "linear") -> float:
    """chi^2 for the linear loss; 2 sum rho(r^2) for a robust one (same scale near 0)."""
    z = res**2
    if loss == "soft_l1":
        return float(np.sum(4 * (np.sqrt(1 + z) - 1)))
    if loss == "cauchy":
        return float(np.sum(2 * np.log1p(z)))
    return float(np.sum(z))


#: A fit that comes this near (in each coordinate it moves) to a point of `ends` ends there.
NEAR = 1e-2


class _Stop(Exception):
    """A point where a watched fit stops: (z, cost or None, why)."""


def local_fit(
    obj: Problem,
    z0,
    fixed: int | None = None,
    value: float | None = None,
    loss: str = "linear",
    tol: float = 1e-12,
    max_nfev: int = 200,
    *,
    below: float | None = None,
    ends=(),
):
    """Minimise the cost of the problem `obj` (problem.py: any dimension) from z0, with
    coordinate `fixed` held at `value` if given, and the coordinates `obj.fixed` (the user's
    fixed parameters) held at theirs. Returns (z, cost at z, least_squares result).

    A watched fit stops early (result status -2): at its first point of cost under `below`
    (the question asked was whether it gets there), and where it comes within NEAR (in each
    coordinate it moves, lambda as asinh(lambda)) of a point of `ends` (where earlier fits
    at the same held value ended: it would end there too), returning that point."""
    held = dict(obj.fixed)
    if fixed is not None:
        held[fixed] = value
    lower, upper = obj.bounds()
    free = [i for i in range(lower.size) if i not in held]
    z = np.clip(np.array(z0, dtype=float), lower, upper)
    for i, v in held.items():
        z[i] = v
    if not free:  # every coordinate held: nothing to minimise
        c = cost(obj.residuals(z), loss)
        return (
            z,
            c,
            optimize.OptimizeResult(
                x=z[[]], status=1, nfev=1, success=True, message="Every coordinate held."
            ),
        )
    inner = (lower[free] < z[free]) & (z[free] < upper[free])
    z[free] = np.where(inner, z[free], np.clip(z[free], lower[free] + 1e-9, upper[free] - 1e-9))
    # the stretched coordinates' positions among the free ones: the fit moves x = asinh(z)
    bent = [k for k, i in enumerate(free) if i in getattr(obj, "stretched", ())]

    def full(x):
        w = z.copy()
        w[free] = x
        w[[free[k] for k in bent]] = np.sinh(x[bent])
        return w

    def jac(x):
        j = obj.jacobian(full(x), columns)[:, free]
        j[:, bent] *= np.cosh(x[bent])
        return j

    def stretch(v):
        v = np.array(v, dtype=float)
        v[bent] = np.arcsinh(v[bent])
        return v

    columns = free if held else None  # the columns the fit needs
    evaluations = 0
    arrivals = [(e, stretch(e[free])) for e in (np.array(p, dtype=float) for p in ends)]

    def residuals(x):
        nonlocal evaluations
        evaluations += 1
        w = full(x)
        r = obj.residuals(w)
        if below is not None and (c := cost(r, loss)) < below:
            raise _Stop(w, c, f"cost {c:.6g} under {below:.6g}")
        for e, xe in arrivals:
            if np.max(np.abs(x - xe)) < NEAR:
                raise _Stop(e, None, "at an earlier fit's end")
        return r

    try:
        res = optimize.least_squares(
            residuals,
            stretch(z[free]),
            jac=jac,
            bounds=(stretch(lower[free]), stretch(upper[free])),
            method="trf",
            x_scale="jac",
            loss=loss,
            xtol=tol,
            ftol=tol,
            gtol=tol,
            max_nfev=max_nfev,
        )
    except _Stop as stop:
        w, c, why = stop.args
        c = cost(obj.residuals(w), loss) if c is None else c
        result = optimize.OptimizeResult(
            x=w[free], status=-2, nfev=evaluations, success=False, message=why
        )
        return w, c, result
    z = full(res.x)
    return z, cost(obj.residuals(z), loss), res
