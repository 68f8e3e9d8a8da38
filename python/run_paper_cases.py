"""Simulate the paper's three cases with the WoundOpening FMU and compare with the exact solution.

lambda = 0.1 (friction), 1 (intermediate), 10 (viscous); R_inf = 10, sigma = 1, edge
stress 0; t from 0 to 500 T on a log-ish grid of communication points.  fmpy's FMU2Slave
is the master.  Writes

    OUT/paper_cases.csv     lambda, time, wound_radius, edge_velocity,
                            wound_radius_exact, edge_velocity_exact
    OUT/wound_radius.png    R(t), log time axis, exact dashed; below, the error
    OUT/edge_velocity.png   dR/dt, log-log, exact dashed; below, the relative error

and prints the largest error per lambda at t >= 0.01: radius relative to the opening
R_final - R1, velocity relative to max(|v_exact|, (R_final - R1) / 100).  At t = 0 the
exact columns hold R1 and the velocity u_t(1, 0+) from its Bessel-function closed form.

    python python/run_paper_cases.py --fmu target/fmu/WoundOpening.fmu --out out
"""

from __future__ import annotations

import argparse
import csv
import shutil
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import scipy.special as sp  # noqa: E402
from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi2 import FMU2Slave  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import wound_exact  # noqa: E402

LAMBDAS = (0.1, 1.0, 10.0)
SIGMA, R_INF, T_END = 1.0, 10.0, 500.0
T_MIN = 0.01  # accuracy is measured from here on (velocity ~ t^-1/2 as t -> 0 at small lambda)


def time_grid() -> np.ndarray:
    """0, then steps 0.001 to 0.01, 0.01 to 1, 0.1 to 10, 0.5 to 500 (1180 steps)."""
    return np.unique(
        np.concatenate(
            [
                [0.0],
                np.arange(1, 11) / 1000.0,
                np.arange(1, 101) / 100.0,
                np.arange(10, 101) / 10.0,
                np.arange(20, int(T_END * 2) + 1) / 2.0,
            ]
        )
    )


def initial_velocity(lam: float) -> float:
    """u_t(1, 0+) for lambda > 0 (docs/model.md, "Exact results"): w = A I1(r/l) + B K1(r/l) with
    lambda^2 D w(1) = p - sigma (p = 0) and D w(R_inf) = 0."""
    k = 1.0 / lam
    d_i = lambda r: 2 * (2 * k * sp.i0(k * r) - sp.i1(k * r) / r)  # noqa: E731
    d_k = lambda r: -2 * (2 * k * sp.k0(k * r) + sp.k1(k * r) / r)  # noqa: E731
    a, b = np.linalg.solve(
        [[lam**2 * d_i(1.0), lam**2 * d_k(1.0)], [d_i(R_INF), d_k(R_INF)]], [-SIGMA, 0.0]
    )
    return a * sp.i1(k) + b * sp.k1(k)


def simulate(unzipdir: str, md, lam: float, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Run one case on the communication points `times` (times[0] = start time)."""
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(
        guid=md.guid,
        unzipDirectory=unzipdir,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName=f"lambda={lam:g}",
    )
    fmu.instantiate()
    try:
        fmu.setupExperiment(startTime=times[0], stopTime=times[-1])
        fmu.setReal(
            [vr["lambda"], vr["sigma"], vr["R_inf"], vr["edge_stress"]], [lam, SIGMA, R_INF, 0.0]
        )
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        out_vr = [vr["wound_radius"], vr["edge_velocity"]]
        rows = [fmu.getReal(out_vr)]
        for t, t_next in zip(times[:-1], times[1:]):
            fmu.doStep(t, t_next - t)
            rows.append(fmu.getReal(out_vr))
        fmu.terminate()
    finally:
        fmu.freeInstance()
    radius, velocity = np.array(rows).T
    return radius, velocity


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fmu", required=True, type=Path, help="path to WoundOpening.fmu")
    parser.add_argument("--out", required=True, type=Path, help="output directory")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    md = read_model_description(str(args.fmu))
    unzipdir = extract(str(args.fmu))
    times = time_grid()
    later = times >= T_MIN
    r1 = wound_exact.initial_radius(SIGMA)
    amplitude = wound_exact.final_radius(SIGMA, R_INF) - r1

    results = {}
    try:
        for lam in LAMBDAS:
            start = time.perf_counter()
            radius, velocity = simulate(unzipdir, md, lam, times)
            elapsed = time.perf_counter() - start
            r_exact = np.full(times.shape, r1)
            v_exact = np.full(times.shape, initial_velocity(lam))
            r_exact[1:], v_exact[1:] = wound_exact.edge(lam, SIGMA, R_INF, times[1:])
            results[lam] = radius, velocity, r_exact, v_exact

            err_r = np.abs(radius - r_exact)[later] / amplitude
            err_v = (np.abs(velocity - v_exact) / np.maximum(np.abs(v_exact), amplitude / 100))[
                later
            ]
            print(
                f"lambda = {lam:>4g}: {len(times) - 1} steps in {elapsed:.2f} s; max error at "
                f"t >= {T_MIN}: radius {err_r.max():.2e} (of R_final - R1, at t = "
                f"{times[later][err_r.argmax()]:g}), "
                f"velocity {err_v.max():.2e} (relative, at t = {times[later][err_v.argmax()]:g})"
            )
    finally:
        shutil.rmtree(unzipdir, ignore_errors=True)

    with open(args.out / "paper_cases.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(
            [
                "lambda",
                "time",
                "wound_radius",
                "edge_velocity",
                "wound_radius_exact",
                "edge_velocity_exact",
            ]
        )
        for lam, columns in results.items():
            for t, *values in zip(times, *columns):
                writer.writerow([f"{lam:g}", repr(float(t))] + [repr(float(x)) for x in values])

    # Okabe-Ito colours (distinguishable with the common colour-vision deficiencies).
    palette = ["#0072B2", "#D55E00", "#009E73"]
    for index, name, label, logy in (
        (0, "wound_radius", "wound radius R / R0", False),
        (1, "edge_velocity", "edge velocity dR/dt (R0 / T)", True),
    ):
        fig, (ax, err_ax) = plt.subplots(
            2, 1, figsize=(7, 6.5), sharex=True, gridspec_kw={"height_ratios": [2, 1]}
        )
        for k, (lam, columns) in enumerate(results.items()):
            color = palette[k % len(palette)]
            fmu, exact_values = columns[index][1:], columns[index + 2][1:]
            ax.plot(times[1:], fmu, color=color, lw=2.5, alpha=0.7, label=f"FMU, λ = {lam:g}")
            ax.plot(
                times[1:],
                exact_values,
                color="k",
                lw=0.8,
                ls="--",
                label="exact" if k == len(results) - 1 else None,
            )
            # Error as in the printed summary: radius over the opening, velocity relative
            # (with the floor), from t = T_MIN where the accuracy promise starts.
            scale = amplitude if index == 0 else np.maximum(np.abs(exact_values), amplitude / 100)
            err = np.abs(fmu - exact_values) / scale
            keep = times[1:] >= T_MIN
            err_ax.plot(
                times[1:][keep],
                np.maximum(err[keep], 1e-17),
                color=color,
                lw=1.5,
                label=f"λ = {lam:g}",
            )
        ax.set_xscale("log")
        if logy:
            ax.set_yscale("log")
            ax.set_ylim(1e-8, None)
        ax.set_ylabel(label)
        ax.set_title(
            f"Wound opening, R_inf = {R_INF:g} R0, σ = {SIGMA:g} G: FMU against the exact solution"
        )
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(loc="best", framealpha=0.9)
        err_ax.set_yscale("log")
        err_ax.set_ylim(1e-16, 1e-8)
        if index == 0:
            err_ax.axhline(1e-10, color="0.4", lw=1, ls=":")
            err_ax.text(times[1], 1.4e-10, "default tolerance 1e-10", fontsize=8, color="0.3")
        err_ax.set_ylabel(
            "error: "
            + (
                "|R − R_exact| / (R_final − R1)"
                if index == 0
                else "relative (floor (R_final − R1) / 100)"
            )
        )
        err_ax.set_xlabel("time t / T   (T = ζ R0² / 4G; errors from t = 0.01)")
        err_ax.grid(True, which="both", alpha=0.3)
        fig.tight_layout()
        fig.savefig(args.out / f"{name}.png", dpi=130)
        plt.close(fig)
    print(
        f"wrote {args.out / 'paper_cases.csv'}, {args.out / 'wound_radius.png'}, "
        f"{args.out / 'edge_velocity.png'}"
    )


if __name__ == "__main__":
    main()
