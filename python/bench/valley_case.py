"""A viscous wound recorded early: radius only, lambda = 10, T = 10 s (eta/G = 1000 s), R0 = 10 um,
sigma = 0.5, outer 100 um, 100 frames 0.2-50 s (the opening 4.7 % done at the last),
noise as a fraction of the opening, estimated by the fit (threshold F(1, 96) = 3.94).
Prints each draw's estimate and the intervals of the four parameters.

    PYTHONPATH=python python -m bench.valley_case NOISE SEED[,SEED...]
"""

from __future__ import annotations

import sys
import time

import numpy as np
import wound_exact as we

from wound_opening.fitting.single import fit
from wound_opening.inputs.series import RadiusSeries

LAM, T, SIGMA, R0, OUTER = 10.0, 10.0, 0.5, 10.0, 100.0
TIMES = np.linspace(0.2, 50.0, 100)


def series(noise: float, seed: int) -> RadiusSeries:
    exact = R0 * we.edge(LAM, SIGMA, OUTER / R0, TIMES / T)[0]
    opening = R0 * (we.final_radius(SIGMA, OUTER / R0) - we.initial_radius(SIGMA))
    rng = np.random.default_rng(seed)
    return RadiusSeries(TIMES, exact + noise * opening * rng.standard_normal(TIMES.size))


def main(noise: float, seeds) -> None:
    for seed in seeds:
        cpu = time.process_time()
        res = fit(series(noise, seed), outer_radius_um=OUTER, derived=False)
        print(f"noise {noise:g} seed {seed}: converged {res.converged} {res.reasons}")
        for name, rep in res.reports.items():
            print(f"  {name} = {rep.estimate:.4g}  {rep.ci95}")
        print(f"  CPU {time.process_time() - cpu:.1f} s, {res.evaluations} evaluations")


if __name__ == "__main__":
    main(float(sys.argv[1]), [int(s) for s in sys.argv[2].split(",")])
