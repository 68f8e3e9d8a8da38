"""What the usual recoil fit reads from a wound opening, against this model's fit.

Labs fit the single-exponential Kelvin-Voigt recoil R(t) = R1 + D (1 - exp(-t / tau)) with
scipy.optimize.curve_fit and read tau as the viscoelastic time eta/G ("viscosity"), the
initial recoil velocity v0 = D / tau as the tension (over the friction) and R1 + D as the
final radius. Here both that fit and `wound_opening.fit` are given the same recording from
the EXACT solution (python/wound_exact.py) plus Gaussian noise of 0.02 um (declared to
`fit`), for lambda = 0.05 .. 10 in two designs and two recording windows:

    eta/G fixed   tau = eta/G = 10 s, T = tau / lambda^2 (lambda set by the friction zeta)
    T fixed       T = zeta R0^2 / (4 G) = 10 s, eta/G = lambda^2 T (lambda set by eta)
    short         frames every 0.5 s, 0.5 .. 30 s (60 frames)
    long          frames every 2.5 s, 2.5 .. 300 s (120 frames)

R0 = 10 um, tension/G = sigma = 0.5, outer radius 100 um. Compared with the truth: tau
against eta/G and T; v0 against the exact edge velocity just after the cut, v(0+) =
lim s->inf s^2 V(1, s) (R0 / T); D against the exact opening after the cut, R_final - R1;
this model's eta/G and tension/G (estimate and 95 % profile interval). And two tissues
that differ only in friction (same G, eta, tension: the eta/G-fixed design at lambda 0.3
and 1): the ratios the recoil fit reads as "tension" (v0) and "viscosity" (tau) against
the ratios of tension/G and eta/G this model recovers (both truly 1).

    python python/bench/recoil_compare.py --out out/recoil   # table (Markdown, JSON), figure
    python python/bench/recoil_compare.py --no-model         # the recoil fits alone (seconds)
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import curve_fit

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import wound_exact as we  # noqa: E402

R0, SIGMA, OUTER, NOISE = 10.0, 0.5, 100.0, 0.02
LAMBDAS = (0.05, 0.1, 0.3, 1.0, 3.0, 10.0)
TAU, T_FIXED = 10.0, 10.0
DESIGNS = ("eta/G fixed", "T fixed")
#: window -> (frame interval [s], number of frames): frames at dt, 2 dt, ..., n dt.
WINDOWS = {"short": (0.5, 60), "long": (2.5, 120)}
#: The two tissues of the two-condition comparison: same G, eta, tension; friction differs.
CONDITIONS = (0.3, 1.0)


def time_scale(design: str, lam: float) -> float:
    """T [s] of the design at lambda."""
    if design == "eta/G fixed":
        return TAU / lam**2
    if design == "T fixed":
        return T_FIXED
    raise ValueError(f"design {design!r}: one of {', '.join(DESIGNS)}")


def recording(lam: float, T: float, window: str, seed: int = 0):
    """Frame times [s] and radii [um]: the exact solution plus N(0, NOISE^2)."""
    dt, n = WINDOWS[window]
    t = dt * np.arange(1, n + 1)
    exact = R0 * we.edge(lam, SIGMA, OUTER / R0, t / T)[0]
    return t, exact + NOISE * np.random.default_rng(seed).standard_normal(n)


def initial_velocity(lam: float, T: float) -> float:
    """v(0+) [um/s]: the exact edge velocity just after the cut (lambda > 0), by the initial
    value theorem on the velocity's transform s V(1, s), at s = 1e12 (converged to 1e-9)."""
    s = np.array([1e12 + 0j])
    return float((s * s * we.edge_transform(s, lam, SIGMA, OUTER / R0)).real[0]) * R0 / T


def opening_after_cut() -> float:
    """R_final - R1 [um]: the opening after the elastic jump at the cut."""
    return R0 * (we.final_radius(SIGMA, OUTER / R0) - we.initial_radius(SIGMA))


def exponential(t, R1, D, tau):
    return R1 + D * -np.expm1(-t / tau)


def recoil_fit(t, radius) -> dict:
    """R1, D, tau [s] and v0 = D / tau [um/s] of the single-exponential recoil, by least
    squares (curve_fit, D and tau >= 0, started at the first frame, the last frame's rise
    and a third of the window)."""
    p0 = (radius[0], max(radius[-1] - radius[0], 1e-6), t[-1] / 3)
    (R1, D, tau), _ = curve_fit(
        exponential,
        t,
        radius,
        p0=p0,
        bounds=([-np.inf, 0.0, 1e-9], [np.inf, np.inf, np.inf]),
        maxfev=20000,
    )
    return {"R1": float(R1), "D": float(D), "tau": float(tau), "v0": float(D / tau)}


def model_fit(t, radius) -> dict:
    """This model's eta/G [s] and tension/G, each (estimate, [lower, upper], identified)."""
    from wound_opening import RadiusSeries, fit

    result = fit(RadiusSeries(t, radius, noise_um=NOISE), outer_radius_um=OUTER)
    m = result.material
    return {
        k: (m[k]["estimate"], m[k]["ci95"], m[k]["identifiable"])
        for k in ("eta_over_G_s", "tension_over_G")
    }


def case(design: str, lam: float, window: str, model: bool = True, seed: int = 0) -> dict:
    """One recording fitted both ways, with the truth it is compared to."""
    T = time_scale(design, lam)
    t, radius = recording(lam, T, window, seed)
    row = {
        "design": design,
        "window": window,
        "lambda": lam,
        "T_s": T,
        "eta_over_G_s": lam**2 * T,
        "v0_true": initial_velocity(lam, T),
        "opening_true": opening_after_cut(),
        **recoil_fit(t, radius),
    }
    row["tau_over_eta_G"] = row["tau"] / row["eta_over_G_s"]
    row["tau_over_T"] = row["tau"] / T
    row["v0_over_true"] = row["v0"] / row["v0_true"]
    row["D_over_opening"] = row["D"] / row["opening_true"]
    if model:
        row["model"] = model_fit(t, radius)
    return row


def two_conditions(rows: list) -> dict:
    """window -> the recoil fit's "tension" (v0) and "viscosity" (tau) ratios, lambda 1 over
    0.3 in the eta/G-fixed design, and (with the model's fits) this model's ratios of
    tension/G and eta/G."""
    out = {}
    for window in WINDOWS:
        pair = [
            next((r for r in rows if (r["design"], r["window"], r["lambda"]) == key), None)
            for key in ((DESIGNS[0], window, x) for x in CONDITIONS)
        ]
        if None in pair:
            continue
        a, b = pair
        ratios = {"v0": b["v0"] / a["v0"], "tau": b["tau"] / a["tau"]}
        ratios["v0_true"] = b["v0_true"] / a["v0_true"]
        if "model" in a and "model" in b:
            for k in ("tension_over_G", "eta_over_G_s"):
                ratios[k] = b["model"][k][0] / a["model"][k][0]
        out[window] = ratios
    return out


def _interval(value) -> str:
    v, (lo, hi), ok = value

    def f(x):
        return "open" if x is None else f"{x:.3g}"

    return f"{v:.3g} [{f(lo)}, {f(hi)}]" + ("" if ok else " n.i.")


def markdown(rows: list) -> str:
    model = all("model" in r for r in rows)
    head = (
        "| design | window | lambda | eta/G [s] | T [s] | tau [s] | tau/(eta/G) | tau/T "
        "| v0/v(0+) | D/(R_final-R1) |"
    )
    sep = "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
    if model:
        head += " this model: eta/G [s] | tension/G (truth 0.5) |"
        sep += "---|---|"
    lines = [head, sep]
    for r in rows:
        line = (
            f"| {r['design']} | {r['window']} | {r['lambda']:g} | {r['eta_over_G_s']:.4g} | "
            f"{r['T_s']:.4g} | {r['tau']:.3g} | {r['tau_over_eta_G']:.3g} | "
            f"{r['tau_over_T']:.3g} | {100 * r['v0_over_true']:.0f} % | "
            f"{100 * r['D_over_opening']:.0f} % |"
        )
        if model:
            m = r["model"]
            line += f" {_interval(m['eta_over_G_s'])} | {_interval(m['tension_over_G'])} |"
        lines.append(line)
    return "\n".join(lines)


def plot(rows: list, path: Path) -> None:
    """The recoil fit's readings against the truth (this model's are in the table)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11, 7.5))
    axes = fig.subplots(2, 2)
    colours = {"short": "#0072B2", "long": "#D55E00"}
    marks = {DESIGNS[0]: "o", DESIGNS[1]: "s"}
    for design in DESIGNS:
        for window in WINDOWS:
            sel = [r for r in rows if (r["design"], r["window"]) == (design, window)]
            lam = [r["lambda"] for r in sel]
            kw = dict(
                color=colours[window],
                marker=marks[design],
                ls="-" if design == DESIGNS[0] else "--",
                label=f"{design}, {window} window",
            )
            axes[0, 0].loglog(lam, [r["tau_over_eta_G"] for r in sel], **kw)
            axes[0, 1].loglog(lam, [r["tau_over_T"] for r in sel], **kw)
            axes[1, 0].semilogx(lam, [100 * r["v0_over_true"] for r in sel], **kw)
            axes[1, 1].semilogx(lam, [100 * r["D_over_opening"] for r in sel], **kw)
    for ax, label in zip(
        axes.flat,
        (
            "fitted tau / true eta/G",
            "fitted tau / true T = zeta R0^2 / 4G",
            "v0 = D / tau, % of the true v(0+)",
            "D, % of the true R_final - R1",
        ),
    ):
        ax.set_xlabel("lambda = viscous length / R0")
        ax.set_ylabel(label)
        ax.axhline(100 if "%" in label else 1, color="k", lw=0.7)
        ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=6.5, loc="upper right")
    fig.suptitle(
        "Single-exponential recoil fit R1 + D (1 - exp(-t/tau)) on exact wound openings "
        "(R0 = 10 um, sigma = 0.5, R_inf = 10)",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="out/recoil", help="folder (default: %(default)s)")
    ap.add_argument("--no-model", action="store_true", help="the recoil fits only")
    ap.add_argument("--figure", default=None, help="also write the figure here")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = [
        case(design, lam, window, model=not args.no_model)
        for design in DESIGNS
        for window in WINDOWS
        for lam in LAMBDAS
    ]
    table = markdown(rows)
    lines = [table, ""]
    for window, r in two_conditions(rows).items():
        text = (
            f"two tissues, friction only (lambda {CONDITIONS[0]} -> {CONDITIONS[1]}), {window} "
            f"window: recoil 'tension' (v0) x{r['v0']:.3g}, 'viscosity' (tau) x{r['tau']:.3g} "
            f"(true v(0+) x{r['v0_true']:.3g})"
        )
        if "tension_over_G" in r:
            text += (
                f"; this model: tension/G x{r['tension_over_G']:.3g}, eta/G x"
                f"{r['eta_over_G_s']:.3g} (truth x1, x1)"
            )
        lines.append(text)
    text = "\n".join(lines)
    print(text)
    (out / "recoil_compare.md").write_text(text + "\n")
    (out / "recoil_compare.json").write_text(json.dumps(rows, indent=1, default=float) + "\n")
    plot(rows, out / "recoil_compare.png")
    if args.figure:
        plot(rows, Path(args.figure))


if __name__ == "__main__":
    main()
