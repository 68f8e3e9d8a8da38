"""Stability maps (lambda against step size, colour = status) and the explicit limits chart.

Input: the Rust `stability.csv` (scheme, lambda, dt, points, status) and
`explicit_limits.csv` (points, lambda, dt_max_theory, dt_max_measured, lambda_max_theory,
lambda_max_measured). lambda = 0 cannot sit on a log axis: it is drawn as its own row
below the smallest positive lambda, labelled "0".
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

STATUSES = ("bounded", "oscillating", "unbounded")
COLOURS = ("#7fc97f", "#fdc086", "#d7301f")
MEANING = {
    "bounded": "bounded and monotone",
    "oscillating": "bounded, edge displacement not monotone",
    "unbounded": "blows up",
}


def edges(values: np.ndarray) -> np.ndarray:
    """Cell edges on a log scale: geometric midpoints, the ends mirrored."""
    logs = np.log10(values)
    mid = (logs[1:] + logs[:-1]) / 2
    return 10 ** np.r_[2 * logs[0] - mid[0], mid, 2 * logs[-1] - mid[-1]]


def lambda_axis(lams: list[float]) -> tuple[np.ndarray, str | None]:
    """Positive positions for the lambda rows (0 -> one step below the smallest positive)."""
    pos = sorted(x for x in lams if x > 0)
    if len(pos) < 2:
        pos = pos + [p * 10 for p in pos] or [1.0, 10.0]
    zero = 10 ** (2 * math.log10(pos[0]) - math.log10(pos[1])) if 0.0 in lams else None
    return np.array(([zero] if zero else []) + sorted(x for x in lams if x > 0)), zero


def scheme_map(ax, rows: list[dict], limits: list[dict]) -> None:
    lams = sorted({float(r["lambda"]) for r in rows})
    dts = np.array(sorted({float(r["dt"]) for r in rows}))
    ys, zero = lambda_axis(lams)
    grid = np.full((len(lams), len(dts)), np.nan)
    for r in rows:
        i, j = lams.index(float(r["lambda"])), int(np.searchsorted(dts, float(r["dt"])))
        grid[i, j] = STATUSES.index(r["status"])
    ax.pcolormesh(
        edges(dts),
        edges(ys),
        grid,
        cmap=ListedColormap(COLOURS),
        vmin=-0.5,
        vmax=2.5,
        edgecolors="white",
        linewidth=0.3,
    )
    ax.set_xscale("log")
    ax.set_yscale("log")
    if zero:
        ticks = [zero] + [
            10.0**k for k in range(math.ceil(math.log10(ys[1])), math.floor(math.log10(ys[-1])) + 1)
        ]
        ax.set_yticks(ticks, ["0"] + [f"$10^{{{round(math.log10(t))}}}$" for t in ticks[1:]])
        ax.minorticks_off()
    if limits:
        # Theory: dt_max(lambda) as a curve, lambda_max as a line (lambda = 0 on its row).
        lam = np.array([float(r["lambda"]) for r in limits])
        dt_max = np.array([float(r["dt_max_theory"]) for r in limits])
        y = np.where(lam > 0, lam, zero or np.nan)
        order = np.argsort(y)
        ax.plot(dt_max[order], y[order], "k--", lw=1.2, label="theory: dt_max(lambda)")
        ax.axhline(
            float(limits[0]["lambda_max_theory"]),
            color="k",
            ls=":",
            lw=1.2,
            label="theory: lambda_max",
        )
        ax.legend(fontsize=7, loc="upper right")
    ax.set_xlabel("time step dt (T)")
    ax.set_ylabel("lambda")


def plot_scheme(scheme: str, rows: list[dict], limits: list[dict], path) -> None:
    sizes = sorted({r["points"] for r in rows}, key=int)
    fig, axes = plt.subplots(
        1, len(sizes), figsize=(max(5.2 * len(sizes) + 1, 9.0), 4.8), squeeze=False
    )
    for ax, points in zip(axes[0], sizes):
        mine = [r for r in limits if r["points"] == points]
        scheme_map(ax, [r for r in rows if r["points"] == points], mine)
        ax.set_title(f"{scheme}, " + ("default mesh" if points == "0" else f"{points} points"))
    # Only the statuses that occur in this chart (an all-bounded map gets one entry).
    present = {r["status"] for r in rows}
    handles = [Patch(color=c, label=MEANING[s]) for s, c in zip(STATUSES, COLOURS) if s in present]
    fig.legend(handles=handles, loc="lower center", ncol=3, fontsize=9)
    fig.suptitle(f"Stability map: {scheme} (R_inf = 10, sigma = 1, edge stress 0)")
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_explicit_limits(limits: list[dict], path) -> None:
    """Left: dt_max against lambda per grid size; right: lambda_max against grid size."""
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.8))
    sizes = sorted({r["points"] for r in limits}, key=int)
    colours = plt.cm.viridis(np.linspace(0, 0.85, len(sizes)))
    for points, colour in zip(sizes, colours):
        mine = sorted(
            (r for r in limits if r["points"] == points), key=lambda r: float(r["lambda"])
        )
        lam = [float(r["lambda"]) for r in mine]
        left.plot(
            lam,
            [float(r["dt_max_theory"]) for r in mine],
            "-",
            color=colour,
            label=f"N = {points}: theory",
        )
        left.plot(
            lam,
            [float(r["dt_max_measured"]) for r in mine],
            "o",
            color=colour,
            mfc="none",
            label=f"N = {points}: measured",
        )
    left.set_yscale("log")
    left.set_xlabel("lambda")
    left.set_ylabel("largest stable dt (T)")
    left.set_title("Explicit scheme: step limit against lambda")
    left.legend(fontsize=7, ncol=2)
    per_size = [next(r for r in limits if r["points"] == p) for p in sizes]
    n = [int(p) for p in sizes]
    right.loglog(n, [float(r["lambda_max_theory"]) for r in per_size], "k-", label="theory")
    right.loglog(
        n, [float(r["lambda_max_measured"]) for r in per_size], "ro", mfc="none", label="measured"
    )
    right.set_xlabel("grid points N")
    right.set_ylabel("largest stable lambda (any dt)")
    right.set_title("Explicit scheme: lambda limit against grid size")
    right.legend(fontsize=8)
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
