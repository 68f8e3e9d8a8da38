"""Synthetic laser-ablation experiments from the EXACT solution (python/wound_exact.py) for
coverage studies of `fit`: designs x lambda x noise, one noisy draw per seed.

R0 = 10 um, sigma = 0.5, outer radius 100 um; T = 10 s, except in the viscous regime
(lambda >= 5) where T = 10 s / lambda^2 keeps tau = lambda^2 T = 10 s inside the minute of
data. Noise is relative to the opening R_final - R1 (radii) and to the largest PIV speed.

Designs (40 radii each):
  radius   0.5 .. 60 s
  piv      radius + PIV at 1 s and 3 s: a vector at the wound edge, one 2 % outside it,
           ten out to 6 R0 (at current positions)
  plateau  42 .. 60 s
  early    0.5 .. 5 s
"""

from __future__ import annotations

import numpy as np
import wound_exact as we

from wound_opening.inputs.series import RadiusSeries, VelocityProfile

R0, SIGMA, OUTER = 10.0, 0.5, 100.0
NAMES = ("R0_um", "sigma", "lambda", "T_s")
TIMES = {
    "radius": np.linspace(0.5, 60, 40),
    "piv": np.linspace(0.5, 60, 40),
    "plateau": np.linspace(42, 60, 40),
    "early": np.linspace(0.5, 5, 40),
}
PIV_TIMES = np.array([1.0, 3.0])


def T_of(lam: float) -> float:
    return 10.0 if lam < 5 else 10.0 / lam**2


def truth(lam: float) -> dict:
    return {"R0_um": R0, "sigma": SIGMA, "lambda": lam, "T_s": T_of(lam)}


def clean(design: str, lam: float):
    """Exact radii at the design's times; for "piv" also (times, r_um, velocity_um_s)."""
    T, r_inf = T_of(lam), OUTER / R0
    t = TIMES[design]
    radius = R0 * we.edge(lam, SIGMA, r_inf, t / T)[0]
    if design != "piv":
        return t, radius, None
    edge = we.edge(lam, SIGMA, r_inf, PIV_TIMES / T)[0]
    rows = []
    for time, e in zip(PIV_TIMES, edge):
        x = np.concatenate([[1.0], np.linspace(1.5, 6.0, 10)])  # reference radii in R0
        u, v = we.profile(lam, SIGMA, r_inf, x, np.array([time / T]))
        r = R0 * (x + u[0])
        r = np.insert(r, 1, 1.02 * R0 * e)  # 2 % outside the edge: interpolate the velocity there
        vel = np.insert(R0 / T * v[0], 1, np.nan)
        rows.append((np.full(r.size, time), r, vel))
    times, r, vel = (np.concatenate(c) for c in zip(*rows))
    out = np.isnan(vel)
    if (
        out.any()
    ):  # the velocity at 2 % outside the edge: from the exact field at that material point
        for k in np.flatnonzero(out):
            lo, hi = 1.0, 1.1
            for _ in range(60):  # bisect the reference radius whose current position is r[k]
                mid = 0.5 * (lo + hi)
                u, _ = we.profile(lam, SIGMA, r_inf, np.array([mid]), np.array([times[k] / T]))
                lo, hi = (mid, hi) if R0 * (mid + u[0, 0]) < r[k] else (lo, mid)
            vel[k] = (
                R0
                / T
                * we.profile(lam, SIGMA, r_inf, np.array([lo]), np.array([times[k] / T]))[1][0, 0]
            )
    return t, radius, (times, r, vel)


def draw(design: str, lam: float, noise: float, seed: int, data=None):
    """(RadiusSeries, VelocityProfile or None) with the noise given (as an experimenter who
    knows the noise would), from `data` = clean(design, lam) or computed."""
    t, radius, piv = data if data is not None else clean(design, lam)
    rng = np.random.default_rng(seed)
    opening = R0 * (we.final_radius(SIGMA, OUTER / R0) - we.initial_radius(SIGMA))
    sd = noise * opening
    series = RadiusSeries(t, radius + sd * rng.standard_normal(t.size), sd)
    if piv is None:
        return series, None
    times, r, vel = piv
    sdv = noise * float(np.max(np.abs(vel)))
    return series, VelocityProfile(times, r, vel + sdv * rng.standard_normal(vel.size), sdv)


def covers(ci, value) -> bool:
    lo, hi = ci
    return lo is not None and hi is not None and lo <= value <= hi
