"""Calibration of lambda's interval where the truth is lambda = 0 (its bound): the fraction
of draws whose profile delta chi^2 at lambda = 0 exceeds the threshold 3.84, i.e. whose
95 % interval excludes the truth (fit_designs.py data, noise given, seeds 5000 + k).

    nice python -m bench.fit_lambda_zero --design early --noise 1e-3 --draws 80

A constrained fit at lambda = 0 is started from the truth and from the estimate; the lower
chi^2 counts. With R(t) depending on lambda^2 (a parameter on its bound) the asymptotic
fraction lies between 2.5 % (half the draws with lambda estimated at 0) and 5 %.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from bench.fit_designs import clean, draw, truth
from wound_opening.fitting.local import local_fit
from wound_opening.fitting.objective import Objective, to_z
from wound_opening.fitting.single import fit


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--design", default="early")
    ap.add_argument("--noise", type=float, default=1e-3)
    ap.add_argument("--draws", type=int, default=80)
    args = ap.parse_args()
    data, z_true = clean(args.design, 0.0), to_z(tuple(truth(0.0).values()))
    start, deltas, at_zero = time.process_time(), [], 0
    for k in range(args.draws):
        radius, profile = draw(args.design, 0.0, args.noise, 5000 + k, data)
        result = fit(radius, profile, outer_radius_um=100.0, intervals=False)
        obj = Objective(radius, profile, 100.0)
        chi2_0 = min(
            local_fit(obj, z0, fixed=2, value=0.0)[1] for z0 in (z_true, to_z(result.theta))
        )
        deltas.append(chi2_0 - result.chi2)
        at_zero += result.theta[2] < 1e-6
    deltas = np.array(deltas)
    print(
        f"{args.design}, noise {args.noise:g}, {args.draws} draws: delta chi^2(lambda = 0) > 3.84 "
        f"in "
        f"{int(np.sum(deltas > 3.84))} ({np.mean(deltas > 3.84):.1%}), lambda estimated 0 in "
        f"{at_zero}; "
        f"{time.process_time() - start:.0f} s CPU"
    )


if __name__ == "__main__":
    main()
