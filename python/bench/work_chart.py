"""Work-precision charts: error against CPU time for the whole scenario, one chart per regime.

Rows come from the Rust `work_precision.csv` (one line per scheme, drawn in the order of
its resolutions) and from the peers' CSVs (sweeps over two settings, e.g. grid size and
rtol: every run is a faint point and the line joins the runs no other run beats in both
error and time). The FMU through fmpy at its default settings is one star per regime.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt

from bench import common

#: scheme -> (label, colour, marker); schemes not listed get matplotlib's next colour.
# Okabe-Ito colours (distinguishable with the common colour-vision deficiencies), and a
# distinct marker per method so that no series depends on its colour alone.
STYLE = {
    "modal": ("modal, degree 8, exact in time (default)", "#0072B2", "o"),
    "modal_linear": ("modal, linear elements", "#56B4E9", "v"),
    "trbdf2": ("TR-BDF2 on the Galerkin system", "#009E73", "s"),
    "paper": ("paper's scheme (Rust)", "#D55E00", "D"),
    "explicit": ("explicit (Rust)", "#7f7f7f", "x"),
    "paper_peer": ("paper's scheme, NumPy/SciPy peer", "#8c3a00", "d"),
    "scipy_BDF": ("SciPy peer: FD + solve_ivp BDF", "#CC79A7", "^"),
    "scipy_LSODA": ("SciPy peer: FD + solve_ivp LSODA", "#F0E442", "<"),
    "scipy_DOP853": ("SciPy peer: FD + solve_ivp DOP853", "#E69F00", ">"),
    "fmpy": ("modal through fmpy (FMU, default settings)", "black", "*"),
}
ERROR_TARGET, TIME_TARGET = 1e-9, 1e-3


def pareto(points: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """The (error, seconds) points that no other point beats in both, by rising error."""
    front, best = [], math.inf
    for err, sec in sorted(points):
        if sec < best:
            front.append((err, sec))
            best = sec
    return front


def finite(rows: list[dict]) -> list[dict]:
    return [r for r in rows if math.isfinite(float(r["error"])) and float(r["error"]) > 0]


def plot_regime(lam: str, rust: list[dict], peers: list[dict], fmpy: list[dict], path) -> None:
    fig, ax = plt.subplots(figsize=(9.5, 6.5))
    schemes = list(dict.fromkeys(r["scheme"] for r in rust + peers))
    for scheme in schemes:
        label, colour, marker = STYLE.get(scheme, (scheme, None, "o"))
        mine = finite([r for r in rust if r["scheme"] == scheme and r["lambda"] == lam])
        theirs = finite([r for r in peers if r["scheme"] == scheme and r["lambda"] == lam])
        if mine:
            xs = [float(r["error"]) for r in mine]
            ys = [float(r["cpu_seconds"]) for r in mine]
            ax.plot(xs, ys, marker=marker, color=colour, label=label, lw=1.6, ms=6)
        if theirs:
            pts = [(float(r["error"]), float(r["cpu_seconds"])) for r in theirs]
            ax.scatter(*zip(*pts), marker=marker, color=colour, alpha=0.25, s=22)
            front = pareto(pts)
            ax.plot(*zip(*front), marker=marker, color=colour, label=label, lw=1.6, ms=6)
    stars = [r for r in fmpy if r["what"] == "fmpy_scenario" and r["lambda"] == lam]
    if stars:
        label, colour, marker = STYLE["fmpy"]
        ax.scatter(
            [float(r["error"]) for r in stars],
            [float(r["seconds"]) for r in stars],
            marker=marker,
            color=colour,
            s=160,
            zorder=5,
            label=label,
        )
    ax.axvline(ERROR_TARGET, color="k", ls=":", lw=1)
    ax.axhline(TIME_TARGET, color="k", ls=":", lw=1)
    ax.annotate(
        "targets: error 1e-9, 1 ms",
        (ERROR_TARGET, TIME_TARGET),
        xytext=(4, 4),
        textcoords="offset points",
        fontsize=8,
    )
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("error: max over the 1000 communication points of |R - R_exact| / (R_final - R1)")
    ax.set_ylabel("CPU seconds, whole scenario (t in [0, 100], 1000 steps of 0.1)")
    ax.set_title(f"Work-precision, lambda = {lam} (R_inf = 10, sigma = 1)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
    fig.text(
        0.01,
        0.01,
        "Rust schemes: one point per resolution, in order. Peers: faint points "
        "= every run, line = runs no other run beats in both error and time.",
        fontsize=7,
    )
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(path, dpi=120)
    plt.close(fig)


def all_rows(rust: list[dict], peers: list[dict], fmpy: list[dict]) -> list[tuple]:
    """Everything on the charts as rows of docs/work_precision.csv."""
    rows = [tuple(r[c] for c in common.WORK_COLUMNS) for r in rust + peers]
    rows += [
        ("fmpy", r["lambda"], "default", "", r["error"], r["seconds"])
        for r in fmpy
        if r["what"] == "fmpy_scenario"
    ]
    return rows
