"""The stages of a fit, shared by one wound (single.py) and several (wounds.py): the best of
local fits from several starts continued side by side (`best_of`), the noise estimated from
the residuals and the fit repeated at it (`refit_at_noise`), the verdict (optimiser, chi^2
and its p-value, systematic residuals by the runs test of gof.py, rank of the Jacobian and
the covariance: `verdict`), the other local optima
a profile may reach (`alternates`) and the flagged points as input rows (`outliers`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special

from .._native import SolverError
from ..inputs.series import where
from ..results.outcome import CHI2_FAIL_P, CHI2_WARN_P
from .bounds import regular
from .gof import judge_series
from .local import cost, local_fit
from .objective import Objective
from .problem import Problem

#: A cost drop this small (chi^2 units) moves a 95 % interval end (chi^2 + 3.84) negligibly:
#: a fit that ran out of evaluations on a flat valley is converged if a restart drops less.
FLAT = 0.01
#: |residual| / noise above which a point is flagged as down-weighted by a robust loss.
OUTLIER = 3.0
LOSSES = ("linear", "soft_l1", "cauchy")


def check_loss(loss: str) -> None:
    if loss not in LOSSES:
        raise ValueError(f"loss = {loss!r}: expected linear, soft_l1 or cauchy")


def best_of(obj, starts, loss, rounds: int = 6):
    """The lowest-cost local fit from `starts`. Fits that run out of evaluations (a narrow,
    curved valley they crawl along, as plateau data at low noise give) continue side by side
    in rounds of 400 evaluations, until the optimiser converges, a round lowers the cost by
    less than FLAT (at its minimum for the intervals: status 1, said in the message), or
    `rounds` are spent (status 0). Each round continues the fits lowest cost first and
    abandons a fit whose cost lies above the best finished one by more than its last drop
    times the rounds left (it cannot overtake it) or by less than FLAT (`_worth`). `obj`:
    a Problem (problem.py)."""
    fits, failures = [], []
    for z0 in starts:
        try:
            z, c, res = local_fit(obj, z0, loss=loss)
        except SolverError as e:
            failures.append(str(e))
            continue
        fits.append([z, c, res, math.inf])  # z, cost, result, last drop
    for left in range(rounds, 0, -1):
        live = [f for f in fits if f[2].status == 0]
        if not any(_worth(f, fits, left) for f in live):
            break
        for f in sorted(live, key=lambda f: f[1]):  # the lowest first
            if not _worth(f, fits, left):
                continue
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
                f[2].message += (
                    f" The last restart lowered the cost by {max(f[3], 0):.2g} (< {FLAT}): at its "
                    "minimum for the intervals, the parameters moving along a flat valley."
                )
    ends = [(f[0], f[1]) for f in fits]
    best = min(fits, key=lambda f: f[1])[:3] if fits else None
    return (tuple(best) if best else None), failures, ends


def _worth(f, fits, left: int) -> bool:
    """Whether the live fit f ([z, cost, result, last drop]) is worth another round: not if
    its cost lies above the best finished one (converged, or at its minimum by FLAT) by more
    than its last drop times the `left` rounds (it cannot overtake it), nor by less than
    FLAT (the same flat valley, reached lower: a round of it would move the minimum by less
    than FLAT, as one of the finished fit did)."""
    done = [g[1] for g in fits if g[2].status > 0]
    if not done:
        return True
    gap = f[1] - min(done)
    return not (gap > f[3] * left or 0 <= gap < FLAT)


def refit_at_noise(problem: Problem, parts, z_of, best, loss: str, share: float):
    """Noise from the residuals, then the fit again with those weights, twice: each
    Objective of `parts` scales its estimated uncertainties at its coordinates `z_of(k, z)`."""
    z = best[0]
    for _ in range(2):
        for k, part in enumerate(parts):
            part.estimate_noise(z_of(k, z), loss != "linear", share)
        best, _, _ = best_of(problem, [z], loss)
        z = best[0]
    return best


@dataclass
class Verdict:
    """Whether a fit stands: `reasons` it does not (empty: converged), chi^2 without the
    flagged points (plus `extra_chi2`), its p-value (None with an estimated noise), the
    threshold of delta chi^2 for 95 % intervals, the covariance of the coordinates
    (nan where the Jacobian does not determine them), the runs tests of the series
    (gof.py) and the warnings they give."""

    reasons: list
    optimizer: dict
    flagged: np.ndarray
    chi2: float
    p_value: float | None
    threshold: float
    cov: np.ndarray
    runs: tuple = ()
    warnings: tuple = ()
    #: The covariance the standard errors are reported from (`reported_cov`): `cov` with
    #: the coordinates that sit on a bound held there.
    reported: np.ndarray | None = None


#: A coordinate this close to a finite bound (relative to its range, or to 1 where the
#: other side is open) sits on it.
ON_BOUND = 1e-6


def on_bound(problem: Problem, z, columns) -> list:
    """The coordinates of `columns` that sit on a finite bound of `problem` at z."""
    lower, upper = problem.bounds()
    out = []
    for i in columns:
        lo, hi = float(lower[i]), float(upper[i])
        span = hi - lo if math.isfinite(hi - lo) else 1.0 + abs(float(z[i]))
        if (math.isfinite(lo) and z[i] - lo <= ON_BOUND * span) or (
            math.isfinite(hi) and hi - z[i] <= ON_BOUND * span
        ):
            out.append(i)
    return out


def reported_cov(jac, free, pinned, cov) -> np.ndarray:
    """The covariance of the standard errors: (J^T J)^-1 over the free columns less those on
    a bound (`pinned`), rows and columns of the pinned nan. A coordinate on its bound has
    no symmetric error, and where its column is nearly a combination of the others (the
    cut time against R0 and sigma when the opening is one slow exponential: a shift in time
    is a change of amplitude) keeping it makes the others' errors 1e5 times their profile
    intervals; held, they are the curvature's along the bound. `cov` when none is pinned or
    the rest is singular."""
    kept = [i for i in free if i not in pinned]
    if not pinned or not kept:
        return cov
    out = covariance(jac, kept)
    return cov if out is None else out


def covariance(jac, columns) -> np.ndarray | None:
    """(J^T J)^-1 over `columns`, nan in the other rows and columns; None where J's columns
    are singular (smallest singular value at most 1e-12 of the largest)."""
    sv = np.linalg.svd(jac[:, columns], compute_uv=False)
    if not (sv.size == len(columns) and sv[-1] > 1e-12 * sv[0]):
        return None
    n = jac.shape[1]
    out = np.full((n, n), np.nan)
    try:
        out[np.ix_(columns, columns)] = np.linalg.inv(jac[:, columns].T @ jac[:, columns])
    except np.linalg.LinAlgError:
        return None
    return out


def verdict(
    residuals,
    jac,
    free,
    res,
    *,
    dof: int,
    noise_given: bool,
    loss: str,
    extra_chi2: float = 0.0,
    what: str = "the parameters",
    runs=(),
) -> Verdict:
    """The verdict at the best point: `residuals` and `jac` there, `free` the columns judged
    (a coordinate on a bound where its column vanishes left out), `res` the optimiser's
    result; `what` the singular Jacobian leaves undetermined; `runs` the runs tests of the
    series (gof.series_tests: systematic residuals fail the fit or warn, whether the noise
    is given or estimated)."""
    threshold = regular(noise_given, dof)
    optimizer = {"status": int(res.status), "message": str(res.message), "nfev": int(res.nfev)}
    reasons = [] if res.status > 0 else [f"optimiser stopped without converging ({res.message})"]
    flagged = np.flatnonzero(np.abs(residuals) > OUTLIER) if loss != "linear" else np.empty(0, int)
    chi2 = float(np.sum(np.delete(residuals, flagged) ** 2) + extra_chi2)
    p_value = float(special.chdtrc(max(dof - flagged.size, 1), chi2)) if noise_given else None
    if p_value is not None and p_value < CHI2_FAIL_P:
        reasons.append(
            f"chi^2 = {chi2:.4g} for {dof - flagged.size} degrees of freedom (p = {p_value:.2g}): "
            "the model does not describe the data with the given noise"
        )
    systematic, warnings = judge_series(runs)
    reasons += systematic
    cov = covariance(jac, free)
    if cov is None:
        cov = np.full((jac.shape[1],) * 2, np.nan)
        reasons.append(
            f"the Jacobian at the best point is singular: the data do not determine {what}"
        )
    return Verdict(
        reasons, optimizer, flagged, chi2, p_value, threshold, cov, tuple(runs), tuple(warnings)
    )


def field_test(part: Objective, residuals, share: float) -> tuple[list, list]:
    """(reasons the fit fails, warnings) from the PIV profile's own chi^2, where its noise
    comes with the data (the rings' covariance or scatter, or a given noise): the sum of its
    (whitened) residuals squared against chi^2 with n (1 - share) degrees of freedom, `share`
    the fraction of the data the parameters take. A failing field is named, whatever the
    radius series does: the vectors are then not the model's flow at these parameters."""
    if not part.groups or part.estimated[1]:
        return [], []
    res = part.split(np.asarray(residuals, float))[1]
    dof = max(res.size * (1 - share), 1.0)
    chi2 = float(np.sum(res**2))
    p = float(special.chdtrc(dof, chi2))
    if p >= CHI2_WARN_P:
        return [], []
    said = (
        f"the PIV field disagrees with the model: chi^2 = {chi2:.4g} for {dof:.0f} degrees "
        f"of freedom of its {res.size} points (p = {p:.2g}); the vectors are not the model's "
        "flow at the fitted parameters: a wrong centre (--centre-um), windows that straddle "
        "the wound (--piv-window), a unit or frame mistake (--piv-units, --frame-interval-s), "
        "or a tissue the model does not describe"
    )
    return ([said], []) if p < CHI2_FAIL_P else ([], [said])


def alternates(problem: Problem, z, ends, chi2_min: float, loss: str) -> list:
    """Other local optima among the fits' ends (z, delta chi^2 refitted at the final noise),
    more than 1e-2 apart in every coordinate: a profile may reach them."""
    out = []
    for e, _ in ends:
        if all(np.max(np.abs(e - other)) > 1e-2 for other in [z] + [a for a, _ in out]):
            out.append((e, cost(problem.residuals(e), loss) - chi2_min))
    return out


def outliers(obj: Objective, flagged) -> dict:
    """Flagged points as rows of the input (1 = first row), and under "where" each as its
    file and file line when read from a file (inputs.series.where), else as its row."""
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
    out["where"] = [
        where(data, key, k)
        for key, data in zip(("radius", "profile"), obj.inputs)
        for k in sorted(rows[key])
    ]
    return out


def settle(obj, parts, z_of, starts, loss: str, runs, who: str, what: str = "the parameters"):
    """From `starts` to the optimum, one wound's or several's: the best local fit
    (`best_of`), refitted at the estimated noise where any of the Objectives `parts` has its
    noise estimated (`refit_at_noise`, at coordinates `z_of(k, z)`); the verdict at it
    (`verdict`: the problem's vanishing columns left out, the priors counted as data,
    `runs(residuals)` the series' runs tests); the covariance with the held coordinates'
    rows and columns 0; the other local optima (`alternates`). Returns (Optimum, Verdict).
    `who` names the fit in a refusal, `what` what a singular Jacobian leaves undetermined."""
    from .optimum import Optimum

    best, failures, ends = best_of(obj, starts, loss)
    if best is None:
        raise ValueError(
            f"{who}: the model could not be evaluated from any start: " + "; ".join(failures[:2])
        )
    if any(any(p.estimated) for p in parts):
        best = refit_at_noise(obj, parts, z_of, best, loss, len(obj.free) / obj.inner.size)
    z, chi2, res = best
    residuals = obj.inner.residuals(z)
    jac = obj.jacobian(z)
    free = [i for i in obj.free if i not in obj.vanishing(z)]
    judged = verdict(
        residuals,
        jac,
        free,
        res,
        dof=max(obj.size - len(obj.free), 1),
        noise_given=not any(any(p.estimated) for p in parts),
        loss=loss,
        extra_chi2=float(np.sum(obj.prior_residuals(z) ** 2)),
        what=what,
        runs=runs(residuals),
    )
    for k, part in enumerate(parts):
        failed, warned = field_test(part, part.residuals(z_of(k, z)), len(obj.free) / obj.size)
        judged.reasons += failed
        judged.warnings += tuple(warned)
    held = list(obj.fixed)
    judged.cov[held, :], judged.cov[:, held] = 0.0, 0.0  # no variance
    judged.reported = reported_cov(jac, free, on_bound(obj, z, free), judged.cov)
    judged.reported[held, :], judged.reported[:, held] = 0.0, 0.0
    others = alternates(obj, z, ends, chi2, loss)
    return Optimum(obj, z, chi2, loss, judged.threshold, judged.cov, others), judged
