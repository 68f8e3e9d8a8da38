"""Figures of the command line: a fit (data and model, residuals, profile likelihoods), a
sweep (a lambda x sigma map of the radius at the last time), a simulation."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .model import simulate  # noqa: E402
from .objective import NAMES  # noqa: E402

LABELS = {"R0_um": "R₀ (µm)", "sigma": "σ", "lambda": "λ", "T_s": "T (s)"}


def fit_figure(result, radius, profile, path):
    R0, sigma, lam, T = result.theta
    fig = plt.figure(figsize=(12, 7.5), layout="constrained")
    grid = fig.add_gridspec(2, 4)
    ax = fig.add_subplot(grid[0, :2])
    t = np.asarray(radius.times_s)
    fine = np.linspace(0, t.max(), 400)
    sim = simulate(fine, lam=lam, sigma=sigma, R0_um=R0, T_s=T, outer_radius_um=result.outer_radius_um)
    ax.plot(t, radius.radius_um, "o", ms=4, label="data")
    ax.plot(fine, sim.radius_um, "-", label="fit")
    ax.axhline(R0 * (1 + sigma / 6), ls=":", c="gray", label="R₁ = R₀(1 + σ/6)")
    ax.set(xlabel="time since the cut (s)", ylabel="wound radius (µm)")
    ax.legend(loc="lower right")
    ax = fig.add_subplot(grid[0, 2])
    fitted = simulate(t, lam=lam, sigma=sigma, R0_um=R0, T_s=T, outer_radius_um=result.outer_radius_um).radius_um
    ax.plot(t, np.asarray(radius.radius_um) - fitted, "o", ms=4)
    ax.axhline(0, c="gray", lw=0.8)
    ax.set(xlabel="time (s)", ylabel="radius residual (µm)")
    ax = fig.add_subplot(grid[0, 3])
    if profile is not None:
        for time in np.unique(profile.times_s):
            sel = np.asarray(profile.times_s) == time
            r = np.asarray(profile.r_um)[sel]
            line, = ax.plot(r, np.asarray(profile.velocity_um_s)[sel], "o", ms=4, label=f"t = {time:g} s")
            rr = np.linspace(r.min(), r.max(), 200)
            model = simulate([time], lam=lam, sigma=sigma, R0_um=R0, T_s=T, outer_radius_um=result.outer_radius_um,
                             radii_um=rr)
            ax.plot(rr, model.velocity_um_s[0], "-", c=line.get_color())
        ax.set(xlabel="distance from the centre (µm)", ylabel="tissue velocity (µm/s)")
        ax.legend(loc="upper right")
    else:
        ax.axis("off")
        ax.text(0.05, 0.5, "no velocity profile given", transform=ax.transAxes)
    for k, name in enumerate(NAMES):
        ax = fig.add_subplot(grid[1, k])
        rep = result.reports[name]
        if rep.profile is not None:
            v, d = np.array(rep.profile.points).T
            ax.plot(v, d, "o-", ms=3)
            ax.axhline(result.threshold, ls="--", c="gray", label="95 % threshold")
            lo, hi = rep.ci95
            for end in (lo, hi):
                if end is not None:
                    ax.axvline(end, c="C3", lw=0.8)
        ax.set(xlabel=LABELS[name], ylabel="Δχ² (profile)",
               title=f"{LABELS[name]}: {'identified' if rep.identifiable else 'not identified'}")
        if k == 0:
            ax.legend(loc="upper center")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def sweep_figure(df, path):
    first = df[df.R_inf == df.R_inf.iloc[0]]
    last = first[first.time == first.time.max()]
    lams, sigmas = np.unique(last["lambda"]), np.unique(last.sigma)
    fig, ax = plt.subplots(figsize=(6.5, 5), layout="constrained")
    if lams.size > 1 and sigmas.size > 1:
        table = last.pivot_table(index="sigma", columns="lambda", values="wound_radius")
        # One cell per value, whatever the spacing (the values label the cells).
        mesh = ax.pcolormesh(np.arange(table.shape[1] + 1), np.arange(table.shape[0] + 1), table.values)
        ax.set_xticks(np.arange(table.shape[1]) + 0.5, [f"{v:g}" for v in table.columns])
        ax.set_yticks(np.arange(table.shape[0]) + 0.5, [f"{v:g}" for v in table.index])
        fig.colorbar(mesh, ax=ax, label=f"wound radius at t = {last.time.iloc[0]:g}")
        ax.set(xlabel="λ", ylabel="σ", title=f"R_inf = {first.R_inf.iloc[0]:g}")
    else:
        for (lam, sigma), rows in first.groupby(["lambda", "sigma"]):
            ax.plot(rows.time, rows.wound_radius, "o-", ms=3, label=f"λ = {lam:g}, σ = {sigma:g}")
        ax.set(xlabel="time", ylabel="wound radius")
        ax.legend(loc="lower right", fontsize="small")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def simulate_figure(sim, path):
    fig, axes = plt.subplots(1, 2 if sim.radii_um is not None else 1, figsize=(11, 4.2), layout="constrained",
                             squeeze=False)
    ax = axes[0, 0]
    ax.plot(sim.times_s, sim.radius_um, "-o", ms=3)
    ax.set(xlabel="time since the cut (s)", ylabel="wound radius (µm)")
    if sim.radii_um is not None:
        ax = axes[0, 1]
        for i, t in enumerate(sim.times_s[:: max(1, len(sim.times_s) // 5)]):
            k = list(sim.times_s).index(t)
            ax.plot(sim.radii_um, sim.velocity_um_s[k], label=f"t = {t:g} s")
        ax.set(xlabel="distance from the wound centre (µm)", ylabel="tissue velocity (µm/s)")
        ax.legend(loc="upper right")
    fig.savefig(path, dpi=120)
    plt.close(fig)
