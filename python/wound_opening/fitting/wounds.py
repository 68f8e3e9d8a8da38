"""`fit_wounds`: several wounds cut in one tissue, fitted together. The material is shared,
the size of each cut is its own.

The material enters each wound's model (R0_k, sigma, lambda_k, T_k) through three numbers
shared by every wound of the tissue,

    l = lambda R0 = 2 sqrt(eta / zeta)  [um]     the viscous length
    sigma = tension / G                          the pre-stress
    zeta / G = 4 T / R0^2               [s/um^2] the friction time per area

(and eta / G = tau = lambda^2 T = l^2 (zeta/G) / 4 [s]), while the radius R0_k of each cut
and the outer radius of its tissue (given) are the wound's own:

    lambda_k = l / R0_k,    T_k = (zeta/G) R0_k^2 / 4.

A small wound (lambda_k large) opens in the viscous regime, on the time scale tau = eta/G
alone; a large one in the friction regime, on T_k: wounds of several sizes identify l and
zeta/G separately where one wound's radius identifies only their combination.

Coordinates of the optimiser: y = (l, sigma, ln zeta/G, ln R0_1, ..., ln R0_K), l >= 0.
Residuals: the wounds' Objective residuals, concatenated. Jacobian by the chain rule from each
wound's Objective.jacobian in z_k = (ln R0_k, sigma, lambda_k, ln T_k):

    d lambda_k / d l = 1 / R0_k,   d lambda_k / d ln R0_k = -lambda_k,
    d ln T_k / d ln zeta/G = 1,    d ln T_k / d ln R0_k = 2,   d ln R0_k / d ln R0_k = 1.

Stages, as for one wound (single.py): starts from each wound fitted alone (no intervals)
combined, and from a coarse grid in l; local fits (local.py); noise given or estimated per
data set of each wound; the verdict (optimiser, rank of the Jacobian, chi^2, the runs test of
each wound's series: gof.py); profile likelihood intervals of l, tension/G, zeta/G, eta/G
and every R0_k (wound_profiles.py, with intervals.py's walker).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._native import SolverError
from ..inputs.series import RadiusSeries, VelocityProfile, check_against
from ..results.export import data_points
from ..results.names import ETA, SHARED
from ..results.profiles import doubted
from ..results.result import ParameterReport
from ..results.wounds import TissueFitResult
from .gof import as_dicts, series_tests
from .local import cost
from .objective import Objective
from .optimum import profiled
from .parameters import G_NAME, Constrained, names, specification
from .plausibility import time_scale_warnings, tissue_intervals
from .recording import check_recording
from .single import fit
from .stages import check_loss, outliers, settle
from .tissue import SINGLE_ONLY, Tissue, TissueNuisances, tissue_coordinates
from .wound_profiles import EtaCoordinate, shared_profiles

__all__ = ["SINGLE_ONLY", "Wound", "fit_wounds", "tissue_coordinates"]

#: Points each wound needs: its start is a fit of its own four parameters (fitting.fit).
MIN_POINTS = 5


@dataclass(frozen=True)
class Wound:
    """One wound of the tissue: its radius series, optionally a PIV velocity profile, the
    outer radius of the tissue around it [um], and a name for messages and the result."""

    radius: RadiusSeries
    outer_radius_um: float
    profile: VelocityProfile | None = None
    name: str | None = None


def _wounds(experiments) -> list[Wound]:
    wounds = []
    for k, w in enumerate(experiments):
        if not isinstance(w, Wound):
            raise TypeError(
                f"fit_wounds: experiment {k + 1} is a {type(w).__name__}, expected a Wound"
            )
        wounds.append(
            w if w.name is not None else Wound(w.radius, w.outer_radius_um, w.profile, str(k + 1))
        )
    if not wounds:
        raise ValueError("fit_wounds: no wound given")
    names = [w.name for w in wounds]
    if len(set(names)) < len(names):
        raise ValueError(
            f"fit_wounds: wound names repeat ({', '.join(names)}): each wound needs its own"
        )
    for w in wounds:
        try:
            check_against(w.radius, w.profile, w.outer_radius_um)
            check_recording(w.radius, w.profile)  # a unit mistake, a closing wound
        except ValueError as e:
            raise ValueError(f"wound {w.name}: {e}") from None
        n = np.size(w.radius.radius_um) + (0 if w.profile is None else np.size(w.profile.r_um))
        if n < MIN_POINTS:
            raise ValueError(
                f"wound {w.name}: {n} data points: need at least {MIN_POINTS} per wound "
                "(its start is a fit of its own four parameters)"
            )
    return wounds


def _combine(tissue: Tissue, singles, cost, count: int = 3) -> list[np.ndarray]:
    """Starts: the single-wound estimates `singles` (theta or None per wound) combined, each
    wound's own material with every R0_k, and a grid of l (0 and 0.02 .. 50 times the median
    R0) with zeta/G from the wounds' opening time scales s_k = T_k (1 + lambda_k^2)
    = (zeta/G) (R0_k^2 + l^2) / 4; the combined start and the `count` best others by cost."""
    ok = [t for t in singles if t is not None]
    if not ok:
        raise ValueError("fit_wounds: no wound could be fitted alone to start from")
    sigma = float(np.median([t[1] for t in ok]))
    r0 = [
        t[0] if t is not None else float(np.min(p.radius)) / (1 + sigma / 6)
        for t, p in zip(singles, tissue.inner.parts)
    ]
    ln_r0 = [math.log(r) for r in r0] + list(tissue.inner.nuisance_start())
    zg = [4 * t[3] / t[0] ** 2 for t in ok]
    ls = [t[2] * t[0] for t in ok]
    scales = [(t[0], t[3] * (1 + t[2] ** 2)) for t in ok]
    combined = np.array([float(np.median(ls)), sigma, float(np.median(np.log(zg)))] + ln_r0)
    candidates = [np.array([l, t[1], math.log(z)] + ln_r0) for l, t, z in zip(ls, ok, zg)]
    for l in [0.0] + list(np.geomspace(0.02, 50, 12) * float(np.median(r0))):
        ln_zg = float(np.mean([math.log(4 * s / (r**2 + l**2)) for r, s in scales]))
        candidates.append(np.array([l, sigma, ln_zg] + ln_r0))
    lower, upper = tissue.bounds()
    scored = []
    for y in candidates:
        y = np.clip(y, lower, upper)
        for i, v in tissue.fixed.items():
            y[i] = v
        try:
            c = cost(y)
        except SolverError:
            continue
        if math.isfinite(c):
            scored.append((c, y))
    scored.sort(key=lambda s: s[0])
    chosen = [np.clip(combined, lower, upper)]
    for i, v in tissue.fixed.items():
        chosen[0][i] = v
    for _, y in scored:
        if all(abs(y[0] - c[0]) > 0.2 * max(c[0], 1e-3) or abs(y[2] - c[2]) > 0.2 for c in chosen):
            chosen.append(y)
        if len(chosen) == count + 1:
            break
    return chosen


def fit_wounds(
    experiments,
    *,
    intervals: bool = True,
    loss: str = "linear",
    params=None,
):
    """Fit several wounds of one tissue: shared l (viscous length, um), sigma = tension/G,
    zeta/G (and eta/G) with each wound's R0; see the module docstring and docs/fitting.md.
    `experiments`: Wound objects. `loss` and the noise of each data set as in `fit`.
    `params`: a Parameters (parameters.py) fixing, bounding or giving a prior to
    viscous_length_um, tension_over_G, zeta_over_G_s_per_um2, R0_um[NAME], and G_pa fixed
    or with a prior for the absolute eta, zeta and tension (parameters.py, read against
    the tissue's coordinates: tissue_coordinates).
    Returns a TissueFitResult."""
    check_loss(loss)
    wounds = _wounds(experiments)
    nuisances = _nuisances(wounds, params)
    parts = [
        Objective(w.radius, w.profile, w.outer_radius_um, nuisances.of(w.name)) for w in wounds
    ]
    tissue = Tissue(parts, [w.name for w in wounds], nuisances)
    spec = specification(params, tissue.coordinates)
    obj = Constrained(tissue, spec)
    cuts = np.cumsum([0] + [p.size for p in parts])

    def runs(residuals):
        return [
            t
            for k, (p, w) in enumerate(zip(parts, wounds))
            for t in series_tests(p, residuals[cuts[k] : cuts[k + 1]], f"wound {w.name}: ")
        ]

    def settle_at(starts):
        return settle(obj, parts, lambda k, y: tissue.z(y, k), starts, loss, runs, "fit_wounds")

    def profile_all(optimum, judged) -> dict:
        return shared_profiles(optimum) if intervals and not judged.reasons else {}

    # a walk that finds a better optimum settles the fit again from it (optimum.profiled)
    optimum, judged, profiles = profiled(settle_at, profile_all, _starts(obj, wounds, loss))
    doubts = [f"wound {w.name}: {m}" for w in wounds for m in getattr(w.radius, "warnings", ())]
    profiles = doubted(profiles, doubts)  # one wound's doubt biases the shared values too
    y, cov = optimum.z, judged.reported  # the coordinates on a bound held (stages.reported_cov)
    reasons, threshold, flagged = judged.reasons, judged.threshold, judged.flagged
    residuals = tissue.residuals(y)
    noise_given = not any(any(p.estimated) for p in parts)
    dof = max(obj.size - len(obj.free), 1)
    # standard errors in each quantity's own units: d quantity / d y_i
    own = np.array([c.d_own(v) for c, v in zip(tissue.coordinates, y)])
    with np.errstate(invalid="ignore"):
        se = np.sqrt(np.diag(cov)) * own
    eta = y[0] ** 2 * math.exp(y[2]) / 4
    se_eta = math.nan
    if y[0] > 0 and np.all(np.isfinite(cov[np.ix_([0, 2], [0, 2])])):
        g = EtaCoordinate.gradient(y)
        se_eta = eta * math.sqrt(max(float(g @ cov @ g), 0.0))
    shared = {
        name: ParameterReport(
            name,
            float(spec.fixed.get(i, v if i != 2 else math.exp(v))),  # a fixed value as given
            float(se[i]),
            profiles.get(name),
            spec.describe(i),
        )
        for i, (name, v) in enumerate(zip(SHARED, y[:3]))
    }
    shared[ETA] = ParameterReport(ETA, eta, se_eta, profiles.get(ETA))
    r0 = [
        ParameterReport(
            "R0_um",
            float(spec.fixed.get(3 + k, math.exp(y[3 + k]))),
            float(se[3 + k]),
            profiles.get(("R0_um", k)),
            spec.describe(3 + k),
        )
        for k in range(len(parts))
    ]
    nuisance_reports = {
        c.name: ParameterReport(c.name, float(spec.fixed.get(i, y[i])), float(se[i]), None,
                                spec.describe(i))
        for i, c in enumerate(tissue.coordinates)
        if i >= 3 + len(parts)
    }  # fmt: skip
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(np.sqrt(np.diag(cov)), np.sqrt(np.diag(cov)))
    start = 0
    warnings = list(judged.warnings)
    wound_rows = []
    for k, (p, w) in enumerate(zip(parts, wounds)):
        part = residuals[start : start + p.size]
        mine = flagged[(flagged >= start) & (flagged < start + p.size)] - start
        start += p.size
        p.residuals(tissue.z(y, k))  # inside_edge at the optimum
        theta = tissue.theta(y, k)
        warnings += [
            f"wound {w.name}: {m}"
            for m in check_recording(w.radius, w.profile)
            + time_scale_warnings(
                theta, p.outer, w.radius, w.profile, tissue_intervals(shared, r0[k], profiles)
            )
        ]
        radius_res = p.split(part * p.sd)[0]
        wound_rows.append(
            {
                "name": w.name,
                "theta": theta,
                "outer_radius_um": p.outer,
                "n_points": (p.n_radius, p.n_profile),
                "chi2": float(np.sum(np.delete(part, mine) ** 2)),
                "noise": (
                    float(np.median(p.sd[: p.n_radius])),
                    float(np.median(p.sd[p.n_radius :])) if p.n_profile else None,
                ),
                "residual_rms_um": float(np.sqrt(np.mean(radius_res**2))),
                "radius_floor_um": p.radius_floor if p.floor_reached() else None,
                "radius_floor_said": p.radius_floor_said,
                "outliers": outliers(p, mine),
                "piv_vectors_at_edge": p.inside_edge,
                "points": data_points(p, tissue.z(y, k), mine),
            }
        )
    return TissueFitResult(
        shared=shared,
        r0=r0,
        wounds=wound_rows,
        nuisances=nuisance_reports,
        correlation=corr,
        chi2=judged.chi2,
        dof=dof,
        p_value=judged.p_value,
        threshold=threshold,
        noise_given=noise_given,
        loss=loss,
        converged=not reasons,
        reasons=reasons,
        optimizer=judged.optimizer,
        evaluations=tissue.evaluations,
        plausibility=warnings,
        residual_runs=as_dicts(judged.runs),
        doubts=doubts,
        G=spec.G,
    )


def _nuisances(wounds, params) -> TissueNuisances:
    """The nuisances `params` names (tissue.py): a name of every possible nuisance's
    coordinate (an alias too) that params gives joins the fit."""
    every = TissueNuisances.every([w.name for w in wounds], [w.profile is not None for w in wounds])
    full = tissue_coordinates([w.name for w in wounds], [w.outer_radius_um for w in wounds], every)
    named = set()
    for name in names(params) - {None, G_NAME}:
        try:
            named.add(full[full.index(name)].name)
        except ValueError:
            pass  # refused by the specification, naming what is accepted
    return TissueNuisances(
        "outline_offset_um" in named,
        tuple(w for w in every.cut if f"cut_s[{w}]" in named),
        tuple(w for w in every.gain if f"piv_gain[{w}]" in named),
    )


def _starts(tissue: Constrained, wounds, loss: str) -> list:
    """Starts from the wounds fitted alone (fit without intervals), combined (_combine)."""
    singles = []
    for w in wounds:
        try:
            singles.append(
                fit(
                    w.radius,
                    w.profile,
                    outer_radius_um=w.outer_radius_um,
                    intervals=False,
                    loss=loss,
                ).theta
            )
        except (ValueError, SolverError):
            singles.append(None)

    def tissue_cost(y):
        return cost(tissue.residuals(y), loss)

    return _combine(tissue, singles, tissue_cost)
