"""Figures of a fit (a sweep's and a simulation's: sim_plots.py). Every axis carries its unit.

fit_figure: the radius on a time axis linear up to the first sampled time and logarithmic
beyond (symlog: the first seconds, where the timing information is, get as much width as
each later decade), with error bars (the given or estimated noise), flagged points marked
and the estimates with their 95 % profile intervals written on it; the residuals below; the
PIV profile only when there is one; each parameter's profile likelihood, drawn through the
points of its interval walk and, where the walk left gaps, through more of PROFILE_POINTS
evenly spaced values by constrained fits (FitResult.profile_at), on a log axis for R0,
lambda and T where the values span more than a decade.

"""

from __future__ import annotations

import io
import math
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import ticker  # noqa: E402

from .names import NAMES  # noqa: E402
from .numbers import interval  # noqa: E402

#: Height of a line of the estimates' strip (font "small", monospace) and its padding, in.
STRIP_LINE_IN, STRIP_PAD_IN = 0.16, 0.3


def side_by_side(groups, gap: int = 5) -> str:
    """Groups of lines as columns of one monospace text, each as wide as its longest line."""
    widths = [max(map(len, g)) for g in groups]
    return "\n".join(
        (" " * gap)
        .join(g[i].ljust(w) if i < len(g) else " " * w for g, w in zip(groups, widths))
        .rstrip()
        for i in range(max(map(len, groups)))
    )


def strip_height_in(groups) -> float:
    """The strip's height under the panels for these groups (`side_by_side`)."""
    return STRIP_PAD_IN + STRIP_LINE_IN * max(map(len, groups))


def estimates_strip(fig, groups, height_in: float):
    """The estimates under the panels, in columns (`side_by_side`), at the figure's bottom
    left: in a box on a data panel they hid points (the first ones of a fast opening, which
    sit high on the left of the log time axis, under a box at the top left; matplotlib's
    "best" place found no free one in a panel of a 120-frame recording)."""
    return fig.text(
        0.75 / fig.get_figwidth(),
        (height_in - 0.12) / fig.get_figheight(),
        side_by_side(groups),
        va="top",
        ha="left",
        fontsize="small",
        family="monospace",
    )


LABELS = {"R0_um": "R₀ (µm)", "sigma": "σ", "lambda": "λ", "T_s": "T (s)"}
SYMBOLS = {"R0_um": ("R₀", " µm"), "sigma": ("σ", ""), "lambda": ("λ", ""), "T_s": ("T", " s")}
#: Evenly spaced values of a profile panel: those with no point of the walk near are fitted.
PROFILE_POINTS = 8


def _g(x) -> str:
    return "open" if x is None else f"{x:.3g}"


def plain_ticks(axis, linthresh: float | None = None) -> None:
    """Ticks at 1, 2 and 5 per decade labelled as plain numbers (0.5, 2, 20) on a log or
    symlog axis, rather than powers of ten whose minor labels collide."""
    if linthresh is None:
        axis.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    else:
        axis.set_major_locator(
            ticker.SymmetricalLogLocator(base=10, linthresh=linthresh, subs=(1.0, 2.0, 5.0))
        )
    axis.set_major_formatter(ticker.FuncFormatter(lambda x, _: f"{x:g}"))
    axis.set_minor_formatter(ticker.NullFormatter())


def time_axis(ax, times) -> None:
    """Linear from 0 to the first positive time, logarithmic beyond (symlog)."""
    t = np.asarray(times, dtype=float)
    positive = t[t > 0]
    if positive.size:
        linthresh = 10 ** math.floor(math.log10(positive.min()))
        ax.set_xscale("symlog", linthresh=linthresh, linscale=0.5)
        ax.set_xlim(0, None)
        if positive.max() < 1e4 * linthresh:  # up to four decades: 1, 2, 5 per decade
            plain_ticks(ax.xaxis, linthresh)


def estimates_text(result) -> str:
    """The estimates with their 95 % profile intervals, and the goodness of fit."""
    return "\n".join(line for group in estimate_groups(result) for line in group)


def estimate_groups(result) -> tuple[list, list, list]:
    """(material values, the model's parameters, the goodness of fit): lines of text."""
    lines = []
    for name in NAMES:
        rep = result.reports[name]
        symbol, unit = SYMBOLS[name]
        if rep.constraint.get("fixed"):
            ci = "(fixed)"
        elif rep.profile is None:
            ci = "(interval not computed)"
        else:
            lo, hi = rep.ci95
            ci = interval(lo, hi, rep.estimate) + ("" if rep.identifiable else " not identified")
        lines.append(f"{symbol} = {rep.estimate:.4g}{unit}  {ci}")
    from .numbers import material_lines

    return material_lines(result.material), lines, goodness_lines(result)


def goodness_lines(result) -> list:
    """chi^2 per degree of freedom (and p where the noise is given), and what the intervals
    are: the last column of the estimates (one wound's or several's)."""
    fit = f"χ²/dof = {result.chi2:.3g}/{result.dof}"
    fit += f", p = {result.p_value:.2g}" if result.p_value is not None else " (noise estimated)"
    return [fit, "95 % profile-likelihood intervals"]


def errorbar_points(ax, x, y, sd, flagged, label, colour=None):
    """Points with error bars, the flagged ones circled; returns the points' colour."""
    bars = ax.errorbar(
        x, y, yerr=sd, fmt="o", ms=3, lw=0.8, capsize=0, label=label, zorder=2, c=colour
    )
    if np.any(flagged):
        named = "flagged (down-weighted)" in ax.get_legend_handles_labels()[1]
        ax.plot(
            x[flagged],
            y[flagged],
            "o",
            ms=9,
            mfc="none",
            mec="C3",
            mew=1.5,
            label=None if named else "flagged (down-weighted)",
            zorder=3,
        )
    return bars[0].get_color()


def fit_figure(
    result, radius=None, profile=None, path=None, *, profile_points: int = PROFILE_POINTS
):
    """The figure of a fit to `path` (a file name or a binary file object), returned
    (closed); a failed fit's shows the model where it stopped, the title its reasons. The
    data come from the result (radius, profile: accepted for the callers that pass them).
    A figure written once is kept with the result (its PNG bytes): the report's and the
    command line's `--plot` are one drawing."""
    draw = lambda: _draw(result, profile_points, noise_words(result, profile))  # noqa: E731
    return drawn_once(result, profile_points, draw, path, 120)


def noise_words(result, profile=None) -> tuple[str, str]:
    """How each data set's noise was had, as the figure and report say it: "estimated" (from
    the residuals), "outline's floor" (estimated below the readers' half pixel, which set it:
    inputs/fiji.py), "floor given" (below a floor a caller set: RadiusSeries.noise_floor_um),
    "ring scatter" (a PIV field's rings: the scatter of their vectors,
    not a noise given) or "given"."""
    estimated = result.points.get("noise_estimated", (not result.noise_given,) * 2)
    rings = any(f.kind == "ring averages" for f in getattr(profile, "files", ()))
    words = ["estimated" if e else "given" for e in estimated]
    if getattr(result, "radius_floor_um", None) is not None:
        words[0] = "outline's floor" if getattr(result, "radius_floor_said", "") else "floor given"
    if rings and not estimated[1]:
        words[1] = "ring scatter"
    return words[0], words[1]


#: A PIV panel's legend names each frame pair up to this many; beyond, the first and the
#: last and how many, the pairs coloured by time.
LEGEND_PAIRS = 6


#: Titles at the top of their axes, where the automatic placement (which measures every
#: tick label of the x axis to lift a title over ticks on top, which these figures do not
#: have) would put them too: a fifth of the drawing's time saved (0.44 -> 0.36 s measured).
FIXED_TITLES = {"axes.titley": 1.0}


def drawn_once(result, key, draw, path, dpi: int):
    """The figure `draw()` makes, written as PNG to `path` (a file name or a binary file
    object; None: not written), returned closed; a figure written once is kept with the
    result (`figures`: key -> (figure, PNG bytes)), so the report's and the command line's
    `--plot` are one drawing."""
    cache = result.figures
    if path is not None and key in cache:
        fig, png = cache[key]
    else:
        with plt.rc_context(FIXED_TITLES):
            fig = draw()
        png = None
        if path is not None:
            buf = io.BytesIO()
            fig.savefig(buf, dpi=dpi, format="png")
            png = buf.getvalue()
            cache[key] = fig, png
        plt.close(fig)
    if png is not None and hasattr(path, "write"):
        path.write(png)
    elif png is not None:
        with open(path, "wb") as f:
            f.write(png)
    return fig


def _draw(result, profile_points: int, noise=("given", "given")):
    tabs = result.tables(stopped=True)  # a failed fit: its curve where it stopped
    pts, curve = tabs["radius"], tabs["curve"]
    has_piv = "profile" in tabs
    profiles = [n for n in NAMES if result.reports[n].profile is not None]
    groups = estimate_groups(result)
    strip = strip_height_in(groups)
    height = (8.5 if profiles else 5.5) + strip
    fig = plt.figure(figsize=(12, height))
    grid = fig.add_gridspec(
        3 if profiles else 2,
        4,
        height_ratios=[3, 1.2, 2.4][: 3 if profiles else 2],
        **margins(12, height, 3 if profiles else 2, 4, top=0.75 if has_piv else 0.45, below=strip),
    )
    width = slice(0, 2) if has_piv else slice(0, 4)
    ax = fig.add_subplot(grid[0, width])
    t, flagged = pts.time_s.to_numpy(), pts.flagged.to_numpy(bool)
    errorbar_points(
        ax, t, pts.radius_um.to_numpy(), pts.sd_um.to_numpy(), flagged, f"data ± noise ({noise[0]})"
    )
    fitted = "fit" if result.converged else "model where the fit stopped (failed)"
    ax.plot(curve.time_s, curve.radius_um, "-", c="C1", label=fitted, zorder=1)
    R0, sigma = result.theta[:2]
    ax.axhline(R0 * (1 + sigma / 6), ls=":", c="gray", lw=0.8, label="R₁ = R₀(1 + σ/6)")
    time_axis(ax, t)
    ax.set(ylabel="wound radius (µm)")
    ax.legend(loc="best", fontsize="small")
    estimates_strip(fig, groups, strip)
    res = fig.add_subplot(grid[1, width], sharex=ax)
    errorbar_points(res, t, pts.residual_um.to_numpy(), pts.sd_um.to_numpy(), flagged, None)
    res.axhline(0, c="gray", lw=0.8)
    res.set(xlabel=time_label(result), ylabel="data − fit (µm)")
    if has_piv:
        pv, pc = tabs["profile"], tabs["profile_curve"]
        pax = fig.add_subplot(grid[0:2, 2:])
        times = np.unique(pv.time_s)
        many = times.size > LEGEND_PAIRS
        for k, time in enumerate(times):
            sel = (pv.time_s == time).to_numpy()
            named = not many or k in (0, times.size - 1)
            colour = errorbar_points(
                pax,
                pv.r_um.to_numpy()[sel],
                pv.velocity_um_s.to_numpy()[sel],
                pv.sd_um_s.to_numpy()[sel],
                pv.flagged.to_numpy(bool)[sel],
                f"t = {time:g} s" if named else None,
                plt.cm.viridis(k / (times.size - 1)) if many else None,
            )
            c = pc[pc.time_s == time]
            pax.plot(c.r_um, c.velocity_um_s, "-", c=colour)
        pax.plot([], [], " ", label=f"{times.size} frame pairs" + (", by time" if many else ""))
        pax.plot([], [], " ", label=f"± noise ({noise[1]})")
        pax.set(
            xlabel="distance from the wound centre (µm)",
            ylabel="tissue velocity (µm/s)",
            title="PIV velocity profile and fit",
        )
        pax.legend(loc="upper right", fontsize="small")
    for k, name in enumerate(profiles):
        profile_panel(fig.add_subplot(grid[2, k]), result, name, profile_points)
    from .status import status

    st = status(result)
    failed = "" if result.converged else "FAILED fit (the model where it stopped): "
    title = textwrap.shorten(failed + st.text, 240, placeholder=" ...")
    fig.suptitle(textwrap.fill(title, 125), color=st.colour, fontsize="medium")
    for a in fig.axes[2:]:  # the PIV and profile panels: each minor tick is a line and a
        a.minorticks_off()  # label to lay out, a third of the drawing, saying little there
    return fig


def time_label(result) -> str:
    """The time axis: since the cut, or on the data's clock when the fit has the cut."""
    if "cut_s" not in result.reports:
        return "time since the cut (s)"
    return f"time (s; the cut at {round(result.reports['cut_s'].estimate, 6):g} s)"


def margins(
    width: float, height: float, rows: int, columns: int, top: float = 0.45, below: float = 0.0
) -> dict:
    """Gridspec margins of a figure width x height inches: 0.75 in left and 0.55 in below
    (tick labels and an axis label; `below` in more under them, for the estimates' strip),
    `top` in on top (a suptitle; 0.75 above a panel's
    title, two lines of it clear of the title), 0.9 in between rows (an
    axis label and the next row's title) and 0.8 in between columns (tick labels and an axis
    label), as fractions. Fixed margins draw in one pass: a layout engine measures every text
    first (about half of this figure's drawing time)."""
    left, right, bottom, row_gap, column_gap = 0.75, 0.15, 0.55 + below, 0.9, 0.8
    tall = height - bottom - top
    wide = width - left - right
    return {
        "left": left / width,
        "right": 1 - right / width,
        "bottom": bottom / height,
        "top": 1 - top / height,
        "hspace": row_gap / ((tall - (rows - 1) * row_gap) / rows),
        "wspace": column_gap / ((wide - (columns - 1) * column_gap) / columns),
    }


def profile_span(result, name) -> tuple[float, float, str]:
    """(left, right, axis scale) of a profile panel: the walk's points and half the interval's
    width beyond each closed end (so the rise past the threshold shows), log where R0, T or
    lambda span more than a decade (symlog for lambda reaching 0)."""
    rep = result.reports[name]
    v = np.array([p[0] for p in rep.profile.points] + [rep.estimate])
    est, (lo, hi) = rep.estimate, rep.ci95
    logish = name in ("R0_um", "T_s")
    left, right = float(v.min()), float(v.max())
    if lo is not None and not rep.profile.at_bound and lo < est:
        left = min(left, lo * (lo / est) ** 0.5 if logish else lo - 0.5 * (est - lo))
    if hi is not None and hi > est:
        right = max(right, hi * (hi / est) ** 0.5 if logish else hi + 0.5 * (hi - est))
    if name == "lambda":
        left = max(left, 0.0)
        if right > 10 * max(left, 1e-300):
            return left, right, "symlog" if left <= 0 or left < 1e-3 * right else "log"
    if logish and right > 10 * left:
        return left, right, "log"
    return left, right, "linear"


def _linthresh(right: float) -> float:
    """The linear part of a symlog profile axis from 0: a power of ten 3-4 decades below `right`."""
    return 10.0 ** math.floor(math.log10(right / 1e3))


def _values(left, right, scale, n):
    if scale == "log":
        return np.geomspace(left, right, n)
    if scale == "symlog":
        thresh = _linthresh(right)
        return np.concatenate(
            [
                np.linspace(left, thresh, n // 4, endpoint=False),
                np.geomspace(thresh, right, n - n // 4),
            ]
        )
    return np.linspace(left, right, n)


def _gaps(values, known, scale: str, right: float):
    """The values farther than half their spacing (on the axis's scale) from every point the
    interval walk already has: the profile is drawn through both, and only the gaps the walk
    left cost constrained fits."""
    if values.size < 2 or known.size == 0:
        return values

    def axis(v):
        if scale == "log":
            return np.log(v)
        if scale == "symlog":
            return np.arcsinh(np.asarray(v) / (2 * _linthresh(right)))
        return np.asarray(v)

    u, w = axis(values), axis(known)
    half = 0.5 * (u.max() - u.min()) / (u.size - 1)
    return values[np.min(np.abs(u[:, None] - w[None, :]), axis=1) > half]


def profile_panel(ax, result, name, n=PROFILE_POINTS):
    rep = result.reports[name]
    if rep.constraint.get("fixed"):  # no profile: say so in the panel
        ax.text(
            0.5,
            0.5,
            f"{LABELS[name]} fixed at {rep.estimate:.6g}",
            ha="center",
            va="center",
            transform=ax.transAxes,
        )
        ax.set(xticks=[], yticks=[], title=f"{LABELS[name]}: fixed")
        ax.title.set_fontsize("small")
        return
    left, right, scale = profile_span(result, name)
    walk = np.array(rep.profile.points).reshape(-1, 2)
    known = walk[np.isfinite(walk[:, 1])]
    values = _values(left, right, scale, n) if n and result.refit is not None else np.empty(0)
    values = _gaps(values, known[:, 0], scale, right)
    delta = result.profile_at(name, values) if values.size else values
    pts = sorted(
        {(rep.estimate, 0.0)}
        | {(float(a), float(b)) for a, b in zip(values, delta) if np.isfinite(b)}
        | {(float(a), float(b)) for a, b in known}
    )
    x, y = np.array(pts).T
    ax.plot(x, y, "o-", ms=2.5, lw=1, label="profile")
    ax.plot(walk[:, 0], walk[:, 1], "x", c="C2", ms=4, label="interval search")
    y = np.concatenate([y, walk[:, 1]])
    threshold = rep.profile.threshold or result.threshold  # its own near lambda's bound
    ax.axhline(threshold, ls="--", c="gray", lw=0.8, label=f"95 % threshold {threshold:.3g}")
    ax.axvline(rep.estimate, c="k", ls=":", lw=0.8)
    for end in rep.ci95:
        if end is not None:
            ax.axvline(end, c="C3", lw=0.8)
    if scale == "symlog":
        ax.set_xscale("symlog", linthresh=_linthresh(right), linscale=0.7)
        ax.xaxis.set_major_formatter(ticker.FuncFormatter(lambda x, _: f"{x:g}"))
    elif scale == "log":
        ax.set_xscale("log")
        if right < 1e3 * left:
            plain_ticks(ax.xaxis)
    ax.set_xlim(min(left, float(x.min())), max(right, float(x.max())))
    ax.set_ylim(0, max(1.5 * threshold, min(float(y.max()) * 1.05, 4 * threshold)))
    lo, hi = rep.ci95
    verdict = "identified" if rep.identifiable else "not identified"
    ax.set(
        xlabel=LABELS[name],
        ylabel="Δχ² (profile)",
        title=f"{LABELS[name]}: {interval(lo, hi, rep.estimate)}, {verdict}",
    )
    ax.title.set_fontsize("small")
    if name == next(
        n for n in NAMES if not result.reports[n].constraint.get("fixed")
    ):  # the first drawn
        ax.legend(loc="upper center", fontsize="x-small")
