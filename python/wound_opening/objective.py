"""Weighted residuals of the model against a radius series and a velocity profile.

Coordinates of the optimiser: z = (ln R0, sigma, lambda, ln T), lambda >= 0. The outer
radius is fixed in um, so R_inf = outer / R0 moves with R0; each R_inf needs its own modal
basis (~0.2 ms), every other parameter change costs O(modes) (~25 us a curve). The fits
therefore hold R_inf at the current R0 during a least-squares run and repeat the run with
the updated R_inf until R0 settles (`frozen`), then polish with R_inf following R0 exactly.
"""

from __future__ import annotations

import math

import numpy as np

from . import _native
from .data import RadiusSeries, VelocityProfile

NAMES = ("R0_um", "sigma", "lambda", "T_s")
#: Largest lambda searched: a viscous length of 50 R0, beyond which the tissues of these
#: experiments (outer radius ~10 R0) move as one and R(t) depends on tau = lambda^2 T only.
LAMBDA_MAX = 50.0
#: Accuracy of the curves inside fits: far below any measurement noise, coarser grids.
FIT_TOLERANCE = 1e-8
#: Residual given to a data point the model cannot produce (a PIV radius inside the wound).
PENALTY = 1e3


def to_z(theta) -> np.ndarray:
    R0, sigma, lam, T = theta
    return np.array([math.log(R0), sigma, lam, math.log(T)])


def from_z(z) -> tuple[float, float, float, float]:
    return math.exp(z[0]), float(z[1]), max(float(z[2]), 0.0), math.exp(z[3])


class Objective:
    """Residuals (model - data) / noise, radius points first, then profile points."""

    def __init__(self, radius: RadiusSeries, profile: VelocityProfile | None, outer_radius_um: float):
        self.outer = float(outer_radius_um)
        t = np.asarray(radius.times_s, dtype=float)
        self.order = np.argsort(t, kind="stable")
        self.t_sorted = t[self.order]
        self.radius = np.asarray(radius.radius_um, dtype=float)[self.order]
        self.groups = []
        if profile is not None:
            pt = np.asarray(profile.times_s, dtype=float)
            for time in np.unique(pt):
                idx = np.flatnonzero(pt == time)
                self.groups.append((time, np.asarray(profile.r_um, float)[idx],
                                    np.asarray(profile.velocity_um_s, float)[idx]))
        self.n_radius = self.radius.size
        self.n_profile = sum(g[1].size for g in self.groups)
        self.noise = [1.0, 1.0]  # radius [um], velocity [um/s]
        self.evaluations = 0

    @property
    def size(self) -> int:
        return self.n_radius + self.n_profile

    def r_inf(self, R0: float) -> float:
        return self.outer / R0

    def model(self, theta, r_inf: float | None = None):
        """Radius [um] at the (sorted) radius times, and velocities [um/s] per profile group."""
        R0, sigma, lam, T = theta
        r_inf = self.r_inf(R0) if r_inf is None else r_inf
        self.evaluations += 1
        radius, _ = _native.series(lam, sigma, r_inf, self.t_sorted / T, velocity=False, tolerance=FIT_TOLERANCE)
        velocities = []
        for time, r, _ in self.groups:
            _, v = _native.profile_series(lam, sigma, r_inf, [time / T], r / R0, tolerance=FIT_TOLERANCE)
            velocities.append(R0 / T * v[0])
        return R0 * radius, velocities

    def residuals(self, z, r_inf: float | None = None) -> np.ndarray:
        theta = from_z(z)
        try:
            radius, velocities = self.model(theta, r_inf)
        except _native.SolverError:
            return np.full(self.size, PENALTY)
        parts = [(radius - self.radius) / self.noise[0]]
        parts += [(v - data) / self.noise[1] for v, (_, _, data) in zip(velocities, self.groups)]
        return np.concatenate(parts)

    def split(self, res: np.ndarray):
        """(radius residuals, profile residuals) of a residual vector."""
        return res[: self.n_radius], res[self.n_radius:]
