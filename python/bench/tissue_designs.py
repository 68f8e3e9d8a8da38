"""Synthetic wounds of one tissue from the EXACT solution (python/wound_exact.py), for
`fit_wounds`: wounds of radius R0_k = 5, 10, 20 um cut in one material,

    viscous length l = 20 um, tension/G = sigma = 0.5, zeta/G = 0.1 s/um^2
    -> lambda_k = l / R0_k = 4, 2, 1;   T_k = (zeta/G) R0_k^2 / 4 = 0.625, 2.5, 10 s;
       eta/G = l^2 (zeta/G) / 4 = 10 s,

in tissues of outer radius 80, 100, 120 um, 40 radii each over 0.5 .. 60 s, the noise
relative to each wound's opening R_final - R1 and given to the fit (fit_designs.draw's
convention).
"""

from __future__ import annotations

import numpy as np
import wound_exact as we

from wound_opening.fitting.wounds import Wound
from wound_opening.inputs.series import RadiusSeries

L_UM, SIGMA, ZETA_G = 20.0, 0.5, 0.1
R0S, OUTERS = (5.0, 10.0, 20.0), (80.0, 100.0, 120.0)
TIMES = np.linspace(0.5, 60, 40)
#: The true shared quantities, by their names in TissueFitResult.shared.
TRUTH = {
    "viscous_length_um": L_UM,
    "tension_over_G": SIGMA,
    "zeta_over_G_s_per_um2": ZETA_G,
    "eta_over_G_s": L_UM**2 * ZETA_G / 4,
}


def wound_truth(R0: float) -> dict:
    """One wound's own parameters (fit's names)."""
    return {"R0_um": R0, "sigma": SIGMA, "lambda": L_UM / R0, "T_s": ZETA_G * R0**2 / 4}


def clean(R0: float, outer: float, times=TIMES) -> np.ndarray:
    """Exact radii [um] of the wound of radius R0 at `times` [s]."""
    p = wound_truth(R0)
    return R0 * we.edge(p["lambda"], SIGMA, outer / R0, np.asarray(times) / p["T_s"])[0]


def opening(R0: float, outer: float) -> float:
    return R0 * (we.final_radius(SIGMA, outer / R0) - we.initial_radius(SIGMA))


def draw(noise: float, seed: int, r0s=R0S, outers=OUTERS, curves=None) -> list[Wound]:
    """One noisy draw of the wounds (Wound objects named R0 = 5 um, ...), the noise given;
    `curves`: their clean radii (computed if None)."""
    rng = np.random.default_rng(seed)
    curves = curves if curves is not None else [clean(r, o) for r, o in zip(r0s, outers)]
    out = []
    for R0, outer, radius in zip(r0s, outers, curves):
        sd = noise * opening(R0, outer)
        series = RadiusSeries(TIMES, radius + sd * rng.standard_normal(TIMES.size), sd)
        out.append(Wound(series, outer, name=f"R0={R0:g}um"))
    return out
