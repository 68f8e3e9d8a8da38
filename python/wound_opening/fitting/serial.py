"""Serially correlated radius errors: an outline measured frame after frame borders the same
cells, so its error is close to the previous frame's (lag-1 correlation 0.5 to 0.8 measured
on outlines of rendered movies by ImageJ's threshold). Modelled as a first-order
autoregression, e_i = rho_i e_(i-1) + innovation, with rho_i = rho^(g_i) over a gap of g_i
frame intervals (a frame where the tracking failed), the marginal standard deviation the
series' sd. The fit's radius residuals are then the standardised innovations

    w_0 = e_0,    w_i = (e_i - rho_i e_(i-1)) / sqrt(1 - rho_i^2),

independent and of unit variance when the model holds (Prais-Winsten). rho is estimated
with the noise from the residuals at the fit (the lag-1 correlation of consecutive frames),
at most RHO_MAX: a smooth misfit reads as a correlation near 1, and the cap keeps a fifth of
it in the innovations, where the runs tests (gof.py) still see it."""

from __future__ import annotations

import numpy as np

#: The largest lag-1 correlation estimated.
RHO_MAX = 0.8


def gaps(times: np.ndarray) -> np.ndarray:
    """Each point's distance from the previous one in frame intervals (the smallest step);
    1 for repeated times."""
    dt = np.diff(np.asarray(times, float))
    step = float(np.min(dt[dt > 0], initial=np.inf))
    if not np.isfinite(step):
        return np.ones(dt.size)
    return np.where(dt > 0, dt / step, 1.0)


def whiten(a: np.ndarray, rho: float, gap: np.ndarray) -> np.ndarray:
    """The innovations of `a` (a vector, or rows of a matrix) in time order (module
    docstring)."""
    if rho == 0.0 or a.shape[0] < 2:
        return a
    r = rho**gap
    shape = (-1,) + (1,) * (a.ndim - 1)
    out = a.copy()
    out[1:] = (a[1:] - r.reshape(shape) * a[:-1]) / np.sqrt(1 - r * r).reshape(shape)
    return out


def lag1(e: np.ndarray, gap: np.ndarray) -> float:
    """The lag-1 correlation of consecutive frames' residuals, in [0, RHO_MAX]."""
    near = gap <= 1.5
    if np.count_nonzero(near) < 3:
        return 0.0
    num = float(np.sum(e[1:][near] * e[:-1][near]))
    den = float(np.sum(e**2)) * np.count_nonzero(near) / max(e.size, 1)
    return float(np.clip(num / den if den > 0 else 0.0, 0.0, RHO_MAX))
