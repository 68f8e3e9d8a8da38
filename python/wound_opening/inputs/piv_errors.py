"""The errors of PIV ring means, estimated from the field itself: correlated between
overlapping windows and between the frame pairs of one grid point.

A PIV vector's error is mostly the texture in its window: the same cells sit in the window
of a grid point pair after pair (they move a fraction of a window per pair), and windows
that overlap share texture. So the error e_{g,k} of the vector at grid point g in pair k is
modelled as

    Cov(e_{g,k}, e_{h,j}) = s^2 rho_s(g - h) rho_t(|j - k|),    rho_t(0) = 1,

s^2 the variance of a vector's error, rho_s the correlation of two vectors of one pair at the
grid offset g - h, rho_t(l) the correlation of one grid point's errors in two pairs l apart in
the pairs' order (the texture moves on: it decays with l). All are estimated from the
deviations d of the vectors used from their pair's smooth radial profile (`deviations`: a
least-squares a / r + b / r^2 + c / r^3 + d per pair, so s^2 = sum d^2 / (N - 4 pairs)):

    rho_s(o) = sum_k sum_g d_{g,k} d_{g+o,k} / (s^2 N_o)      (|o| < the window, else 0)
    rho_t(l) = sum_k sum_g d_{g,k} d_{g,k+l} / (s^2 N_l)

(N the number of products summed; rho_s symmetrised, clipped to [-1, 1], its negative
values set to 0; rho_t clipped to [0, 0.99] and made non-increasing in l). A ring mean m_a =
(1/n_a) sum_{g in a} v_g of pair k_a then has

    Cov(m_a, m_b) = s^2 / (n_a n_b) sum_{g in a, h in b} rho_s(g - h) rho_t(|k_a - k_b|),

computed as I_a . (rho_s * I_b) with I the rings' indicator images on the grid (* a 2-D
convolution). With rho_s = delta and rho_t = 0 this is the independent s^2 / n_a the rings
used before; with errors as locked to the texture as OpenPIV's (rho_t 0.8 over many pairs) 24 pairs
weigh like a few. The matrix
is made positive definite by clipping its correlation's eigenvalues at EIGEN_FLOOR."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Smallest eigenvalue kept in the ring means' correlation matrix.
EIGEN_FLOOR = 1e-6


@dataclass(frozen=True)
class Grid:
    """The PIV grid: each vector's column and row index, and the grid's shape."""

    ix: np.ndarray
    iy: np.ndarray
    shape: tuple


def grid_of(x, y, spacing: float) -> Grid:
    """Indices of positions on a regular grid of step `spacing` (same units)."""
    ix = np.rint((x - np.min(x)) / spacing).astype(int)
    iy = np.rint((y - np.min(y)) / spacing).astype(int)
    return Grid(ix, iy, (int(iy.max()) + 1, int(ix.max()) + 1))


def border(grid: Grid) -> np.ndarray:
    """The vectors on the grid's outer rows and columns: their windows' search areas reach
    the image border (OpenPIV and PIVlab pad there)."""
    return (
        (grid.ix == 0)
        | (grid.iy == 0)
        | (grid.ix == grid.shape[1] - 1)
        | (grid.iy == grid.shape[0] - 1)
    )


def _convolve(a: np.ndarray, b: np.ndarray, same: bool = False) -> np.ndarray:
    """The linear convolution of the stacks a and b over their last two axes (b broadcast
    along the first), full, or `same` as a's (centred, scipy.signal's "same" mode), by
    numpy's real FFTs zero-padded to the full size: the sums are exact but for rounding
    (scipy.signal.fftconvolve, whose import costs 0.7 s of every PIV fit, does the same)."""
    full = [a.shape[k] + b.shape[k] - 1 for k in (-2, -1)]
    out = np.fft.irfftn(
        np.fft.rfftn(a, full, axes=(-2, -1)) * np.fft.rfftn(b, full, axes=(-2, -1)),
        full,
        axes=(-2, -1),
    )
    if not same:
        return out
    y0, x0 = ((b.shape[k] - 1) // 2 for k in (-2, -1))
    return out[..., y0 : y0 + a.shape[-2], x0 : x0 + a.shape[-1]]


def _images(values, pair, grid: Grid, pairs):
    """(values, mask) as images per pair: (len(pairs), ny, nx)."""
    img = np.zeros((len(pairs), *grid.shape))
    mask = np.zeros_like(img)
    k = np.searchsorted(pairs, pair)
    img[k, grid.iy, grid.ix] = values
    mask[k, grid.iy, grid.ix] = 1.0
    return img, mask


def correlations(d, pair, grid: Grid, reach: int, s2: float):
    """(rho_s as a (2 reach + 1)^2 kernel, rho_t by the lag in frame-pair order, 1 at lag 0)
    of the deviations `d` (module docstring)."""
    pairs = np.unique(pair)
    img, mask = _images(d, pair, grid, pairs)
    flip = img[:, ::-1, ::-1]
    prod = _convolve(img, flip)
    count = _convolve(mask, mask[:, ::-1, ::-1])
    cy, cx = grid.shape[0] - 1, grid.shape[1] - 1
    window = (slice(None), slice(cy - reach, cy + reach + 1), slice(cx - reach, cx + reach + 1))
    num, n = prod[window].sum(axis=0), np.rint(count[window].sum(axis=0))
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = np.where(n >= 10, num / (np.maximum(n, 1) * s2), 0.0)
    rho = np.clip(0.5 * (rho + rho[::-1, ::-1]), -1.0, 1.0)
    rho[reach, reach] = 1.0
    rho[rho < 0] = 0.0  # past the overlap the estimate is noise about 0
    rho_t = np.ones(len(pairs))
    for lag in range(1, len(pairs)):
        num = float(np.sum(img[lag:] * img[:-lag]))
        n_lag = float(np.sum(mask[lag:] * mask[:-lag]))
        rho_t[lag] = num / (n_lag * s2) if n_lag >= 10 else 0.0
    # clipped to [0, 0.99] and never rising with the lag (the texture only moves on)
    return rho, np.minimum.accumulate(np.clip(rho_t, 0.0, 0.99))


def deviations(r, vr, pair) -> tuple[np.ndarray, float]:
    """(deviations, s^2): each vector's radial velocity less its pair's smooth profile, the
    least-squares fit of a / r + b / r^2 + c / r^3 + d (the centre's, centre.py), and their
    variance sum d^2 / (N - 4 pairs). A smooth profile, not the ring means: a ring one grid
    step wide holds few neighbours, and deviations about its mean are anti-correlated
    between neighbours whatever the errors are."""
    out = np.empty(vr.size)
    pairs = np.unique(pair)
    for k in pairs:
        rows = np.flatnonzero(pair == k)
        basis = np.column_stack([1 / r[rows], r[rows] ** -2, r[rows] ** -3, np.ones(rows.size)])
        coef, *_ = np.linalg.lstsq(basis, vr[rows], rcond=None)
        out[rows] = vr[rows] - basis @ coef
    dof = max(vr.size - 4 * pairs.size, 1)
    return out, float(np.sum(out**2)) / dof


def ring_covariance(ring, pair, grid: Grid, rho, rho_t, s2: float) -> np.ndarray:
    """Cov of the ring means (rings 0 .. n-1; `ring` of each vector, `pair` its frame pair),
    s^2 the vectors' variance (`deviations`)."""
    rings = int(ring.max()) + 1
    ind = np.zeros((rings, *grid.shape))
    np.add.at(ind, (ring, grid.iy, grid.ix), 1.0)
    smooth = _convolve(ind, rho[None, :, :], same=True)
    raw = ind.reshape(rings, -1) @ smooth.reshape(rings, -1).T
    ring_pair = np.zeros(rings, dtype=int)
    ring_pair[ring] = np.searchsorted(np.unique(pair), pair)  # the pair's place in order
    lag = np.abs(ring_pair[:, None] - ring_pair[None, :])
    n = ind.reshape(rings, -1).sum(axis=1)
    cov = s2 * raw * rho_t[lag] / np.outer(n, n)
    return _positive(cov)


def _positive(cov: np.ndarray) -> np.ndarray:
    sd = np.sqrt(np.diag(cov))
    corr = cov / np.outer(sd, sd)
    w, v = np.linalg.eigh(0.5 * (corr + corr.T))
    if w[0] >= EIGEN_FLOOR:
        return cov
    corr = (v * np.maximum(w, EIGEN_FLOOR)) @ v.T
    d = np.sqrt(np.diag(corr))
    return corr / np.outer(d, d) * np.outer(sd, sd)
