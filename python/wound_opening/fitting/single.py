"""`fit`: weighted least squares of the model on a wound radius series and/or a PIV velocity
profile, for R0_um, sigma, lambda (>= 0) and T_s, with profile-likelihood intervals.

1. Global stage (starts.py): a lambda x time-scale grid with R0 and sigma solved linearly at
   each point; the four best distinct points start local fits.
2. Local fits (local.py): scipy.optimize.least_squares with the objective's Jacobian
   (objective.py), tolerances 1e-12; the best of the starts is kept.
3. Noise: given (one level or per point), or estimated per data set from its residuals
   (degrees of freedom shared in proportion to the points; 1.4826 x the median absolute
   residual with a robust loss); with an estimated noise the intervals use the F(1, dof)
   quantile instead of chi^2(1) (3.84).
4. Intervals: profile likelihood (optimum.py, intervals.py), also of tau, zeta/G and the
   viscous length (derived.py); standard errors from the Jacobian.
5. Verdict: converged only if the optimiser reports convergence, the Jacobian has full rank,
   with the noise given chi^2 is consistent with its degrees of freedom (p >= 1e-6), and the
   signs of each series' residuals show no systematic misfit (runs test, gof.py).

`params` (parameters.py): parameters held fixed, bounded or given a Gaussian prior, and G
for the absolute material values (material.py). Fixed parameters leave every stage; each
prior is one more residual; the degrees of freedom are n + priors - free parameters.
"""

from __future__ import annotations

import numpy as np

from ..inputs.series import RadiusSeries, VelocityProfile, check_against
from ..results.export import data_points
from ..results.profiles import doubted
from ..results.result import FitResult, ParameterReport
from .bounds import thresholds as bound_thresholds
from .derived import derived_profiles
from .gof import as_dicts, series_tests
from .local import cost
from .objective import NUISANCES, Objective, from_z, wound_coordinates
from .optimum import profiled
from .parameters import Constrained, names, specification
from .plausibility import intervals_of, time_scale_warnings
from .recording import check_recording
from .stages import check_loss, outliers, settle
from .starts import grid_starts


def fit(
    radius: RadiusSeries,
    profile: VelocityProfile | None = None,
    *,
    outer_radius_um: float,
    intervals: bool = True,
    loss: str = "linear",
    derived: bool = True,
    params=None,
) -> FitResult:
    """Fit R0_um, sigma, lambda and T_s; see the module docstring and docs/fitting.md.
    `loss`: "linear" (least squares), or "soft_l1" / "cauchy" (robust to outliers).
    `intervals`: the parameters' profile likelihoods; `derived`: also those of tau, zeta/G
    and the viscous length (without them these are reported not identified).
    `params`: a Parameters (parameters.py; or an lmfit.Parameters) fixing, bounding or
    giving a prior to R0_um, sigma, lambda, T_s, and G_pa fixed or with a prior; a nuisance
    it names (objective.NUISANCES: outline_offset_um) joins the fit, given or fitted."""
    check_loss(loss)
    check_against(radius, profile, outer_radius_um)
    recording = check_recording(radius, profile)  # refuses a unit mistake, a closing wound
    nuisances = [n for n in NUISANCES if n in names(params)]
    spec = specification(params, wound_coordinates(outer_radius_um, nuisances))
    data = Objective(radius, profile, outer_radius_um, nuisances)
    n_free = len(spec.free)
    if data.size < n_free + 1:
        raise ValueError(
            f"fit: {data.size} data points for {n_free} free parameters: need at least {n_free + 1}"
        )
    obj = Constrained(data, spec)  # the data with the priors, bounds and fixed parameters
    coordinates = data.coordinates

    def settle_at(starts):
        return settle(
            obj,
            [data],
            lambda k, z: z,
            starts,
            loss,
            lambda residuals: series_tests(data, residuals),
            "fit",
            f"the {n_free} free parameters",
        )

    def profile_all(optimum, judged) -> dict:
        if not intervals or judged.reasons:
            return {}
        dof = max(obj.size - n_free, 1)
        near, found = bound_thresholds(
            obj,
            optimum.z,
            optimum.chi2,
            loss,
            not any(data.estimated),
            dof,
            optimum.alternates,
            restart=optimum.restart,  # a fit of its below the optimum settles it again
        )
        optimum.alternates += found  # a valley at lambda ~ 0 the starts did not end in
        optimum.thresholds = near
        # lambda first: its interval spares the others' valley search a regime (valleys.py)
        first = [n for n in coordinates.names if n == "lambda"]
        walked = {name: optimum.profile(optimum.target(name)) for name in first}
        profiles = {
            name: walked.get(name) or optimum.profile(optimum.target(name))
            for name in coordinates.names
        }
        if derived:
            profiles |= derived_profiles(optimum)
        return profiles

    # a walk that finds a better optimum settles the fit again from it (optimum.profiled)
    optimum, judged, profiles = profiled(settle_at, profile_all, _starts(obj, data, spec, loss))
    doubts = list(getattr(radius, "warnings", ()) or ())
    profiles = doubted(profiles, doubts)  # a reader's warning: no interval vouched for
    z = optimum.z
    cov_z = judged.reported  # the coordinates on a bound held (stages.reported_cov)
    own = [spec.fixed.get(i, v) for i, v in enumerate(from_z(z) + coordinates.own(z)[4:])]
    theta = tuple(own[:4])  # a fixed value as given, not exp(ln v)
    scale = np.array([c.d_own(v) for c, v in zip(coordinates, z)])  # d value / d z
    cov = cov_z * np.outer(scale, scale)
    with np.errstate(invalid="ignore"):
        se = np.sqrt(np.diag(cov))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(se, se)
    reports = {
        name: ParameterReport(name, own[i], float(se[i]), profiles.get(name), spec.describe(i))
        for i, name in enumerate(coordinates.names)
    }
    residuals = data.residuals(z)  # and inside_edge at the optimum
    radius_res = data.split(residuals * data.sd)[0]
    return FitResult(
        theta=theta,
        reports=reports,
        correlation=corr,
        chi2=judged.chi2,
        threshold=judged.threshold,
        outer_radius_um=data.outer,
        residual_rms_um=float(np.sqrt(np.mean(radius_res**2))),
        noise=(
            float(np.median(data.sd[: data.n_radius])),
            float(np.median(data.sd[data.n_radius :])) if data.n_profile else None,
        ),
        n_points=(data.n_radius, data.n_profile),
        has_profile=profile is not None,
        evaluations=data.evaluations,
        G=spec.G,
        converged=not judged.reasons,
        reasons=judged.reasons,
        optimizer=judged.optimizer,
        dof=max(obj.size - n_free, 1),
        p_value=judged.p_value,
        noise_given=not any(data.estimated),
        loss=loss,
        outliers=outliers(data, judged.flagged),
        piv_at_edge=data.inside_edge,
        derived_profiles={n: p for n, p in profiles.items() if n not in coordinates.names},
        plausibility=recording
        + list(judged.warnings)
        + time_scale_warnings(
            theta,
            data.outer,
            radius,
            profile,
            intervals_of(reports, profiles) if profiles else None,
        ),
        points=data_points(data, z, judged.flagged),
        radius_floor_um=data.radius_floor if data.floor_reached() else None,
        radius_floor_said=data.radius_floor_said,
        residual_runs=as_dicts(judged.runs),
        doubts=doubts,
        refit=optimum.profile_at if not judged.reasons else None,
    )


def _starts(obj: Constrained, data: Objective, spec, loss: str) -> list:
    """The global grid's starts (starts.py), or ValueError where none describes the data."""

    def objective_cost(z):
        return cost(obj.residuals(z), loss)

    starts = grid_starts(data, objective_cost, spec=spec)
    if not starts:
        raise ValueError(
            "fit: no point of the global grid (lambda x time scale, R0 and sigma solved linearly) "
            "gives a wound with R0 > 0 inside the outer radius"
            + (
                " with the fixed values and bounds given: the data cannot be described with them"
                if spec.fixed or spec.bounds
                else ""
            )
        )
    return starts
