"""The measured files against the exact truth: how OpenPIV's and the outline's errors are
correlated, the numbers a fitter's error model needs.

PIV. The truth of a vector is what it measures: the displacement, from frame a to frame
a + 1, of the material in its interrogation window at frame a (the exact displacement of an
8 x 8 lattice of points spread over the 32 px window, averaged over those on tissue), over
the frame interval. Its error e = measured - truth, in radial and tangential components about
the true centre, is studied on the windows whose search area (40 px) stays clear of the wound
at both frames ("tissue windows"): the least-squares slope of the measured radial velocity
on the true one (and on the displacement of the window's centre point alone), the
correlation of e at one grid point between pairs k and k + L (pooled over points and
pairs), and between windows 1, 2 and 4 grid steps apart
in one pair (grid steps of 40 - 24 = 16 px: the 32 px windows 1 step apart share half their
pixels, 2 and 4 steps apart none). The windows
that reach into the wound are summarised by their mean radial velocity over the exact one
at their centre.

Outline. offset_k = measured radius - exact R(t_k); its mean, spread, and the lag-1
correlation over the frames after the cut of offset_k - mean and of offset_k less its
straight-line fit over k (the drift removed).
"""

from __future__ import annotations

import numpy as np

from bench.lab_measure import SEARCH_PX, WINDOW_PX
from bench.lab_render import Movie, edge_radius_um, lagrangian_displacement_um

LATTICE = 8


def window_truth(m: Movie, truth: dict, a: int, centres_px: np.ndarray) -> np.ndarray:
    """Exact window-averaged Lagrangian displacement [um] (n, 2: x, y image axes)."""
    off = (np.arange(LATTICE) + 0.5) / LATTICE * WINDOW_PX - WINDOW_PX / 2
    ox, oy = np.meshgrid(off, off)
    lat = np.column_stack([ox.ravel(), oy.ravel()])
    pts = centres_px[:, None, :] + lat[None, :, :]
    d = lagrangian_displacement_um(m, truth, a, pts.reshape(-1, 2)).reshape(*pts.shape)
    with np.errstate(invalid="ignore"):
        return np.nanmean(d, axis=1)


def _corr(a: np.ndarray, b: np.ndarray) -> float:
    ok = np.isfinite(a) & np.isfinite(b)
    return float(np.corrcoef(a[ok], b[ok])[0, 1]) if ok.sum() > 10 else float("nan")


def piv_errors(m: Movie, truth: dict, piv: dict) -> dict:
    cx, cy = m.centre()
    px = piv["px"]
    d = px - np.array([cx, cy])
    r_px = np.hypot(d[:, 0], d[:, 1])
    er = d / r_px[:, None]
    n_side = int(round(np.sqrt(len(px))))
    err_r, err_t, near_ratio, slope = [], [], [], np.zeros((2, 2))
    for a, u, v, fl in zip(piv["a"], piv["u"], piv["v"], piv["flags"]):
        true = window_truth(m, truth, a, px) / m.frame_s
        meas = np.column_stack([u, v])
        e = meas - true
        er_k = np.sum(e * er, 1)
        et_k = e[:, 1] * er[:, 0] - e[:, 0] * er[:, 1]
        t_b = truth["t_s"][a + 1]
        wound_px = edge_radius_um(m, t_b)[0] / m.pixel_um
        clear = r_px - SEARCH_PX / np.sqrt(2) > wound_px
        bad = (fl != 0) | ~clear
        er_k[bad], et_k[bad] = np.nan, np.nan
        err_r.append(er_k)
        err_t.append(et_k)
        ok = ~bad
        centre = lagrangian_displacement_um(m, truth, a, px[ok]) / m.frame_s
        vr_meas = np.sum(meas[ok] * er[ok], 1)
        for j, t in enumerate((np.sum(true[ok] * er[ok], 1), np.sum(centre * er[ok], 1))):
            slope[j] += (np.sum(vr_meas * t), np.sum(t * t))
        ring = (~clear) & (fl == 0) & (r_px > wound_px)
        centre_true = lagrangian_displacement_um(m, truth, a, px[ring]) / m.frame_s
        vr_true = np.sum(centre_true * er[ring], 1)
        vr_meas = np.sum(meas[ring] * er[ring], 1)
        near_ratio.append(float(np.sum(vr_meas) / np.sum(vr_true)))
    E = {"radial": np.array(err_r), "tangential": np.array(err_t)}
    out = {
        "tissue_windows_per_pair": int(np.isfinite(E["radial"][0]).sum()),
        "radial_slope_on_window_truth": float(slope[0, 0] / slope[0, 1]),
        "radial_slope_on_centre_point": float(slope[1, 0] / slope[1, 1]),
    }
    for name, e in E.items():
        k = e.shape[0]
        grid = e.reshape(k, n_side, n_side)
        res = {
            "rms_um_s": float(np.sqrt(np.nanmean(e**2))),
            "mean_um_s": float(np.nanmean(e)),
            "pairs_lag": {
                str(lag): _corr(e[:-lag].ravel(), e[lag:].ravel())
                for lag in (1, 5, 10, 20)
                if lag < k
            },
            "neighbours_steps": {
                str(s): _corr(
                    np.concatenate([grid[:, :, :-s].ravel(), grid[:, :-s, :].ravel()]),
                    np.concatenate([grid[:, :, s:].ravel(), grid[:, s:, :].ravel()]),
                )
                for s in (1, 2, 4)
            },
        }
        persistent = np.nanmean(e, axis=0)
        res["point_mean_over_pairs_rms_um_s"] = float(np.sqrt(np.nanmean(persistent**2)))
        out[name] = res
    out["wound_ring_ratio_per_pair"] = near_ratio
    out["wound_ring_ratio_range"] = [float(np.nanmin(near_ratio)), float(np.nanmax(near_ratio))]
    return out


def outline_errors(m: Movie, truth: dict, measured_um: np.ndarray) -> dict:
    after = truth["t_s"] > 0
    off = measured_um[after] - truth["radius_um"][after]
    off = off[np.isfinite(off)]

    def lag1(c):
        return float(np.sum(c[1:] * c[:-1]) / np.sum(c * c)) if c.size > 2 else float("nan")

    k = np.arange(off.size)
    drift = np.polyval(np.polyfit(k, off, 1), k) if off.size > 2 else off.mean()
    half = off.size // 2
    return {
        "frames": int(off.size),
        "offset_mean_um": float(off.mean()),
        "offset_sd_um": float(off.std(ddof=1)),
        "offset_min_um": float(off.min()),
        "offset_max_um": float(off.max()),
        "offset_first_half_mean_um": float(off[:half].mean()),
        "offset_second_half_mean_um": float(off[half:].mean()),
        "lag1_correlation": lag1(off - off.mean()),
        "lag1_correlation_detrended": lag1(off - drift),
        "offsets_um": [round(float(x), 4) for x in off],
    }
