"""Speed of the wound_opening package against the fmpy FMU path, measured side by side in
one run. Writes OUT/benchmarks_fitting.csv and prints a markdown table.

    curve_package       simulate(): 40 times of a new (lambda, sigma, T) at a fixed outer radius
    curve_native        the same through wo_series alone (one ctypes call)
    curve_fmpy_instance a reused fmpy FMU2Slave: instantiate, parameters, 40 doStep + getReal, free
    curve_fmpy_simulate fmpy.simulate_fmu of the same 40 output points (extracts the FMU each call)
    fit_4_parameters    fit() of R0, sigma, lambda, T to 40 radii without intervals
    fit_with_intervals  the same with the four profile likelihoods
    fit_radius_piv_intervals  40 radii + a PIV profile (bench/fit_designs.py "piv"), intervals
    sweep_1e5_grid      1e5 rows on one process: 100 lambda x 100 sigma x 10 times
    sweep_1e5_pairs     1e5 rows on one process: 10^4 lambda (distinct solves) x 10 times
    dask_1_worker, dask_2_workers   a 4e5-pair sweep on a LocalCluster of 1 and 2 single-thread workers

Medians of wall-clock times (time.perf_counter) over repeats; run on an otherwise idle machine.

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


def fmpy_paths(fmu: str):
    from fmpy import extract, read_model_description, simulate_fmu
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(fmu)
    unzip = extract(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}

    def instance(k):
        s = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier,
                      instanceName="bench")
        s.instantiate()
        s.setupExperiment(startTime=0.0)
        s.setReal([vr[n] for n in ("lambda", "sigma", "R_inf", "R0", "T")], [0.5 + 1e-4 * k, 0.5, OUTER / R0, R0, T])
        s.enterInitializationMode()
        s.exitInitializationMode()
        t, out = 0.0, []
        for t_next in TIMES:
            s.doStep(t, t_next - t)
            t = t_next
            out.append(s.getReal([vr["wound_radius"], vr["edge_velocity"]]))
        s.terminate()
        s.freeInstance()
        return out

    def simulate(k):
        return simulate_fmu(fmu, start_values={"lambda": 0.5 + 1e-4 * k, "sigma": 0.5, "R_inf": OUTER / R0,
                                               "R0": R0, "T": T},
                            stop_time=60.0, output_interval=1.5, output=["wound_radius", "edge_velocity"])

    return instance, simulate


def fit_rows(record) -> None:
    """Fits: 40 radii (noise estimated), with and without intervals; 40 radii + PIV. Medians
    of the CPU time of this process (time.process_time: one core, insensitive to other jobs)."""
    cpu = time.process_time
    rng = np.random.default_rng(5)
    clean = R0 * we.edge(0.5, 0.5, OUTER / R0, TIMES / T)[0]
    draws = [wo.RadiusSeries(TIMES, clean + 0.05 * rng.standard_normal(TIMES.size)) for _ in range(20)]
    record("fit_4_parameters", median_time(lambda k: wo.fit(draws[k], outer_radius_um=OUTER, intervals=False), 10, cpu),
           "CPU: 40 radii, 0.05 um noise (~2 % of the opening, estimated), grid + 4 local starts")
    record("fit_with_intervals", median_time(lambda k: wo.fit(draws[k], outer_radius_um=OUTER), 5, cpu),
           "CPU: the same with the 4 profile likelihoods and 3 of derived values")
    from bench.fit_designs import clean as design_data, draw

    piv = design_data("piv", 0.5)
    piv_draws = [draw("piv", 0.5, 1e-2, 50 + k, piv) for k in range(10)]
    record("fit_radius_piv_intervals", median_time(lambda k: wo.fit(*piv_draws[k], outer_radius_um=OUTER), 5, cpu),
           "CPU: 40 radii + 24 PIV vectors (edge ones included), noise 1 % given, all profiles")



def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu", default=str(ROOT / "target" / "fmu" / "WoundOpening.fmu"))
    ap.add_argument("--out", default=str(ROOT / "docs"))
    ap.add_argument("--only-fit", action="store_true", help="only the fit rows, printed (nothing written)")
    args = ap.parse_args()
    rows = []

    def record(what, seconds, note):
        rows.append((what, seconds, note))
        print(f"{what:<22} {seconds * 1e3:12.4f} ms  {note}", flush=True)

    if args.only_fit:
        return fit_rows(record)
    wo.simulate(TIMES, lam=0.5, sigma=0.5, R0_um=R0, T_s=T, outer_radius_um=OUTER)  # basis of R_inf = 10 cached
    record("curve_package", median_time(lambda k: wo.simulate(TIMES, lam=0.5 + 1e-6 * k, sigma=0.5 + 1e-6 * k, R0_um=R0,
                                                             T_s=T + 1e-6 * k, outer_radius_um=OUTER), 2000),
           "40 times, new (lambda, sigma, T) each call")
    record("curve_native", median_time(lambda k: _native.series(0.5 + 1e-6 * k, 0.5, 10.0, TIMES / T), 2000),
           "wo_series through ctypes")
    instance, simulate = fmpy_paths(args.fmu)
    record("curve_fmpy_instance", median_time(instance, 200), "FMU2Slave reused unzip, 40 doStep")
    record("curve_fmpy_simulate", median_time(simulate, 20), "fmpy.simulate_fmu, 40 output points")

    fit_rows(record)

    times10 = np.array([0.0, 0.1, 0.3, 1, 3, 10, 30, 100, 300, 1000])
    grid = {"lambda": np.linspace(0, 10, 100), "sigma": np.linspace(0.1, 2, 100), "R_inf": [10.0]}
    record("sweep_1e5_grid", median_time(lambda k: wo.sweep(grid, times=times10, processes=1, progress=False), 3),
           "100 x 100 x 10 times: 100 solves")
    pairs = {"lambda": np.linspace(0, 10, 10_000), "sigma": [1.0], "R_inf": [10.0]}
    record("sweep_1e5_pairs", median_time(lambda k: wo.sweep(pairs, times=times10, processes=1, progress=False), 3),
           "10^4 lambda x 10 times: 10^4 solves")

    from distributed import Client, LocalCluster

    big = {"lambda": np.linspace(0, 10, 400_000), "sigma": [1.0], "R_inf": [10.0]}
    for n in (1, 2):
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
                Client(cluster) as client:
            wo.sweep({"lambda": [1.0], "sigma": [1.0], "R_inf": [10.0]}, times=times10, scheduler=client.scheduler.address)
            seconds = median_time(lambda k: wo.sweep(big, times=times10, scheduler=cluster.scheduler_address,
                                                      progress=False), 2)
        record(f"dask_{n}_worker{'s' if n > 1 else ''}", seconds, "4e5 lambda x 10 times (4e6 rows)")
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
