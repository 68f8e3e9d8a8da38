"""Figures of the command line's sweep and simulate (a fit's: plots.py). Every axis carries
its unit.

sweep_figure: the opening fraction f(t) = (R - R1) / (R_final - R1) of every (lambda, R_inf)
of the sweep (the sweep's values as markers on the model's curve), coloured by lambda, and
the half-opening time against lambda. With a free edge R - R1 is proportional to sigma, so
both depend on lambda and R_inf only (sigma sets the size of the opening, not its timing).
"""

from __future__ import annotations

import matplotlib
import numpy as np

from ..model import half_opening_time, opening_fraction
from .plots import plt, time_axis
from .status import radii


def sweep_figure(df, path, *, R0_um: float | None = None, T_s: float | None = None):
    """The sweep's opening fraction and half-opening time (module docstring). Physical
    columns (time_s, wound_radius_um) need R0_um and T_s, taken from df.attrs by default."""
    physical = "time_s" in df.columns
    R0 = R0_um or df.attrs.get("R0_um", 1.0)
    T = T_s or df.attrs.get("T_s", 1.0)
    time, radius = ("time_s", "wound_radius_um") if physical else ("time", "wound_radius")
    t_unit = " (s)" if physical else " (in T)"
    rows = df[df.sigma != 0]
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8), layout="constrained")
    lams = np.unique(df["lambda"])
    positive = lams[lams > 0]
    if (
        positive.size > 1 and positive.max() > 10 * positive.min()
    ):  # lambda spanning decades: log colours
        norm = (
            matplotlib.colors.SymLogNorm(positive.min(), linscale=0.5, vmin=0, vmax=lams.max())
            if lams.min() == 0
            else matplotlib.colors.LogNorm(lams.min(), lams.max())
        )
    else:
        norm = matplotlib.colors.Normalize(
            lams.min(), lams.max() if lams.max() > lams.min() else lams.min() + 1
        )
    cmap = plt.get_cmap("viridis")
    t_all = np.unique(df[time]) / T
    last = max(t_all.max(), 1e-12)
    first = t_all[t_all > 0].min() / 10 if np.any(t_all > 0) else last / 1e3
    tau = np.unique(np.concatenate([np.linspace(0, first, 20), np.geomspace(first, last, 200)]))
    styles = ["-", "--", ":", "-."]
    r_infs = np.unique(df.R_inf)
    for (lam, r_inf), group in rows.groupby(["lambda", "R_inf"]):
        colour = cmap(norm(lam))
        style = styles[int(np.searchsorted(r_infs, r_inf)) % len(styles)]
        a.plot(tau * T, opening_fraction(lam, r_inf, tau), style, c=colour, lw=1.2)
        first = group[group.sigma == group.sigma.iloc[0]]
        ends = radii(R0, first.sigma.to_numpy(), R0 * r_inf)
        R1, Rf = ends["R1_um"], ends["R_final_um"]
        a.plot(first[time], (first[radius] - R1) / (Rf - R1), "o", ms=4, c=colour)
    time_axis(a, tau * T)
    a.set(
        xlabel="time since the cut" + t_unit,
        ylabel="opening fraction (R − R₁)/(R_final − R₁)",
        title="the sweep's values (markers) on the model's curves",
    )
    fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), ax=a, label="λ")
    if r_infs.size > 1:
        for k, r_inf in enumerate(r_infs[: len(styles)]):
            a.plot([], [], styles[k], c="k", label=f"R_inf = {r_inf:g}")
        a.legend(loc="upper left", fontsize="small")
    fine = lams
    if positive.size and lams.size > 1:
        fine = np.unique(np.concatenate([lams, np.geomspace(positive.min(), lams.max(), 60)]))
    for k, r_inf in enumerate(r_infs):
        b.plot(
            fine,
            [half_opening_time(lam, r_inf) * T for lam in fine],
            "-",
            c=f"C{k}",
            label=f"R_inf = {r_inf:g}",
        )
        b.plot(
            lams,
            [half_opening_time(lam, r_inf) * T for lam in lams],
            "o",
            ms=5,
            c=f"C{k}",
            label="the sweep's λ" if k == 0 else None,
        )
    if positive.size and lams.max() > 10 * positive.min():
        b.set_xscale(
            "symlog" if lams.min() == 0 else "log",
            **({"linthresh": positive.min()} if lams.min() == 0 else {}),
        )
        b.set_yscale("log")
    b.set(
        xlabel="λ (viscous length / R₀)",
        ylabel="half-opening time" + t_unit,
        title="time to half the final opening (any σ)",
    )
    b.legend(loc="upper left", fontsize="small")
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return fig


def simulate_figure(sim, path):
    """Radius and edge velocity against time (linear to the first time, log beyond) and, with
    radii, the tissue velocity against the distance from the centre at a few times."""
    n = 3 if sim.radii_um is not None else 2
    fig, axes = plt.subplots(1, n, figsize=(5 * n, 4.2), layout="constrained")
    axes[0].plot(sim.times_s, sim.radius_um, "-o", ms=3)
    axes[0].set(xlabel="time since the cut (s)", ylabel="wound radius (µm)")
    finite = np.isfinite(sim.edge_velocity_um_s)
    axes[1].plot(
        np.asarray(sim.times_s)[finite], np.asarray(sim.edge_velocity_um_s)[finite], "-o", ms=3
    )
    axes[1].set(xlabel="time since the cut (s)", ylabel="edge velocity dR/dt (µm/s)")
    for ax in axes[:2]:
        time_axis(ax, sim.times_s)
    if sim.radii_um is not None:
        for t in sim.times_s[:: max(1, len(sim.times_s) // 5)]:
            k = list(sim.times_s).index(t)
            axes[2].plot(sim.radii_um, sim.velocity_um_s[k], "-o", ms=3, label=f"t = {t:g} s")
        axes[2].set(xlabel="distance from the wound centre (µm)", ylabel="tissue velocity (µm/s)")
        axes[2].legend(loc="upper right")
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return fig
