"""`fit`: weighted least squares of the model on a wound radius series and/or a PIV velocity
profile, for R0_um, sigma, lambda (>= 0) and T_s, with profile-likelihood intervals.

1. Global stage (start.py): a lambda x time-scale grid with R0 and sigma solved linearly at
   each point; the four best distinct points start local fits.
2. Local fits (local.py): scipy.optimize.least_squares with the objective's Jacobian
   (objective.py), tolerances 1e-12; the best of the starts is kept.
3. Noise: given (one level or per point), or estimated per data set from its residuals
   (degrees of freedom shared in proportion to the points; 1.4826 x the median absolute
   residual with a robust loss); with an estimated noise the intervals use the F(1, dof)
   quantile instead of chi^2(1) (3.84).
4. Intervals: profile likelihood (likelihood.py), also of tau, zeta/G and the viscous length
   (derived.py); standard errors from the Jacobian.
5. Verdict: converged only if the optimiser reports convergence, the Jacobian has full rank
   and, with the noise given, chi^2 is consistent with its degrees of freedom (p >= 1e-6).

`params` (parameters.py): parameters held fixed, bounded or given a Gaussian prior, and G
for the absolute material values (material.py). Fixed parameters leave every stage; each
prior is one more residual; the degrees of freedom are n + priors - free parameters.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from .._native import SolverError
from ..inputs.series import RadiusSeries, VelocityProfile, check_against, where
from ..results.export import data_points
from ..results.names import NAMES
from .objective import Objective, from_z
from .plausibility import time_scale_warnings
from ..results.profiles import Profile
from ..results.result import FitResult, ParameterReport

#: chi^2 p-value below which the model is said not to describe the data (fit failed), and
#: below which a warning is given.
P_FAIL, P_WARN = 1e-6, 1e-3
#: A cost drop this small (chi^2 units) moves a 95 % interval end (chi^2 + 3.84) negligibly:
#: a fit that ran out of evaluations on a flat valley is converged if a restart drops less.
FLAT = 0.01
#: |residual| / noise above which a point is flagged as down-weighted by a robust loss.
OUTLIER = 3.0


def _uncertainties(obj: Objective, radius: RadiusSeries, profile: VelocityProfile | None):
    """Initial per-point uncertainties and which data sets have theirs estimated."""
    r_sd = radius.sd_um if radius.sd_um is not None else np.full(obj.n_radius, radius.noise_um or 1.0)
    sd = [np.asarray(r_sd, float)[obj.order]]
    estimated = [radius.noise_um is None and radius.sd_um is None, False]
    if profile is not None:
        p_sd = profile.sd_um_s if profile.sd_um_s is not None else np.full(obj.n_profile, profile.noise_um_s or 1.0)
        sd.append(np.concatenate([np.asarray(p_sd, float)[g[3]] for g in obj.groups]))
        estimated[1] = profile.noise_um_s is None and profile.sd_um_s is None
        if estimated[1]:
            sd[1][:] = max(float(np.std(np.concatenate([g[2] for g in obj.groups]))), 1e-12) * 0.1
    if estimated[0]:
        sd[0][:] = 0.01 * float(np.mean(obj.radius))
    obj.sd = np.concatenate(sd)
    return estimated


def _estimate_noise(obj: Objective, z, estimated, robust: bool, share: float | None = None) -> None:
    """Scale the estimated data sets' uncertainties to their residuals at z; `share`: the
    fraction of each set's points taken by the parameters (default 4 / the points)."""
    res = obj.residuals(z)
    parts = obj.split(res)
    scale = []
    for k, part in enumerate(parts):
        if not (estimated[k] and part.size):
            scale.append(np.ones(part.size))
            continue
        if robust:
            factor = 1.4826 * float(np.median(np.abs(part)))
        else:
            dof = max(part.size * (1 - (4 / obj.size if share is None else share)), 1.0)
            factor = math.sqrt(float(np.sum(part**2)) / dof)
        scale.append(np.full(part.size, max(factor, 1e-300)))
    obj.sd = obj.sd * np.concatenate(scale)


def _best(obj, starts, loss, rounds: int = 6):
    """The lowest-cost local fit from `starts`. Fits that run out of evaluations (a narrow,
    curved valley they crawl along, as plateau data at low noise give) continue side by side
    in rounds of 400 evaluations, until the optimiser converges, a round lowers the cost by
    less than FLAT (at its minimum for the intervals: status 1, said in the message), or
    `rounds` are spent (status 0); a fit whose cost lies above the best converged one by more
    than its last drop times the rounds left is abandoned (it cannot overtake it). `obj`:
    an Objective or any objective local_fit takes (parameters.py, tissue.py)."""
    from .local import local_fit

    fits, failures = [], []
    for z0 in starts:
        try:
            z, c, res = local_fit(obj, z0, loss=loss)
        except SolverError as e:
            failures.append(str(e))
            continue
        fits.append([z, c, res, math.inf])  # z, cost, result, last drop
    for left in range(rounds, 0, -1):
        done = [f[1] for f in fits if f[2].status > 0]
        live = [f for f in fits if f[2].status == 0 and not (done and f[1] - min(done) > f[3] * left)]
        if not live:
            break
        for f in live:
            try:
                z2, c2, res2 = local_fit(obj, f[0], loss=loss, max_nfev=400)
            except SolverError:
                f[3] = 0.0
                continue
            f[3] = f[1] - c2
            if c2 < f[1]:
                f[0], f[1] = z2, c2
            if res2.status > 0:
                f[2] = res2
            elif f[3] < FLAT:
                f[2].status = 1
                f[2].message += (f" The last restart lowered the cost by {max(f[3], 0):.2g} (< {FLAT}): at its "
                                 "minimum for the intervals, the parameters moving along a flat valley.")
    ends = [(f[0], f[1]) for f in fits]
    best = min(fits, key=lambda f: f[1])[:3] if fits else None
    return (tuple(best) if best else None), failures, ends


def fit(radius: RadiusSeries, profile: VelocityProfile | None = None, *, outer_radius_um: float,
        intervals: bool = True, loss: str = "linear", derived: bool = True, params=None) -> FitResult:
    """Fit R0_um, sigma, lambda and T_s; see the module docstring and docs/fitting.md.
    `loss`: "linear" (least squares), or "soft_l1" / "cauchy" (robust to outliers).
    `intervals`: the parameters' profile likelihoods; `derived`: also those of tau, zeta/G
    and the viscous length (without them these are reported not identified).
    `params`: a Parameters (parameters.py; or an lmfit.Parameters) fixing, bounding or
    giving a prior to R0_um, sigma, lambda, T_s, and G_pa fixed or with a prior."""
    from scipy import stats

    from .intervals import profile_all, profile_at
    from .local import cost
    from .starts import grid_starts

    if loss not in ("linear", "soft_l1", "cauchy"):
        raise ValueError(f"loss = {loss!r}: expected linear, soft_l1 or cauchy")
    from .parameters import Constrained, specification

    check_against(radius, profile, outer_radius_um)
    spec = specification(params, outer_radius_um)
    data = Objective(radius, profile, outer_radius_um)
    n_free = len(spec.free)
    if data.size < n_free + 1:
        raise ValueError(f"fit: {data.size} data points for {n_free} free parameters: need at least {n_free + 1}")
    estimated = _uncertainties(data, radius, profile)
    obj = Constrained(data, spec)  # the data with the priors, bounds and fixed parameters

    def objective_cost(z):
        return cost(obj.residuals(z), loss)

    starts = grid_starts(data, objective_cost, spec=spec)
    if not starts:
        raise ValueError("fit: no point of the global grid (lambda x time scale, R0 and sigma solved linearly) "
                         "gives a wound with R0 > 0 inside the outer radius" + (
                             " with the fixed values and bounds given: the data cannot be described with them"
                             if spec.fixed or spec.bounds else ""))
    best, failures, ends = _best(obj, starts, loss)
    if best is None:
        raise ValueError("fit: the model could not be evaluated from any start: " + "; ".join(failures[:2]))
    z = best[0]
    if any(estimated):
        for _ in range(2):  # noise from the residuals, then refit with those weights
            _estimate_noise(data, z, estimated, loss != "linear", n_free / data.size)
            best, _, _ = _best(obj, [z], loss)
            z = best[0]
    z, chi2_cost, res = best  # residuals, Jacobian and chi^2 below at the point reported
    dof = max(obj.size - n_free, 1)  # the priors count as data
    threshold = float(stats.f.ppf(0.95, 1, dof)) if any(estimated) else float(stats.chi2.ppf(0.95, 1))
    residuals = data.residuals(z)
    jac = obj.jacobian(z)
    reasons = []
    optimizer = {"status": int(res.status), "message": str(res.message), "nfev": int(res.nfev)}
    if res.status <= 0:
        reasons.append(f"optimiser stopped without converging ({res.message})")
    flagged = np.flatnonzero(np.abs(residuals) > OUTLIER) if loss != "linear" else np.empty(0, int)
    chi2 = float(np.sum(np.delete(residuals, flagged) ** 2) + np.sum(obj.prior_residuals(z) ** 2))
    p_value = None if any(estimated) else float(stats.chi2.sf(chi2, max(dof - flagged.size, 1)))
    if p_value is not None and p_value < P_FAIL:
        reasons.append(f"chi^2 = {chi2:.4g} for {dof - flagged.size} degrees of freedom (p = {p_value:.2g}): "
                       "the model does not describe the data with the given noise")
    # lambda on its bound 0: its column is 0 (R depends on lambda^2); the others are judged alone
    free = [i for i in spec.free if not (i == 2 and z[2] <= 1e-8)]
    sv = np.linalg.svd(jac[:, free], compute_uv=False)
    cov_z = np.full((4, 4), np.nan)
    held = list(spec.fixed)
    cov_z[held, :], cov_z[:, held] = 0.0, 0.0  # no variance
    singular = not (sv.size == len(free) and sv[-1] > 1e-12 * sv[0])
    if not singular:
        try:
            cov_z[np.ix_(free, free)] = np.linalg.inv(jac[:, free].T @ jac[:, free])
        except np.linalg.LinAlgError:
            singular = True
    if singular:
        reasons.append(f"the Jacobian at the best point is singular: the data do not determine the {n_free} free parameters")
    theta = tuple(spec.fixed.get(i, v) for i, v in enumerate(from_z(z)))  # a fixed value as given, not exp(ln v)
    scale = np.array([theta[0], 1.0, 1.0, theta[3]])  # d theta / d z
    cov = cov_z * np.outer(scale, scale)
    with np.errstate(invalid="ignore"):
        se = np.sqrt(np.diag(cov))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(se, se)
    # other local optima (refitted at the final noise) that a profile may reach
    alternates = []
    for e, _ in ends:
        if all(np.max(np.abs(e - other)) > 1e-2 for other in [z] + [a for a, _ in alternates]):
            alternates.append((e, cost(obj.residuals(e), loss) - chi2_cost))
    profiles = profile_all(obj, z, chi2_cost, threshold, cov_z, loss, alternates) if intervals and not reasons else {}
    if profiles and derived:
        from .derived import derived_profiles

        profiles |= derived_profiles(obj, z, chi2_cost, threshold, loss, alternates, cov_z)
    if profiles:
        for i, v in spec.fixed.items():
            profiles[NAMES[i]] = Profile(v, v, False, [(v, 0.0)])
    reports = {name: ParameterReport(name, theta[i], float(se[i]), profiles.get(name), spec.describe(i))
               for i, name in enumerate(NAMES)}
    derived_p = {name: p for name, p in profiles.items() if name not in NAMES}
    data.residuals(z)  # inside_edge at the optimum
    radius_res = data.split(residuals * data.sd)[0]
    return FitResult(theta=theta, reports=reports, correlation=corr, chi2=chi2, threshold=threshold,
                     outer_radius_um=data.outer, residual_rms_um=float(np.sqrt(np.mean(radius_res**2))),
                     noise=(float(np.median(data.sd[:data.n_radius])),
                            float(np.median(data.sd[data.n_radius:])) if data.n_profile else None),
                     n_points=(data.n_radius, data.n_profile), has_profile=profile is not None,
                     evaluations=data.evaluations, G=spec.G, converged=not reasons, reasons=reasons,
                     optimizer=optimizer,
                     dof=dof, p_value=p_value, noise_given=not any(estimated), loss=loss,
                     outliers=_outliers(data, flagged, radius, profile), piv_at_edge=data.inside_edge,
                     derived_profiles=derived_p, plausibility=time_scale_warnings(theta, obj.outer, radius, profile),
                     points=data_points(data, z, flagged, radius, profile, estimated),
                     refit=partial(profile_at, obj, z, chi2_cost, loss=loss) if not reasons else None)


def _outliers(obj: Objective, flagged, radius: RadiusSeries, profile: VelocityProfile | None) -> dict:
    """Flagged points as rows of the input (1 = first row), and under "where" each as its
    file and file line when read from a file (data.where), else as its row."""
    rows = {"radius": [], "profile": []}
    for k in flagged:
        if k < obj.n_radius:
            rows["radius"].append(int(obj.order[k]))
        else:
            j = k - obj.n_radius
            for _, r, _, idx in obj.groups:
                if j < r.size:
                    rows["profile"].append(int(idx[j]))
                    break
                j -= r.size
    out = {key: sorted(k + 1 for k in v) for key, v in rows.items()}
    out["where"] = [where(data, key, k) for key, data in (("radius", radius), ("profile", profile))
                    for k in sorted(rows[key])]
    return out
