"""`fit`: weighted least squares of the model on a wound radius series and/or a PIV velocity
profile, for R0_um, sigma, lambda (>= 0) and T_s, with profile-likelihood intervals.

1. Global stage: chi^2 on a grid of (lambda, T) around the data's time scale, with R0 and
   sigma from the first and last radii; the three best distinct points start local fits.
2. Local fits: scipy.optimize.least_squares (trust region, lambda >= 0 as a bound) in
   z = (ln R0, sigma, lambda, ln T); see objective.py for how R_inf = outer / R0 is handled.
3. Noise: given, or estimated per data set from its residuals (degrees of freedom shared
   in proportion to the points); with an estimated noise the intervals use the F(1, n - 4)
   quantile instead of chi^2(1) (3.84).
4. Intervals: profile likelihood (profile.py); standard errors and correlations from the
   Jacobian at the optimum.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize, stats

from .data import RadiusSeries, VelocityProfile
from .objective import LAMBDA_MAX, NAMES, Objective, from_z, to_z
from .profile import profile_all
from .result import FitResult, ParameterReport



def _bounds(obj: Objective) -> tuple[np.ndarray, np.ndarray]:
    """Bounds in z: R0 between 1 % of the first radius and the outer radius / 1.001 (R_inf
    >= 1.001), sigma free, 0 <= lambda <= LAMBDA_MAX, T within 1e-6 .. 1e6 of the last time."""
    t_max = float(obj.t_sorted[-1]) if obj.t_sorted[-1] > 0 else 1.0
    lower = np.array([math.log(0.01 * obj.radius[0]), -np.inf, 0.0, math.log(1e-6 * t_max)])
    upper = np.array([math.log(obj.outer / 1.001), np.inf, LAMBDA_MAX, math.log(1e6 * t_max)])
    return lower, upper


def local_fit(obj: Objective, z0, fixed: int | None = None, value: float | None = None, exact: bool = False,
              tol: float = 1e-10, passes: int = 6):
    """Minimise chi^2 from z0, with coordinate `fixed` held at `value` if given. R_inf is
    frozen at the current R0 per run and updated until R0 settles (at most `passes` runs);
    `exact` polishes with R_inf following R0. The chi^2 returned is always the exact one
    at the point returned (R_inf = outer / R0). Returns (z, chi2, least_squares result)."""
    free = [i for i in range(4) if i != fixed]
    lower, upper = _bounds(obj)
    z = np.clip(np.array(z0, dtype=float), lower, upper)
    if fixed is not None:
        z[fixed] = value

    def run(r_inf):
        def fun(x):
            full = z.copy()
            full[free] = x
            return obj.residuals(full, r_inf)
        return optimize.least_squares(fun, z[free], bounds=(lower[free], upper[free]), method="trf",
                                      x_scale=1.0, xtol=tol, ftol=tol, max_nfev=400)

    for _ in range(passes):
        r_inf = obj.r_inf(math.exp(z[0]))
        res = run(r_inf)
        moved = abs(res.x[0] - z[0]) if fixed != 0 else 0.0
        z[free] = res.x
        if fixed == 0 or moved < 10 * tol:
            break
    if exact and fixed != 0:
        res = run(None)
        z[free] = res.x
    return z, float(np.sum(obj.residuals(z) ** 2)), res


def _starts(obj: Objective, radius: RadiusSeries) -> list[np.ndarray]:
    """The global stage: a (lambda, T) grid with R0, sigma from the first and last radii."""
    t, r = obj.t_sorted, obj.radius
    r1, rf = float(r[0]), float(max(r[-1], r[0] * 1.001))
    r_inf = obj.outer / r1
    k = r_inf**2 / (r_inf**2 - 1)
    q = rf / r1
    sigma = float(np.clip((q - 1) / (2 * k / 3 - q / 6), 1e-3, 50.0))
    R0 = r1 / (1 + sigma / 6)
    half = float(np.interp(0.5 * (r1 + rf), np.maximum.accumulate(r), t)) if r[-1] > r[0] else float(t[-1])
    half = max(half, float(t[t > 0][0]) if np.any(t > 0) else 1.0)
    grid = []
    for lam in (0.03, 0.3, 1.0, 3.0, 10.0):
        for factor in (0.03, 0.1, 0.3, 1.0, 3.0, 10.0):
            T = half * factor / max(1.0, lam**2)
            z = to_z((R0, sigma, lam, T))
            grid.append((float(np.sum(obj.residuals(z) ** 2)), z))
    grid.sort(key=lambda g: g[0])
    chosen = []
    for _, z in grid:
        if all(abs(z[2] - c[2]) > 0.2 or abs(z[3] - c[3]) > 0.5 for c in chosen):
            chosen.append(z)
        if len(chosen) == 3:
            break
    return chosen


def _estimate_noise(obj: Objective, z) -> None:
    res = obj.residuals(z)
    n = obj.size
    for k, part in enumerate(obj.split(res)):
        if part.size:
            dof = max(part.size - 4 * part.size / n, 1.0)
            obj.noise[k] *= math.sqrt(float(np.sum(part**2)) / dof)


def _covariance(jac: np.ndarray) -> np.ndarray:
    return np.linalg.pinv(jac.T @ jac, rcond=1e-12)


def fit(radius: RadiusSeries, profile: VelocityProfile | None = None, *, outer_radius_um: float,
        starts: int = 2, intervals: bool = True) -> FitResult:
    """Fit R0_um, sigma, lambda and T_s; see the module docstring and docs/fitting.md."""
    obj = Objective(radius, profile, outer_radius_um)
    if obj.n_radius + obj.n_profile < 5:
        raise ValueError(f"fit: {obj.size} data points for 4 parameters: need at least 5")
    known = [radius.noise_um, profile.noise_um_s if profile is not None else None]
    obj.noise = [known[0] or 0.01 * float(np.mean(obj.radius)), known[1] or 1.0]
    if profile is not None and known[1] is None:
        obj.noise[1] = max(float(np.std(np.concatenate([g[2] for g in obj.groups]))), 1e-12) * 0.1
    best = None
    for z0 in _starts(obj, radius)[:starts]:
        z, chi2, res = local_fit(obj, z0)
        if best is None or chi2 < best[1]:
            best = (z, chi2, res)
    z = best[0]
    estimated = [known[0] is None, profile is not None and known[1] is None]
    if any(estimated):
        for _ in range(2):  # noise from the residuals, then refit with those weights
            saved = list(obj.noise)
            _estimate_noise(obj, z)
            obj.noise = [obj.noise[k] if estimated[k] else saved[k] for k in range(2)]
            z, chi2, res = local_fit(obj, z)
    z, chi2, res = local_fit(obj, z, exact=True)
    dof = max(obj.size - 4, 1)
    threshold = float(stats.f.ppf(0.95, 1, dof)) if any(estimated) else float(stats.chi2.ppf(0.95, 1))
    cov_z = _covariance(res.jac)
    theta = from_z(z)
    scale = np.array([theta[0], 1.0, 1.0, theta[3]])  # d theta / d z
    cov = cov_z * np.outer(scale, scale)
    se = np.sqrt(np.clip(np.diag(cov), 0, None))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(se, se)
    profiles = profile_all(obj, z, chi2, threshold, cov_z) if intervals else {}
    reports = {}
    for i, name in enumerate(NAMES):
        p = profiles.get(name)
        reports[name] = ParameterReport(name, theta[i], float(se[i]), p)
    radius_res = obj.split(obj.residuals(z))[0] * obj.noise[0]
    return FitResult(theta=theta, reports=reports, correlation=corr, chi2=chi2, threshold=threshold,
                     outer_radius_um=obj.outer, residual_rms_um=float(np.sqrt(np.mean(radius_res**2))),
                     noise=tuple(obj.noise), n_points=(obj.n_radius, obj.n_profile), has_profile=profile is not None,
                     evaluations=obj.evaluations)
