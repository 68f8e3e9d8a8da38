"""The runs test of the residuals (fitting/gof.py): its false-alarm rate on correct fits of
exact-solution data (bench/fit_designs.py: designs x lambda x noise, the noise estimated, and
given) and its detection rate on a wrong fixed value (piv design, lambda 0.5,
noise 1 % of the opening, noise estimated, R0 fixed at 10.5 um where the truth is 10 um).
Fits without intervals (the verdict needs none). Prints one line per fit and the counts.

    PYTHONPATH=python python python/bench/residual_runs.py --draws 4 --wrong 16
"""

from __future__ import annotations

import argparse
import itertools
import time

from bench.fit_designs import clean, draw
from wound_opening.fitting.gof import RUNS_FAIL_P as P_FAIL
from wound_opening.fitting.gof import RUNS_WARN_P as P_WARN
from wound_opening.fitting.parameters import Parameters
from wound_opening.fitting.single import fit
from wound_opening.inputs.series import RadiusSeries, VelocityProfile

LAMBDAS = (0.0, 0.1, 0.5, 2.0, 10.0)
NOISES = (1e-3, 1e-2, 4e-2)
DESIGNS = ("radius", "piv", "plateau", "early")


def estimated(radius, profile):
    """The same data with the noise left to the fit."""
    r = RadiusSeries(radius.times_s, radius.radius_um)
    p = (
        None
        if profile is None
        else VelocityProfile(profile.times_s, profile.r_um, profile.velocity_um_s)
    )
    return r, p


def one(design, lam, noise, seed, given, params=None):
    data = clean(design, lam)
    radius, profile = draw(design, lam, noise, seed, data)
    if not given:
        radius, profile = estimated(radius, profile)
    res = fit(radius, profile, outer_radius_um=100.0, intervals=False, params=params)
    runs = res.residual_runs
    p_min = min((r["p_value"] for r in runs), default=1.0)
    other = [m for m in res.reasons if "runs of residual signs" not in m]
    return p_min, runs, other


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--draws", type=int, default=4, help="draws per cell of correct fits")
    ap.add_argument("--wrong", type=int, default=16, help="draws of the wrong-R0 case")
    args = ap.parse_args()
    t0 = time.process_time()
    counts = {"fits": 0, "warn": 0, "fail": 0, "other failures": 0}
    cells = itertools.product(itertools.product(LAMBDAS, NOISES, DESIGNS), (False, True))
    for c, ((lam, noise, design), given) in enumerate(cells):
        for k in range(args.draws):  # a draw of its own per cell (independent alarms)
            p_min, runs, other = one(design, lam, noise, 5000 + 100 * c + k, given)
            counts["fits"] += 1
            counts["other failures"] += bool(other)
            counts["fail"] += p_min < P_FAIL
            counts["warn"] += P_FAIL <= p_min < P_WARN
            print(
                f"correct {design} lambda {lam:g} noise {noise:g} given {given} draw {k}: "
                f"p_min {p_min:.3g} "
                + str(
                    [
                        (r["series"], r["runs"], r["points"], round(r["durbin_watson"], 2))
                        for r in runs
                    ]
                ),
                flush=True,
            )
    print("correct fits:", counts)
    wrong = {"fits": 0, "warn": 0, "fail": 0}
    params = Parameters()
    params.add("R0_um", value=10.5, vary=False)
    for k in range(args.wrong):
        p_min, runs, _ = one("piv", 0.5, 0.01, k, False, params)
        wrong["fits"] += 1
        wrong["fail"] += p_min < P_FAIL
        wrong["warn"] += P_FAIL <= p_min < P_WARN
        print(f"wrong R0 draw {k}: p_min {p_min:.3g}", flush=True)
    print("wrong R0 = 10.5 um (truth 10):", wrong)
    print(f"CPU {time.process_time() - t0:.0f} s")


if __name__ == "__main__":
    main()
