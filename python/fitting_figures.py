"""Figures of docs/fitting.md, from synthetic experiments made with the exact solution
(python/wound_exact.py): R0 = 10 um, sigma = 0.5, lambda = 0.5, T = 10 s, outer radius 100 um.

    fitting_example.png         wound-opening fit of 30 radii (0.05 um noise) and a PIV profile
                                at 1 s and 3 s (5 % noise): data with error bars and the fit on a
                                symlog time axis, residuals, the PIV profile, the four profile
                                likelihoods (plots.fit_figure)
    sweep_example.png           a lambda x sigma sweep: opening fraction coloured by lambda and the
                                half-opening time (sim_plots.sweep_figure)
    fitting_identifiability.png lambda's profile likelihood from the radius alone (2 % noise,
                                a typical case) and with the velocity profile added; and
                                R(t) for scaled (G, eta, zeta): identical curves

    python python/fitting_figures.py --out docs
    python python/fitting_figures.py --data-only --out out   # the example's CSV files only
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import wound_exact as we  # noqa: E402

import wound_opening as wo  # noqa: E402
from wound_opening.results.plots import fit_figure  # noqa: E402

LAM, SIGMA, R0, T, OUTER = 0.5, 0.5, 10.0, 10.0, 100.0


def data(noise, seed, with_profile):
    rng = np.random.default_rng(seed)
    t = np.linspace(2.0, 60.0, 30)
    radius = wo.RadiusSeries(
        t, R0 * we.edge(LAM, SIGMA, OUTER / R0, t / T)[0] + noise * rng.standard_normal(t.size)
    )
    if not with_profile:
        return radius, None
    x, times = np.linspace(1.05, 6, 10), np.array([1.0, 3.0])
    u, v = we.profile(LAM, SIGMA, OUTER / R0, x, times / T)
    v = R0 / T * v
    return radius, wo.VelocityProfile(
        np.repeat(times, x.size),
        (R0 * (x + u)).ravel(),
        (v + 0.05 * np.abs(v).max() * rng.standard_normal(v.shape)).ravel(),
    )


def identifiability(path):
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
    for label, noise, with_profile in (
        ("radius alone, 2 % noise", 0.2, False),
        ("radius + velocity profile", 0.2, True),
    ):
        radius, profile = data(noise, 11, with_profile)
        result = wo.fit(radius, profile, outer_radius_um=OUTER, derived=False)
        v = np.concatenate([[0.0], np.geomspace(0.01, 50, 40)])
        d = result.profile_at("lambda", v)  # delta chi^2 by constrained fits at each lambda
        ok = np.isfinite(d)
        a.plot(
            v[ok],
            d[ok],
            "o-",
            ms=3,
            label=f"{label}: {'identified' if result.reports['lambda'].identifiable else 'flat'}",
        )
    a.axhline(result.threshold, ls="--", c="gray", label="95 % threshold")
    a.axvline(LAM, c="k", lw=0.8, label="true λ = 0.5")
    a.set_xscale("symlog", linthresh=0.01, linscale=0.5)
    a.set(
        xlabel="λ",
        ylabel="Δχ² (profile likelihood)",
        xlim=(0, 50),
        ylim=(0, 12),
        title="λ from R(t) alone, and with PIV",
    )
    a.legend(loc="upper right", fontsize="small")
    t = np.linspace(0, 60, 200)
    G, eta, zeta, tension = 100.0, 250.0, 40.0, 50.0  # Pa, Pa s, Pa s/µm², Pa
    for c, style in ((1.0, "-"), (10.0, "--"), (0.1, ":")):
        lam = 2 * np.sqrt(c * eta / (c * zeta)) / R0
        T_s = c * zeta * R0**2 / (4 * c * G)
        sim = wo.simulate(
            t, lam=lam, sigma=c * tension / (c * G), R0_um=R0, T_s=T_s, outer_radius_um=OUTER
        )
        b.plot(t, sim.radius_um, style, lw=2, label=f"G, η, ζ, tension × {c:g}")
    b.axhline(R0, c="gray", lw=0.8)
    b.text(1, R0 + 0.05, "R₀ (cut radius)", fontsize="small")
    b.axhline(R0 * (1 + tension / G / 6), c="gray", ls=":", lw=0.8)
    b.text(
        30,
        R0 * (1 + tension / G / 6) - 0.2,
        "R₁ = R₀(1 + σ/6): first radius measured",
        fontsize="small",
    )
    b.set(
        xlabel="time since the cut (s)",
        ylabel="wound radius (µm)",
        ylim=(R0 - 0.3, None),
        title="only ratios of G, η, ζ matter",
    )
    b.legend(loc="center right", fontsize="small")
    fig.savefig(path, dpi=120)
    plt.close(fig)


def write_data(radius, profile, out: Path):
    """The example experiment as the command line reads it."""
    import pandas as pd

    pd.DataFrame({"time_s": radius.times_s, "radius_um": radius.radius_um}).to_csv(
        out / "experiment_radius.csv", index=False
    )
    pd.DataFrame(
        {"time_s": profile.times_s, "r_um": profile.r_um, "velocity_um_s": profile.velocity_um_s}
    ).to_csv(out / "experiment_profile.csv", index=False)


def main():
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument(
        "--out",
        default="docs",
        help="folder for the figures or the CSV files (default: %(default)s)",
    )
    ap.add_argument(
        "--data-only", action="store_true", help="write experiment_radius.csv and _profile.csv only"
    )
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    radius, profile = data(0.05, 3, True)
    if args.data_only:
        write_data(radius, profile, out)
        return
    fit_figure(
        wo.fit(radius, profile, outer_radius_um=OUTER), radius, profile, out / "fitting_example.png"
    )
    identifiability(out / "fitting_identifiability.png")
    from wound_opening.results.sim_plots import sweep_figure

    grid = {"lambda": [0, 0.1, 0.3, 1, 3, 10], "sigma": [0.25, 0.5, 1, 2], "R_inf": [10, 30]}
    sweep_figure(wo.sweep(grid, times=[0, 1, 10, 100], processes=1), out / "sweep_example.png")


if __name__ == "__main__":
    main()
