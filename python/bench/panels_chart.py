"""The paper's four panels per lambda (docs/model.md, "The paper's figures") from the Rust
`profiles.csv`.

Columns lambda,t,r,u,v: u(r, t) and v = u_t(r, t) on an r grid of [1, R_inf] at the
times the file holds, t = 0 being the state just after the cut (u = sigma r / 6, v the
initial velocity field) and t = inf the relaxed state u_inf = a r + b / r.

a) u against r at several t, t = 0 (red) and t = inf (black) dashed
b) v against r at the same t (log axis: the velocity decays over the viscous length)
c) (u - u_i) / (u_f - u_i) against t at several r (u_i = u(r, 0), u_f = u(r, inf))
d) v / v_max against t at several r (v_max: the largest v at that r over the file's t)
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np

#: Positions of panels c) and d) (the nearest grid radius is used).
RADII = (1.0, 1.5, 2.5, 5.0, 7.5, 10.0)
#: How many finite positive times panels a) and b) show (spread evenly in log t).
CURVES = 7
#: Panel b) has a log v axis spanning this many decades below the largest velocity.
FLOOR_DECADES = 6


class Profiles:
    """u and v of one lambda as (time, radius) arrays."""

    def __init__(self, rows: list[dict]):
        self.t = np.array(sorted({float(r["t"]) for r in rows}))
        self.r = np.array(sorted({float(r["r"]) for r in rows}))
        self.u = np.full((self.t.size, self.r.size), np.nan)
        self.v = np.full_like(self.u, np.nan)
        for row in rows:
            i = np.searchsorted(self.t, float(row["t"]))
            j = np.searchsorted(self.r, float(row["r"]))
            self.u[i, j], self.v[i, j] = float(row["u"]), float(row["v"])
        self.live = np.isfinite(self.t) & (self.t > 0)

    def at(self, t: float) -> int:
        return int(np.searchsorted(self.t, t))

    def shown_times(self) -> list[int]:
        times = self.t[self.live]
        picks = np.geomspace(times[0], times[-1], CURVES)
        return sorted({self.at(times[np.abs(np.log(times) - math.log(p)).argmin()]) for p in picks})


def plot_lambda(lam: str, rows: list[dict], path) -> None:
    p = Profiles(rows)
    fig, ((a, b), (c, d)) = plt.subplots(2, 2, figsize=(12, 9))
    colours = plt.cm.viridis(np.linspace(0, 0.9, CURVES))
    zero, final = p.at(0.0), p.at(math.inf)
    has_zero, has_final = p.t[zero] == 0.0, final < p.t.size and math.isinf(p.t[final])
    if has_zero:
        a.plot(p.r, p.u[zero], "r--", label="t = 0 (before the cut)", zorder=3)
        b.plot(p.r, p.v[zero], "r--", label="t = 0+ (just after the cut)", zorder=3)
    top = np.nanmax(p.v[np.isfinite(p.t)])
    floor = top * 10.0**-FLOOR_DECADES
    for i, colour in zip(p.shown_times(), colours):
        a.plot(p.r, p.u[i], color=colour, label=f"t = {p.t[i]:.3g}")
        # A curve entirely below the log axis' floor is not drawn, so it gets no legend entry.
        if np.nanmax(p.v[i]) > floor:
            b.plot(p.r, p.v[i], color=colour, label=f"t = {p.t[i]:.3g}")
    if has_final:
        a.plot(p.r, p.u[final], "k--", label="t = inf (relaxed)", zorder=3)
    a.set(xlabel="r (R0)", ylabel="u (R0)", title="a) displacement u(r, t)")
    b.set(
        xlabel="r (R0)",
        ylabel="v = du/dt (R0/T)",
        yscale="log",
        title=f"b) velocity v(r, t), log scale (down to 1e-{FLOOR_DECADES} of its largest value)",
    )
    b.set_ylim(floor, top * 2)

    times = p.t[p.live]
    rcol = plt.cm.plasma(np.linspace(0, 0.85, len(RADII)))
    for radius, colour in zip(RADII, rcol):
        j = int(np.abs(p.r - radius).argmin())
        u, v = p.u[p.live, j], p.v[p.live, j]
        if has_zero and has_final:
            c.plot(
                times,
                (u - p.u[zero, j]) / (p.u[final, j] - p.u[zero, j]),
                color=colour,
                label=f"r = {p.r[j]:g}",
            )
        vmax = np.nanmax(np.r_[v, p.v[zero, j] if has_zero else -np.inf])
        d.plot(times, v / vmax, color=colour, label=f"r = {p.r[j]:g}")
    c.set(
        xscale="log",
        xlabel="t (T)",
        ylabel="(u - u_i) / (u_f - u_i)",
        title="c) normalised displacement",
    )
    d.set(
        xscale="log",
        xlabel="t (T)",
        ylabel="v / v_max",
        title="d) normalised velocity (v_max at each r)",
    )
    for ax in (a, b, c, d):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(
        f"Tissue deformation after the cut, lambda = {lam} (R_inf = 10, sigma = 1); "
        "time in T = zeta R0^2 / (4 G)"
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
