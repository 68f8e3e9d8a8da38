"""Coverage of the 95 % intervals next to lambda's bound 0: the friction regime, radius only,
exact-solution data (wound_exact.py) with
R0 = 10 um, sigma = 0.5, T = 10 s, outer radius 100 um, FRAMES radii from 0.5 to 60 s and
noise 1 % of the opening (given). For each lambda, the share of draws whose interval holds
the truth, per quantity, over all converged draws and over those that call it identified,
with a binomial p-value of the misses against honest 95 % intervals, and the law of delta
chi^2 at each parameter's truth (mean, share above 3.84 and 2.71, 95 % point: calibration
by simulation of the threshold). Runs the package on
PYTHONPATH, so the same command measures another tree (e.g. the tree before the change).

    PYTHONPATH=python python python/bench/bound_coverage.py --draws 200 --workers 2
"""

from __future__ import annotations

import argparse
import time
from multiprocessing import Pool

import numpy as np
import wound_exact as we
from scipy import stats

from wound_opening.fitting.local import local_fit
from wound_opening.fitting.objective import to_z
from wound_opening.fitting.single import fit
from wound_opening.inputs.series import RadiusSeries

R0, SIGMA, T, OUTER = 10.0, 0.5, 10.0, 100.0
QUANTITIES = ("R0_um", "sigma", "lambda", "T_s", "zeta_over_G_s_per_um2")


def data(lam: float, seed: int, frames: int = 120, noise: float = 0.01) -> RadiusSeries:
    """The radius series of draw `seed` at `lam`, its noise given."""
    t = np.linspace(0.5, 60.0, frames)
    clean = R0 * we.edge(lam, SIGMA, OUTER / R0, t / T)[0]
    sd = noise * R0 * (we.final_radius(SIGMA, OUTER / R0) - we.initial_radius(SIGMA))
    rng = np.random.default_rng(seed)
    return RadiusSeries(t, clean + sd * rng.standard_normal(t.size), sd)


def one(job):
    lam, seed, frames, noise = job
    result = fit(data(lam, seed, frames, noise), outer_radius_um=OUTER)
    if not result.converged:
        return lam, None
    truth = {
        "R0_um": R0,
        "sigma": SIGMA,
        "lambda": lam,
        "T_s": T,
        "zeta_over_G_s_per_um2": 4 * T / R0**2,
    }
    out = {}
    for name in QUANTITIES:
        if name in result.reports:
            rep = result.reports[name]
            (lo, hi), ident = rep.ci95, rep.identifiable
        else:
            m = result.material[name]
            (lo, hi), ident = m["ci95"], m["identifiable"]
        covered = (lo is None or lo <= truth[name]) and (hi is None or truth[name] <= hi)
        out[name] = (covered, bool(ident))
    out["delta"] = _delta_at_truth(result, truth)
    return lam, out


def _delta_at_truth(result, truth) -> dict:
    """delta chi^2 at each parameter's truth: a fit of the other three (tolerances 1e-12,
    up to 2000 evaluations) from the truth and from the estimate, the lower kept. Its law
    is what the threshold calibrates."""
    optimum = result.refit.__self__  # the fit's Optimum (fitting/optimum.py)
    obj, z_hat, chi2_min = optimum.problem, optimum.z, optimum.chi2
    z_true = to_z([truth[n] for n in QUANTITIES[:4]])
    out = {}
    for i, name in enumerate(QUANTITIES[:4]):
        best = min(
            local_fit(obj, start, fixed=i, value=z_true[i], max_nfev=2000)[1]
            for start in (z_true, z_hat)
        )
        out[name] = max(best - chi2_min, 0.0)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--draws", type=int, default=200)
    ap.add_argument("--lambdas", default="0.05,0.1")
    ap.add_argument("--frames", type=int, default=120)
    ap.add_argument("--noise", type=float, default=0.01)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--seed", type=int, default=7000, help="first seed (each lambda its own)")
    args = ap.parse_args()
    lams = [float(x) for x in args.lambdas.split(",")]
    jobs = [
        (lam, args.seed + 1000 * j + k, args.frames, args.noise)
        for j, lam in enumerate(lams)
        for k in range(args.draws)
    ]
    t0 = time.process_time()
    with Pool(args.workers) as pool:
        done = pool.map(one, jobs, chunksize=1)
    for lam in lams:
        rows = [o for la, o in done if la == lam]
        ok = [o for o in rows if o is not None]
        print(f"lambda {lam:g}: {len(ok)} of {len(rows)} converged")
        for name in QUANTITIES:
            cov = [c for c, _ in (o[name] for o in ok)]
            idc = [c for c, i in (o[name] for o in ok) if i]
            miss = len(cov) - sum(cov)
            p = stats.binom.sf(miss - 1, len(cov), 0.05) if cov else float("nan")
            print(
                f"  {name:<24} covered {sum(cov)}/{len(cov)} (P(misses >= {miss}) = {p:.2g}); "
                f"identified {len(idc)}, of them covered {sum(idc)}"
            )
        for name in QUANTITIES[:4]:
            d = np.array([o["delta"][name] for o in ok])
            d = d[np.isfinite(d)]
            print(
                f"  delta chi^2 at the true {name:<7}: mean {d.mean():.2f} (chi^2_1: 1), "
                f"> 3.84 in {np.sum(d > 3.84)}/{d.size}, > 2.71 in {np.sum(d > 2.71)}/{d.size}, "
                f"95 % point {np.quantile(d, 0.95):.2f}"
            )
    print(f"CPU of this process {time.process_time() - t0:.0f} s (the workers' not counted)")


if __name__ == "__main__":
    main()
