"""Speed of the wound_opening package against the fmpy FMU path, measured side by side in
one run. Writes OUT/benchmarks_fitting.csv and prints a markdown table.

    curve_package       simulate(): 40 times of a new (lambda, sigma, T) at a fixed outer radius
    curve_native        the same through wo_series alone (one ctypes call)
    curve_fmpy_instance a reused fmpy FMU2Slave: instantiate, parameters, 40 doStep + getReal, free
    curve_fmpy_simulate fmpy.simulate_fmu of the same 40 output points (extracts the FMU each call)
    fit_4_parameters    fit() of R0, sigma, lambda, T to 40 radii without intervals
    fit_with_intervals  the same with the four profile likelihoods and the three derived ones
    fit_radius_piv      40 radii + a PIV profile (bench/fit_designs.py "piv"), no intervals
    fit_radius_piv_4_intervals  the same with the four parameter profiles (derived=False)
    fit_radius_piv_intervals    the same with the four parameter profiles and the three derived ones
    fit_fmpy_scipy_radii  fmpy + scipy.optimize.least_squares on the same 40 radii (no intervals)
    sweep_1e5_grid      1e5 rows on one process: 100 lambda x 100 sigma x 10 times
    sweep_1e5_pairs     1e5 rows on one process: 10^4 lambda (distinct solves) x 10 times
    dask_1_worker, dask_2_workers   a 4e5-pair sweep on a LocalCluster of 1 and 2 single-thread
    workers

Medians of wall-clock times (time.perf_counter) over repeats, of CPU times (time.process_time)
for the fits; run on an otherwise idle machine.

    python python/bench/fitting_bench.py --fmu target/fmu/WoundOpening.fmu --out docs
"""

from __future__ import annotations

import argparse
import csv
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))

import wound_exact as we  # noqa: E402

import wound_opening as wo  # noqa: E402
from wound_opening import _native  # noqa: E402

R0, T, OUTER = 10.0, 10.0, 100.0
TIMES = np.linspace(1.5, 60.0, 40)


def median_time(f, repeats, clock=time.perf_counter):
    samples = []
    for k in range(repeats):
        start = clock()
        f(k)
        samples.append(clock() - start)
    return statistics.median(samples)


def fmpy_runner(fmu: str):
    """run(values, times, outputs): one instantiate, the parameters ("lambda", "sigma",
    "R_inf", "R0", "T"), doStep to each time + getReal of `outputs`, free, on an FMU2Slave
    of the FMU unzipped once. Returns the rows of outputs."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(fmu)
    unzip = extract(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}

    def run(values, times, outputs):
        s = FMU2Slave(
            guid=md.guid,
            unzipDirectory=unzip,
            modelIdentifier=md.coSimulation.modelIdentifier,
            instanceName="bench",
        )
        s.instantiate()
        s.setupExperiment(startTime=0.0)
        s.setReal([vr[n] for n in ("lambda", "sigma", "R_inf", "R0", "T")], values)
        s.enterInitializationMode()
        s.exitInitializationMode()
        t, out = 0.0, []
        for t_next in times:
            s.doStep(t, t_next - t)
            t = t_next
            out.append(s.getReal([vr[n] for n in outputs]))
        s.terminate()
        s.freeInstance()
        return out

    return run


def fmpy_paths(fmu: str):
    from fmpy import simulate_fmu

    run = fmpy_runner(fmu)

    def instance(k):
        return run(
            [0.5 + 1e-4 * k, 0.5, OUTER / R0, R0, T], TIMES, ["wound_radius", "edge_velocity"]
        )

    def simulate(k):
        return simulate_fmu(
            fmu,
            start_values={
                "lambda": 0.5 + 1e-4 * k,
                "sigma": 0.5,
                "R_inf": OUTER / R0,
                "R0": R0,
                "T": T,
            },
            stop_time=60.0,
            output_interval=1.5,
            output=["wound_radius", "edge_velocity"],
        )

    return instance, simulate


def fmpy_fit(fmu: str, radius, outer: float):
    """The fit an fmpy user would write: scipy.optimize.least_squares (trf, 2-point
    differences, default tolerances) over (ln R0, sigma, lambda >= 0, ln T), one
    instantiate + 40 doStep of a reused unzipped FMU2Slave per evaluation, residuals
    (R - data) / noise. The FMU gives the wound radius and the edge velocity, not the tissue
    velocity at a PIV position, so it fits the radii alone; no intervals. Started from
    R0 = 0.9 x the first radius, sigma 0.3, lambda 1, T 5 s. Returns (theta, chi^2, FMU runs)."""
    from scipy import optimize

    run = fmpy_runner(fmu)
    times = np.asarray(radius.times_s, float)
    data, sd = np.asarray(radius.radius_um, float), radius.noise_um
    runs = [0]

    def residuals(z):
        R0_, sigma, lam, T_ = np.exp(z[0]), z[1], z[2], np.exp(z[3])
        runs[0] += 1
        return (
            np.array(run([lam, sigma, outer / R0_, R0_, T_], times, ["wound_radius"]))[:, 0] - data
        ) / sd

    z0 = np.array([np.log(0.9 * data[0]), 0.3, 1.0, np.log(5.0)])
    lower = [np.log(0.01 * data.min()), -np.inf, 0.0, np.log(1e-3)]
    upper = [np.log(outer / 1.001), np.inf, 50.0, np.log(1e4)]
    res = optimize.least_squares(residuals, z0, bounds=(lower, upper), method="trf", x_scale="jac")
    theta = (float(np.exp(res.x[0])), float(res.x[1]), float(res.x[2]), float(np.exp(res.x[3])))
    return theta, float(2 * res.cost), runs[0]


def fit_rows(record, fmu: str | None = None) -> None:
    """Fits, medians of the CPU time of this process (time.process_time: one core,
    insensitive to other jobs): 40 radii (noise estimated) with and without intervals;
    40 radii + PIV without intervals, with the four parameter profiles, and with the
    derived ones too; the fmpy + SciPy fit of the same radii (if `fmu`)."""
    cpu = time.process_time
    rng = np.random.default_rng(5)
    clean = R0 * we.edge(0.5, 0.5, OUTER / R0, TIMES / T)[0]
    draws = [
        wo.RadiusSeries(TIMES, clean + 0.05 * rng.standard_normal(TIMES.size)) for _ in range(20)
    ]
    record(
        "fit_4_parameters",
        median_time(lambda k: wo.fit(draws[k], outer_radius_um=OUTER, intervals=False), 10, cpu),
        "CPU: 40 radii, 0.05 um noise (~2 % of the opening, estimated), grid + 4 local starts",
    )
    record(
        "fit_with_intervals",
        median_time(lambda k: wo.fit(draws[k], outer_radius_um=OUTER), 5, cpu),
        "CPU: the same with the 4 profile likelihoods and 3 of derived values",
    )
    from bench.fit_designs import clean as design_data
    from bench.fit_designs import draw

    piv = design_data("piv", 0.5)
    piv_draws = [draw("piv", 0.5, 1e-2, 50 + k, piv) for k in range(10)]
    what = "CPU: 40 radii + 24 PIV vectors (edge ones included), noise 1 % given"
    record(
        "fit_radius_piv",
        median_time(
            lambda k: wo.fit(*piv_draws[k], outer_radius_um=OUTER, intervals=False), 10, cpu
        ),
        what + ", no intervals",
    )
    record(
        "fit_radius_piv_4_intervals",
        median_time(lambda k: wo.fit(*piv_draws[k], outer_radius_um=OUTER, derived=False), 10, cpu),
        what + ", the 4 parameter profiles",
    )
    record(
        "fit_radius_piv_intervals",
        median_time(lambda k: wo.fit(*piv_draws[k], outer_radius_um=OUTER), 10, cpu),
        what + ", the 4 parameter profiles and the 3 derived ones",
    )
    if fmu is None:
        return
    theta = {}

    def peer(k):
        theta[k] = fmpy_fit(fmu, piv_draws[k][0], OUTER)

    seconds = median_time(peer, 5, cpu)
    chi2_peer = statistics.median(t[1] for t in theta.values())
    chi2_own = statistics.median(
        wo.fit(piv_draws[k][0], outer_radius_um=OUTER, intervals=False).chi2 for k in theta
    )
    record(
        "fit_fmpy_scipy_radii",
        seconds,
        f"CPU: fmpy + scipy least_squares on the same 40 radii alone (the FMU has no PIV output), "
        f"no intervals; "
        f"median {statistics.median(t[2] for t in theta.values())} FMU runs, chi^2 {chi2_peer:.4g} "
        f"(package's radius-only fit: {chi2_own:.4g})",
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu", default=str(ROOT / "target" / "fmu" / "WoundOpening.fmu"))
    ap.add_argument("--out", default=str(ROOT / "docs"))
    ap.add_argument(
        "--only-fit", action="store_true", help="only the fit rows, printed (nothing written)"
    )
    ap.add_argument(
        "--fmpy", action="store_true", help="with --only-fit: also the fmpy + SciPy fit"
    )
    args = ap.parse_args()
    rows = []

    def record(what, seconds, note):
        rows.append((what, seconds, note))
        print(f"{what:<22} {seconds * 1e3:12.4f} ms  {note}", flush=True)

    if args.only_fit:
        return fit_rows(record, args.fmu if args.fmpy else None)
    wo.simulate(
        TIMES, lam=0.5, sigma=0.5, R0_um=R0, T_s=T, outer_radius_um=OUTER
    )  # basis of R_inf = 10 cached
    record(
        "curve_package",
        median_time(
            lambda k: wo.simulate(
                TIMES,
                lam=0.5 + 1e-6 * k,
                sigma=0.5 + 1e-6 * k,
                R0_um=R0,
                T_s=T + 1e-6 * k,
                outer_radius_um=OUTER,
            ),
            2000,
        ),
        "40 times, new (lambda, sigma, T) each call",
    )
    record(
        "curve_native",
        median_time(lambda k: _native.series(0.5 + 1e-6 * k, 0.5, 10.0, TIMES / T), 2000),
        "wo_series through ctypes",
    )
    instance, simulate = fmpy_paths(args.fmu)
    record("curve_fmpy_instance", median_time(instance, 200), "FMU2Slave reused unzip, 40 doStep")
    record("curve_fmpy_simulate", median_time(simulate, 20), "fmpy.simulate_fmu, 40 output points")

    fit_rows(record, args.fmu)

    times10 = np.array([0.0, 0.1, 0.3, 1, 3, 10, 30, 100, 300, 1000])
    grid = {"lambda": np.linspace(0, 10, 100), "sigma": np.linspace(0.1, 2, 100), "R_inf": [10.0]}
    record(
        "sweep_1e5_grid",
        median_time(lambda k: wo.sweep(grid, times=times10, processes=1, progress=False), 3),
        "100 x 100 x 10 times: 100 solves",
    )
    pairs = {"lambda": np.linspace(0, 10, 10_000), "sigma": [1.0], "R_inf": [10.0]}
    record(
        "sweep_1e5_pairs",
        median_time(lambda k: wo.sweep(pairs, times=times10, processes=1, progress=False), 3),
        "10^4 lambda x 10 times: 10^4 solves",
    )

    from distributed import Client, LocalCluster

    big = {"lambda": np.linspace(0, 10, 400_000), "sigma": [1.0], "R_inf": [10.0]}
    for n in (1, 2):
        with (
            LocalCluster(
                n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            wo.sweep(
                {"lambda": [1.0], "sigma": [1.0], "R_inf": [10.0]},
                times=times10,
                scheduler=client.scheduler.address,
            )
            seconds = median_time(
                lambda k: wo.sweep(
                    big, times=times10, scheduler=cluster.scheduler_address, progress=False
                ),
                2,
            )
        record(
            f"dask_{n}_worker{'s' if n > 1 else ''}", seconds, "4e5 lambda x 10 times (4e6 rows)"
        )
    speedup = rows[-2][1] / rows[-1][1]
    print(f"dask speed-up 1 -> 2 workers: {speedup:.2f}")

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "benchmarks_fitting.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["what", "seconds", "note"])
        w.writerows([(a, f"{b:.6g}", c) for a, b, c in rows])
    print("\n| what | time | note |\n|---|---|---|")
    for a, b, c in rows:
        shown = f"{b * 1e6:.1f} us" if b < 1e-3 else f"{b * 1e3:.2f} ms" if b < 1 else f"{b:.2f} s"
        print(f"| {a} | {shown} | {c} |")
    print(f"\nDask speed-up from 1 to 2 workers: {speedup:.2f}")


if __name__ == "__main__":
    main()
