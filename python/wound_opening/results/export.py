"""A fit's numbers for reuse: the data with the model, residuals and flags, and the fitted
curve on a fine grid, as tables whose column names carry their units.

    FitResult.tables()       {"radius": ..., "curve": ..., "profile": ..., "profile_curve": ...}
    FitResult.export(stem)   stem_radius.csv, stem_curve.csv (+ stem_profile.csv,
    stem_profile_curve.csv)

radius (one row per radius in the input's order):
    row                      1 = the first data row as given
    file_line                the line of the file it was read from (when read from a file)
    time_s, radius_um        the data, in s since the cut and um
    sd_um                    its standard deviation: given, or estimated from the residuals
    model_radius_um          the fitted model at that time
    residual_um              radius_um - model_radius_um
    normalised_residual      residual_um / sd_um (dimensionless)
    flagged                  down-weighted by a robust loss: |normalised_residual| > 3
profile (PIV): the same with r_um, velocity_um_s, sd_um_s, model_velocity_um_s, residual_um_s.
curve: time_s, radius_um, edge_velocity_um_s of the fitted model at 0 and on a grid uniform
    in log time from a tenth of the first sampled time to the last one, and uniform in time
    (so the curve is smooth on either time axis).
profile_curve: time_s, r_um, velocity_um_s of the model at each PIV time, from the model's
    wound edge to the largest distance measured.

The CSV files hold every number at Python's shortest round-trip precision (read back, they
give the same doubles).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..model import simulate

#: Points of each grid of the curves.
CURVE_POINTS = 200


def data_points(obj, z, flagged) -> dict:
    """The data (`obj.inputs`) in the input's order with the model of the Objective `obj` at
    z, the per-point noise used and the flags (objective indices `flagged`): {"radius":
    columns, "profile": columns or None, "noise_estimated": (radius, profile) whether each
    noise was estimated from the residuals}."""
    radius, profile = obj.inputs
    estimated = obj.estimated
    model = obj.model(z)
    mask = np.zeros(obj.size, bool)
    mask[np.asarray(flagged, int)] = True
    n = obj.n_radius
    back = np.empty(n, int)
    back[obj.order] = np.arange(n)
    out = {
        "radius": _columns(
            radius,
            np.asarray(radius.times_s, float),
            {},
            np.asarray(radius.radius_um, float),
            model[:n][back],
            obj.sd[:n][back],
            mask[:n][back],
            ("radius_um", "sd_um", "model_radius_um", "residual_um"),
        ),
        "profile": None,
        "noise_estimated": tuple(bool(e) for e in estimated),
    }
    if profile is not None:
        idx = np.concatenate([g[3] for g in obj.groups])
        back = np.empty(idx.size, int)
        back[idx] = np.arange(idx.size)
        out["profile"] = _columns(
            profile,
            np.asarray(profile.times_s, float),
            {"r_um": np.asarray(profile.r_um, float)},
            np.asarray(profile.velocity_um_s, float),
            model[n:][back],
            obj.sd[n:][back],
            mask[n:][back],
            ("velocity_um_s", "sd_um_s", "model_velocity_um_s", "residual_um_s"),
        )
    return out


def _columns(data, t, extra, y, model, sd, flagged, names) -> dict:
    value, sd_name, model_name, res_name = names
    lines = getattr(data, "lines", None)
    cols = {"row": np.arange(1, t.size + 1)}
    if lines is not None:
        cols["file_line"] = np.asarray(lines, int)
    residual = y - model
    return (
        cols
        | {"time_s": t}
        | extra
        | {
            value: y,
            sd_name: sd,
            model_name: model,
            res_name: residual,
            "normalised_residual": residual / sd,
            "flagged": flagged,
        }
    )


def curve_times(times_s, points: int = CURVE_POINTS) -> np.ndarray:
    """0, a log-uniform grid from a tenth of the first positive time to the last, and a
    uniform one to the last: a smooth curve on a log or a linear time axis."""
    t = np.asarray(times_s, dtype=float)
    last = float(t.max()) if t.size and t.max() > 0 else 1.0
    first = float(t[t > 0].min()) if np.any(t > 0) else last / 100
    return np.unique(
        np.concatenate(
            [[0.0], np.geomspace(first / 10, last, points), np.linspace(0, last, points)]
        )
    )


def nuisance(result, name: str) -> float:
    """The estimate of a nuisance of the fit (the cut on the data's clock, the outline's
    offset), 0 where the fit has none."""
    rep = getattr(result, "reports", {}).get(name)
    return 0.0 if rep is None else float(rep.estimate)


def tables(result, stopped: bool = False) -> dict:
    """pandas DataFrames of the fit (module docstring); profile tables only with PIV data.
    The curve is on the data's clock (the cut at cut_s) with the outline's offset. A fit that
    did not converge has no fitted curve: ValueError with its reasons; `stopped`: the curve
    where it stopped (the figure of a failed fit)."""
    import pandas as pd

    if not (result.converged or stopped):
        raise ValueError(
            "the fit did not converge (" + "; ".join(result.reasons) + "): nothing to export"
        )
    R0, sigma, lam, T = result.theta[:4]
    cut, offset = nuisance(result, "cut_s"), nuisance(result, "outline_offset_um")
    params = dict(lam=lam, sigma=sigma, R0_um=R0, T_s=T, outer_radius_um=result.outer_radius_um)
    radius = result.points["radius"]
    sim = simulate(curve_times(np.asarray(radius["time_s"], float) - cut), **params)
    out = {
        "radius": pd.DataFrame(radius),
        "curve": pd.DataFrame(
            {
                "time_s": sim.times_s + cut,
                "radius_um": sim.radius_um + offset,
                "edge_velocity_um_s": sim.edge_velocity_um_s,
            }
        ),
    }
    profile = result.points.get("profile")
    if profile is not None:
        out["profile"] = pd.DataFrame(profile)
        rows = []
        for time in np.unique(profile["time_s"]):
            edge = float(simulate([time - cut], **params).radius_um[0])
            far = max(float(np.max(profile["r_um"][profile["time_s"] == time])), 1.01 * edge)
            r = np.linspace(
                edge * (1 + 1e-9), min(far, result.outer_radius_um * (1 - 1e-9)), CURVE_POINTS
            )
            v = simulate([time - cut], radii_um=r, **params).velocity_um_s[0]
            rows.append(pd.DataFrame({"time_s": time, "r_um": r, "velocity_um_s": v}))
        out["profile_curve"] = pd.concat(rows, ignore_index=True)
    return out


def export(result, stem) -> list[Path]:
    """Write tables(result) to stem_radius.csv, stem_curve.csv (and stem_profile.csv,
    stem_profile_curve.csv); a trailing .csv of `stem` is dropped. Returns the paths."""
    stem = Path(stem)
    if stem.suffix.lower() == ".csv":
        stem = stem.with_suffix("")
    paths = []
    for name, frame in tables(result).items():
        path = stem.with_name(f"{stem.name}_{name}.csv")
        frame.to_csv(path, index=False)
        paths.append(path)
    return paths
