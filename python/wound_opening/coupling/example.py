"""The README's worked example: a wound of radius R0 = 10 um opens after the cut and an
actin purse-string then closes it, WoundOpening.fmu and PurseString.fmu (the archives the
package ships, `wound_opening.fmu_path`, or those of --fmu-dir) coupled by the fmpy loop of
wound_opening.coupling.loop (needs fmpy).

Tissue: G = 100 Pa, eta = 1000 Pa s (relaxation time eta / G = 10 s), zeta = 40 Pa s / um^2,
tension 100 Pa, outer radius 100 um  ->  lambda = 1, sigma = 1, R_inf = 10, T = 10 s.
Purse-string: T_max = 6.5 nN, delay 20 s, assembly time 30 s, sheet thickness 5 um.

Writes to OUT:
    coupled_closure.csv       t [s], wound_radius [um], edge_velocity [um/s],
                              edge_stress [Pa], line_tension [pN], free-opening radius [um]
    coupled_closure.png       radius with and without the purse-string; tension and stress
    coupled_convergence.csv   communication step, max |R(h) - R(h/2)| [um] and observed order,
                              with the edge stress held over each step (order 1) and passed
                              with its derivative (fmi2SetRealInputDerivatives: order 2)

    python -m wound_opening.coupling --out out      (or python python/coupled_example.py)
"""

from __future__ import annotations

import argparse
import csv
import math
from pathlib import Path

import numpy as np

from ..shipped import fmu_path
from .loop import MATERIAL_EXAMPLE, PURSE_EXAMPLE, WOUND_EXAMPLE, couple, observed_order
from .start import fmu_start_values

STEP, STOP = 0.5, 300.0
STEPS = (4.0, 2.0, 1.0, 0.5, 0.25, 0.125)


def equilibrium_radius() -> float:
    """Stable root of rho^2 - R_final rho + c A = 0 (tests/python/test_coupling.py), in um."""
    w, pe = WOUND_EXAMPLE, PURSE_EXAMPLE
    k = w["R_inf"] ** 2 / (w["R_inf"] ** 2 - 1)
    r1, rf = 1 + w["sigma"] / 6, 1 + 2 * w["sigma"] / 3 * k
    c = pe["T_max"] / (pe["thickness"] * w["R0"] * w["sigma"] * w["G"])
    return w["R0"] * (rf + math.sqrt(rf * rf - 4 * c * (rf - r1))) / 2


def plot(run, free, path: Path) -> None:
    from matplotlib.figure import Figure  # no pyplot: the caller's backend stays as it is

    fig = Figure(figsize=(7.5, 6.5))
    ax, bx = fig.subplots(2, 1, sharex=True, height_ratios=[3, 2])
    # Okabe-Ito colours (distinguishable with the common colour-vision deficiencies).
    blue, grey, vermillion, green, orange = "#0072B2", "#7f7f7f", "#D55E00", "#009E73", "#E69F00"
    ax.plot(run.time, run.wound_radius, color=blue, lw=2, label="with purse-string (coupled FMUs)")
    ax.plot(
        free.time,
        free.wound_radius,
        color=grey,
        ls="--",
        lw=1.5,
        label="free opening (edge_stress = 0)",
    )
    ax.axhline(
        equilibrium_radius(), color=vermillion, lw=1, ls=":", label="equilibrium with T_c = T_max"
    )
    ax.axhline(WOUND_EXAMPLE["R0"], color="k", lw=0.6)
    ax.set_ylabel("wound radius [µm]")
    # Centre right: between the free opening (above 16 µm there) and the closing wound (below 12).
    ax.legend(loc="center right", fontsize=9, framealpha=0.9)
    ax.set_title(
        "Wound R0 = 10 µm, τ = η/G = 10 s (λ = 1): opening, then purse-string closure", fontsize=10
    )
    bx.plot(run.time, run.line_tension / 1000.0, color=green, lw=2, label="line tension T_c [nN]")
    bx.set_ylabel("T_c [nN]")
    bx.set_xlabel("time since the cut [s]")
    cx = bx.twinx()
    cx.plot(
        run.time,
        run.edge_stress,
        color=orange,
        lw=1.5,
        ls="--",
        label="edge stress p = T_c/(h R) [Pa]",
    )
    cx.set_ylabel("p [Pa]")
    lines = bx.get_lines() + cx.get_lines()
    bx.legend(lines, [line.get_label() for line in lines], loc="center right", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def archives(fmu_dir: str | None) -> tuple[str, str]:
    """WoundOpening.fmu and PurseString.fmu: in `fmu_dir`, or the package's."""
    if fmu_dir is None:
        return str(fmu_path("WoundOpening.fmu")), str(fmu_path("PurseString.fmu"))
    paths = [Path(fmu_dir) / name for name in ("WoundOpening.fmu", "PurseString.fmu")]
    for path in paths:
        if not path.is_file():
            raise SystemExit(f"error: {path} not found (--fmu-dir {fmu_dir})")
    return str(paths[0]), str(paths[1])


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(
        prog="python -m wound_opening.coupling",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    ap.add_argument(
        "--fmu-dir",
        default=None,
        help="folder with WoundOpening.fmu and PurseString.fmu (default: the package's "
        "archives, wound_opening.fmu_path)",
    )
    ap.add_argument(
        "--out", default="out", help="folder for the CSV files and the chart (default: %(default)s)"
    )
    args = ap.parse_args(argv)
    wound, purse = archives(args.fmu_dir)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    derived = fmu_start_values(**MATERIAL_EXAMPLE)
    print("parameters from the material: " + ", ".join(f"{k} = {v:g}" for k, v in derived.items()))
    run = couple(wound, purse, step=STEP, stop=STOP, interpolate=True)
    free = couple(wound, None, step=STEP, stop=STOP, edge_stress=0.0)
    with open(out / "coupled_closure.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(
            [
                "time_s",
                "wound_radius_um",
                "edge_velocity_um_per_s",
                "edge_stress_Pa",
                "line_tension_pN",
                "free_wound_radius_um",
            ]
        )
        for row in zip(
            run.time,
            run.wound_radius,
            run.edge_velocity,
            run.edge_stress,
            run.line_tension,
            free.wound_radius,
        ):
            w.writerow([f"{x:.17g}" for x in row])
    plot(run, free, out / "coupled_closure.png")
    i = int(np.argmax(run.wound_radius))
    print(
        f"communication step {STEP} s: R(0) = {run.wound_radius[0]:.4f} um, max "
        f"{run.wound_radius[i]:.4f} um "
        f"at t = {run.time[i]:g} s, R({STOP:g} s) = {run.wound_radius[-1]:.4f} um "
        f"(free opening: {free.wound_radius[-1]:.4f} um; equilibrium with T_max: "
        f"{equilibrium_radius():.4f} um)"
    )

    _, diffs, orders = observed_order(wound, purse, STEPS, stop=STOP)
    _, diffs2, orders2 = observed_order(wound, purse, STEPS, stop=STOP, interpolate=True)
    with open(out / "coupled_convergence.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(
            [
                "step_s",
                "held_max_abs_R_h_minus_R_half_um",
                "held_observed_order",
                "interpolated_max_abs_R_h_minus_R_half_um",
                "interpolated_observed_order",
            ]
        )
        for k, (h, d, d2) in enumerate(zip(STEPS, diffs, diffs2)):
            order = orders[k - 1] if k > 0 else float("nan")
            order2 = orders2[k - 1] if k > 0 else float("nan")
            w.writerow([h, f"{d:.6g}", f"{order:.4f}", f"{d2:.6g}", f"{order2:.4f}"])
            print(
                f"step {h:6.3f} s: max |R(h) - R(h/2)| held {d:.3e} um, with input derivatives "
                f"{d2:.3e} um" + (f"; observed orders {order:.3f} and {order2:.3f}" if k else "")
            )
    print(
        f"wrote {out / 'coupled_closure.csv'}, {out / 'coupled_closure.png'}, "
        f"{out / 'coupled_convergence.csv'}"
    )


if __name__ == "__main__":
    main()
