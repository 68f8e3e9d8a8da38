"""Likelihood profiles of derived quantities: the fit reparametrised so that the quantity
is one coordinate, then profiled like a parameter (likelihood.py).

    quantity                       coordinate w_k (replaces)      z from w
    tau = eta/G = lambda^2 T [s]   ln tau       (ln T, k = 3)     ln T = w3 - 2 ln lambda
    zeta/G = 4 T / R0^2 [s/um^2]   ln zeta/G    (ln T, k = 3)     ln T = w3 - ln 4 + 2 ln R0
    viscous length lambda R0 [um]  ln L         (lambda, k = 2)   lambda = exp(w2 - ln R0)

tension/G is sigma (its own profile). The Jacobian in w is the objective's times dz/dw.
A quantity needing lambda > 0 is not profiled when lambda's estimate is 0 (its interval
then reaches 0: not identified).
"""

from __future__ import annotations

import math

import numpy as np

from .likelihood import Profile, _side

LN4 = math.log(4.0)


class Reparametrised:
    """The objective in coordinates w (one coordinate replaced), for local_fit."""

    def __init__(self, obj, kind: str):
        self.obj, self.kind = obj, kind
        self.k = 2 if kind == "viscous_length_um" else 3
        for name in ("t_sorted", "radius", "outer", "size"):
            setattr(self, name, getattr(obj, name))

    def to_z(self, w):
        z = np.array(w, dtype=float)
        if self.kind == "tau_s":
            z[3] = w[3] - 2 * math.log(max(w[2], 1e-300))
        elif self.kind == "zeta_over_G_s_per_um2":
            z[3] = w[3] - LN4 + 2 * w[0]
        else:
            z[2] = math.exp(w[2] - w[0])
        return z

    def to_w(self, z):
        w = np.array(z, dtype=float)
        if self.kind == "tau_s":
            w[3] = z[3] + 2 * math.log(z[2])
        elif self.kind == "zeta_over_G_s_per_um2":
            w[3] = z[3] + LN4 - 2 * z[0]
        else:
            w[2] = math.log(z[2]) + z[0]
        return w

    def residuals(self, w):
        return self.obj.residuals(self.to_z(w))

    def jacobian(self, w):
        z = self.to_z(w)
        dz = np.eye(4)
        if self.kind == "tau_s":
            dz[3, 2] = -2 / w[2]
        elif self.kind == "zeta_over_G_s_per_um2":
            dz[3, 0] = 2.0
        else:
            dz[2, 2], dz[2, 0] = z[2], -z[2]
        return self.obj.jacobian(z) @ dz

    def gradient(self, z) -> np.ndarray:
        """d w_k / d z: the row of dw/dz that differs from the identity."""
        g = np.zeros(4)
        if self.kind == "tau_s":
            g[2], g[3] = 2 / z[2], 1.0
        elif self.kind == "zeta_over_G_s_per_um2":
            g[0], g[3] = -2.0, 1.0
        else:
            g[0], g[2] = 1.0, 1 / z[2]
        return g

    def bounds(self):
        from .local import bounds

        lower, upper = bounds(self.obj)
        if self.kind == "tau_s":
            lower[2], lower[3], upper[3] = 1e-6, -np.inf, np.inf
        elif self.kind == "zeta_over_G_s_per_um2":
            lower[3], upper[3] = -np.inf, np.inf
        else:
            lower[2], upper[2] = -np.inf, np.inf
        return lower, upper


def derived_profiles(obj, z_hat, chi2_min: float, threshold: float, loss: str = "linear", alternates=(),
                     cov_z=None) -> dict:
    """Profile (interval in the quantity's units) of tau, zeta/G and the viscous length;
    with other optima below the threshold (`alternates`: (z, delta chi^2)), the hull of the
    intervals walked from each (as likelihood.profile_all does). `cov_z`, the Jacobian's
    covariance in z, gives the first step (the standard error of w_k, from
    cov_w = A cov_z A^T with A = dw/dz) and the start of the other coordinates."""
    out = {}
    centres = [(z_hat, 0.0)] + [(a, d) for a, d in alternates if d < threshold]
    for kind in ("tau_s", "zeta_over_G_s_per_um2", "viscous_length_um"):
        if kind != "zeta_over_G_s_per_um2" and any(c[2] <= 1e-6 for c, _ in centres):
            out[kind] = Profile(0.0, None, True)
            continue
        rep = Reparametrised(obj, kind)
        k = rep.k
        step, slope = 0.05, np.eye(4)[k]
        if cov_z is not None and np.all(np.isfinite(cov_z)):
            A = np.eye(4)
            A[k] = rep.gradient(z_hat)
            cov_w = A @ cov_z @ A.T
            if cov_w[k, k] > 0:
                step = float(np.clip(math.sqrt(cov_w[k, k]), 5e-4, 1.0))
                slope = cov_w[:, k] / cov_w[k, k]
        lows, highs, points = [], [], []
        for centre, delta0 in centres:
            w = rep.to_w(centre)
            for direction, ends in ((-1, lows), (1, highs)):
                if ends and (ends[0] is None or direction * (w[k] - ends[0]) <= 0):
                    continue  # an optimum inside the interval found (or an open end)
                limit = w[k] + direction * math.log(100.0)
                end, _, pts = _side(rep, k, w, chi2_min, threshold, step, direction, limit, slope, loss, delta0)
                ends.append(end)
                points += pts
        lo = None if None in lows else math.exp(min(lows))
        hi = None if None in highs else math.exp(max(highs))
        out[kind] = Profile(lo, hi, False, sorted((math.exp(v), d) for v, d in points))
    return out
