"""Local fits: bounded least squares from a start, with the objective's Jacobian.

scipy.optimize.least_squares (trust region reflective) in z = (ln R0, sigma, lambda, ln T)
with lambda >= 0 as a bound and x_scale from the Jacobian. The tolerances (1e-12 on the
cost, the step and the gradient) are far below the data's precision: a change of chi^2 of
1e-12 chi^2 is invisible at any noise level, so the fit stops at the optimum, not on a
plateau of a coarse criterion. `loss` is least_squares' (linear, soft_l1, cauchy) on the
residuals in units of their uncertainty (f_scale = 1).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from .objective import LAMBDA_MAX, Objective


def bounds(obj: Objective) -> tuple[np.ndarray, np.ndarray]:
    """Bounds in z: R0 between 1 % of the smallest radius and the outer radius / 1.001
    (R_inf >= 1.001), sigma free, 0 <= lambda <= LAMBDA_MAX, T within 1e-6 .. 1e6 of the
    last time."""
    t_max = float(obj.t_sorted[-1]) if obj.t_sorted[-1] > 0 else 1.0
    lower = np.array([math.log(0.01 * float(np.min(obj.radius))), -np.inf, 0.0, math.log(1e-6 * t_max)])
    upper = np.array([math.log(obj.outer / 1.001), np.inf, LAMBDA_MAX, math.log(1e6 * t_max)])
    return lower, upper


def bounds_of(obj) -> tuple[np.ndarray, np.ndarray]:
    """The bounds of `obj`: its own `bounds()` (a wrapper's) or those of an Objective."""
    return obj.bounds() if hasattr(obj, "bounds") else bounds(obj)


def cost(res: np.ndarray, loss: str = "linear") -> float:
    """chi^2 for the linear loss; 2 sum rho(r^2) for a robust one (same scale near 0)."""
    z = res**2
    if loss == "soft_l1":
        return float(np.sum(4 * (np.sqrt(1 + z) - 1)))
    if loss == "cauchy":
        return float(np.sum(2 * np.log1p(z)))
    return float(np.sum(z))


def local_fit(obj: Objective, z0, fixed: int | None = None, value: float | None = None,
              loss: str = "linear", tol: float = 1e-12, max_nfev: int = 200):
    """Minimise the cost from z0, with coordinate `fixed` held at `value` if given, and the
    coordinates `obj.fixed` (a dict, the user's fixed parameters) held at theirs.
    `obj` may be an Objective or another objective of any dimension with its own `bounds()`
    (parameters.py, the reparametrisations of derived.py, the several wounds of tissue.py).
    Returns (z, cost at z, least_squares result)."""
    held = dict(getattr(obj, "fixed", {}))
    if fixed is not None:
        held[fixed] = value
    lower, upper = bounds_of(obj)
    free = [i for i in range(lower.size) if i not in held]
    z = np.clip(np.array(z0, dtype=float), lower, upper)
    for i, v in held.items():
        z[i] = v
    if not free:  # every coordinate held: nothing to minimise
        c = cost(obj.residuals(z), loss)
        return z, c, optimize.OptimizeResult(x=z[[]], status=1, nfev=1, success=True,
                                             message="Every coordinate held.")
    inner = (lower[free] < z[free]) & (z[free] < upper[free])
    z[free] = np.where(inner, z[free], np.clip(z[free], lower[free] + 1e-9, upper[free] - 1e-9))

    def full(x):
        w = z.copy()
        w[free] = x
        return w

    if held and getattr(obj, "partial_jacobian", isinstance(obj, Objective)):
        def jacobian(w):
            return obj.jacobian(w, free)
    else:
        jacobian = obj.jacobian
    res = optimize.least_squares(lambda x: obj.residuals(full(x)), z[free],
                                 jac=lambda x: jacobian(full(x))[:, free],
                                 bounds=(lower[free], upper[free]), method="trf", x_scale="jac", loss=loss,
                                 xtol=tol, ftol=tol, gtol=tol, max_nfev=max_nfev)
    z = full(res.x)
    return z, cost(obj.residuals(z), loss), res
