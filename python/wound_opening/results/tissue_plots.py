"""The figure of a fit of several wounds (`fit_wounds`): every wound's radius data (error
bars: the noise used) and fitted curve overlaid, one colour per wound, on the single fit's
time axis (plots.time_axis), with the material values and their 95 % intervals written on
it; the normalised residuals (data - fit) / noise of every wound below (one scale for wounds
of different sizes); the PIV profiles when a wound has one; the profile likelihoods of the
shared material values (the points the interval walk evaluated) with the threshold and the
interval ends. The status (status.py) is the title, in its colour.
"""

from __future__ import annotations

import numpy as np

from .names import ETA, SHARED
from .numbers import interval, material_lines
from .plots import drawn_once, errorbar_points, goodness_lines, plt, side_by_side, time_axis
from .status import status

LABELS = {
    "viscous_length_um": "viscous length l (µm)",
    "tension_over_G": "tension/G",
    "zeta_over_G_s_per_um2": "ζ/G (s/µm²)",
    "eta_over_G_s": "η/G (s)",
}


def _text(result) -> str:
    """The shared material values and the goodness of fit, side by side (plots.side_by_side):
    the figure's bottom line, under the panels (in a box on the radius panel it hid data)."""
    return side_by_side([material_lines(result.material), goodness_lines(result)])


def _profile_panel(ax, result, name) -> None:
    rep = result.shared[name]
    label = LABELS[name]
    if rep.constraint.get("fixed") or rep.profile is None:
        why = "fixed" if rep.constraint.get("fixed") else "interval not computed"
        ax.text(0.5, 0.5, f"{label}\n{why}", ha="center", va="center", transform=ax.transAxes)
        ax.set(xticks=[], yticks=[], title=f"{label}: {why}")
        ax.title.set_fontsize("small")
        return
    pts = sorted([(rep.estimate, 0.0)] + [tuple(p) for p in rep.profile.points])
    x, y = np.array(pts, dtype=float).reshape(-1, 2).T
    ok = np.isfinite(y)
    ax.plot(x[ok], y[ok], "o-", ms=3, lw=1, label="profile (interval search)")
    ax.axhline(result.threshold, ls="--", c="gray", lw=0.8, label="95 % threshold")
    ax.axvline(rep.estimate, c="k", ls=":", lw=0.8)
    for e in rep.ci95:
        if e is not None:
            ax.axvline(e, c="C3", lw=0.8)
    top = float(np.max(y[ok])) if ok.any() else result.threshold
    ax.set_ylim(0, max(1.5 * result.threshold, min(top * 1.05, 4 * result.threshold)))
    lo, hi = rep.ci95
    verdict = "identified" if rep.identifiable else "not identified"
    ax.set(
        xlabel=label,
        ylabel="Δχ² (profile)",
        title=f"{label}: {interval(lo, hi, rep.estimate)}, {verdict}",
    )
    ax.title.set_fontsize("small")
    if name == SHARED[0]:
        ax.legend(loc="upper center", fontsize="x-small")


def tissue_figure(result, path=None):
    """The figure of a TissueFitResult (a failed one's: the model where it stopped) to
    `path` (a file name or a binary file object), returned (closed); drawn once for the
    report and `--plot` (plots.drawn_once)."""
    return drawn_once(result, "tissue", lambda: _draw(result), path, 110)


def _draw(result):
    tabs = result.tables(stopped=True)  # a failed fit: the curves where it stopped
    has_piv = any("profile" in t for t in tabs.values())
    fig = plt.figure(figsize=(13, 9), layout="constrained")
    grid = fig.add_gridspec(3, 4, height_ratios=[3, 1.2, 2.2])
    width = slice(0, 2) if has_piv else slice(0, 4)
    ax = fig.add_subplot(grid[0, width])
    res = fig.add_subplot(grid[1, width], sharex=ax)
    pax = fig.add_subplot(grid[0:2, 2:]) if has_piv else None
    times = []
    for k, (name, t) in enumerate(tabs.items()):
        colour = f"C{k % 10}"
        pts, curve = t["radius"], t["curve"]
        tt = pts.time_s.to_numpy()
        times.append(tt)
        flagged = pts.flagged.to_numpy(bool)
        ax.errorbar(
            tt, pts.radius_um, yerr=pts.sd_um, fmt="o", ms=3, lw=0.8, c=colour, label=str(name)
        )
        ax.plot(curve.time_s, curve.radius_um, "-", c=colour, lw=1.2)
        res.plot(tt, pts.normalised_residual, "o", ms=3, c=colour)
        if flagged.any():
            res.plot(tt[flagged], pts.normalised_residual[flagged], "o", ms=8, mfc="none", mec="C3")
        if pax is not None and "profile" in t:
            pv, pc = t["profile"], t["profile_curve"]
            errorbar_points(
                pax,
                pv.r_um.to_numpy(),
                pv.velocity_um_s.to_numpy(),
                pv.sd_um_s.to_numpy(),
                pv.flagged.to_numpy(bool),
                f"{name}",
            )
            for time in np.unique(pc.time_s):
                c = pc[pc.time_s == time]
                pax.plot(c.r_um, c.velocity_um_s, "-", c=colour, lw=1)
    time_axis(ax, np.concatenate(times))
    ax.set(ylabel="wound radius (µm)")
    ax.legend(loc="best", fontsize="small", title="wound (data ± noise, fit)")
    fig.supxlabel(_text(result), x=0.01, ha="left", fontsize="small", family="monospace")
    res.axhline(0, c="gray", lw=0.8)
    res.set(xlabel="time since the cut (s)", ylabel="(data − fit) / noise")
    if pax is not None:
        pax.set(
            xlabel="distance from the wound centre (µm)",
            ylabel="tissue velocity (µm/s)",
            title="PIV velocity profiles and fit",
        )
        pax.legend(loc="upper right", fontsize="small")
    for k, name in enumerate(SHARED + (ETA,)):
        _profile_panel(fig.add_subplot(grid[2, k]), result, name)
    st = status(result)
    failed = "" if result.converged else "FAILED fit (the model where it stopped): "
    fig.suptitle(
        f"{failed}{len(tabs)} wounds of one tissue: {st.text}", color=st.colour, fontsize="medium"
    )
    return fig
