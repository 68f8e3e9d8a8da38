"""The report of a fit of several wounds (`fit_wounds`): one self-contained HTML file as the
single fit's (report.py), with

- each wound's input files with their SHA-256 and points, the recording's settings;
- the status (status.py: green, amber or red naming a forbidden value), chi^2 / dof, the
  optimiser, the warnings;
- the shared material values with their 95 % profile intervals (eta/G, zeta/G, tension/G,
  the viscous length; with G given eta, zeta and the tension), the coordinates of the fit
  beside them with their standard errors and constraints (fixed, bounds, prior), advice;
- a section per wound: its outer radius, points, noise, R0 with its interval, lambda, T,
  R1, R_final, chi^2 share and residual rms, its flagged points;
- the figure (tissue_plots.tissue_figure), the software and the command line.
"""

from __future__ import annotations

import datetime
import html
import io
import sys
from pathlib import Path

from .names import ETA, SHARED
from .report import (
    document,
    end_cell,
    figure_html,
    floor_said,
    html_table,
    inputs,
    material_html,
    number_cell,
    raw_files_section,
    settings_html,
    sig,
    status_html,
    warnings_html,
)
from .status import radii


def _constraint(c: dict) -> str:
    if c.get("fixed"):
        return "fixed (given)"
    out = []
    if "prior" in c:
        out.append("prior {:g} ± {:g}".format(*c["prior"]))
    if "bounds" in c:
        out.append("bounds [{:g}, {:g}]".format(*c["bounds"]))
    return "; ".join(out)


def _state(rep) -> str:
    if rep.constraint.get("fixed"):
        return ""
    if rep.profile is None:
        return "interval not computed"
    return "identified" if rep.identifiable else "not identified"


def _shared(result) -> str:
    rows = []
    for name in SHARED + (ETA,):
        rep = result.shared[name]
        lo, hi = rep.ci95
        rows.append(
            (
                name,
                number_cell(rep.estimate),
                number_cell(rep.stderr, 3),
                end_cell(lo, -1, rep.estimate, hi) if rep.profile is not None else "—",
                end_cell(hi, 1, rep.estimate, lo) if rep.profile is not None else "—",
                _state(rep),
                _constraint(rep.constraint),
                result.advice(name),
            )
        )
    return "<h3>Shared coordinates of the fit</h3>" + html_table(
        ["quantity", "estimate", "stderr", "95 % lower", "95 % upper", "", "constraint", "advice"],
        rows,
    )


def _wound(result, k: int, wound) -> str:
    w, rep = result.wounds[k], result.r0[k]
    R0, sigma, lam, T = w["theta"]
    lo, hi = rep.ci95
    r = radii(R0, sigma, w["outer_radius_um"])
    n_r, n_p = w["n_points"]
    noise = f"radius {sig(w['noise'][0], 4)} µm" + (
        f" ({floor_said(w['residual_rms_um'], w.get('radius_floor_said', ''))})"
        if w.get("radius_floor_um") is not None
        else ""
    )
    if n_p:
        noise += f", velocity {sig(w['noise'][1], 4)} µm/s"
    files = [(d, f, h, str(n)) for d, f, h, n in inputs(wound.radius, wound.profile)]
    rows = [
        (
            "R0_um",
            number_cell(R0),
            number_cell(rep.stderr, 3),
            end_cell(lo, -1, R0, hi) if rep.profile is not None else "—",
            end_cell(hi, 1, R0, lo) if rep.profile is not None else "—",
            "µm",
            _state(rep) or "fixed (given)",
            _constraint(rep.constraint) if not rep.constraint.get("fixed") else "",
        ),
        ("lambda = l / R0", number_cell(lam), "—", "—", "—", "1", "", ""),
        ("T_s = (zeta/G) R0² / 4", number_cell(T), "—", "—", "—", "s", "", ""),
        ("R1_um = R0 (1 + sigma / 6)", number_cell(r["R1_um"]), "—", "—", "—", "µm", "", ""),
        ("R_final_um", number_cell(r["R_final_um"]), "—", "—", "—", "µm", "", ""),
    ]
    flagged = w["outliers"].get("where", [])
    return (
        f"<h3>Wound {html.escape(str(w['name']))}</h3>"
        + html_table(["data", "file", "SHA-256", "points"], files)
        + f"<p>Outer radius {sig(w['outer_radius_um'])} µm; {n_r} radii, {n_p} velocities; noise "
        f"(median) {noise}; χ² share {sig(w['chi2'], 4)}; residual rms "
        f"{sig(w['residual_rms_um'], 4)} µm; PIV vectors at the edge "
        f"{w['piv_vectors_at_edge']}.</p>"
        + html_table(
            ["quantity", "estimate", "stderr", "95 % lower", "95 % upper", "unit", "", ""], rows
        )
        + (
            "<p>Flagged points: " + html.escape("; ".join(flagged)) + "</p>"
            if flagged
            else "<p>Flagged points: none.</p>"
        )
    )


def figure_png(result) -> bytes:
    from .tissue_plots import tissue_figure

    buf = io.BytesIO()
    tissue_figure(result, path=buf)
    return buf.getvalue()


def render(result, wounds, *, command: str | None = None, now=None) -> str:
    """The report as an HTML string (module docstring); `wounds`: the fitted Wound objects."""
    now = now or datetime.datetime.now(datetime.timezone.utc)
    command = command if command is not None else " ".join(sys.argv)
    n = len(result.wounds)
    p = "" if result.p_value is None else f", p = {sig(result.p_value, 3)}"
    dof = f"{result.chi2 / result.dof:.4g}" if result.dof else "—"
    parts = [
        f"<h1>Wound-opening fit of {n} wounds of one tissue</h1>"
        f"<p>{html.escape(now.strftime('%Y-%m-%d %H:%M:%S UTC'))}</p>",
        "<h2>Input</h2>",
        settings_html(result.settings),
        "<h2>Fit</h2>",
        f"<p>Status: {status_html(result)}. Optimiser: "
        f"{html.escape(result.optimizer.get('message', ''))}</p>",
        f"<p>χ² = {sig(result.chi2)} for {result.dof} degrees of freedom (χ²/dof = {dof}{p}); "
        f"noise {'given' if result.noise_given else 'estimated from the residuals'}; loss "
        f"{html.escape(result.loss)}.</p>",
    ]
    parts.append(warnings_html(result))
    if result.converged:
        parts += ["<h2>Shared material</h2>", material_html(result.material), _shared(result)]
    else:
        parts.append("<p>No estimates: the fit did not converge.</p>")
    parts.append("<h2>Wounds</h2>")
    parts += [_wound(result, k, w) for k, w in enumerate(wounds)]
    parts.append(raw_files_section(*(s for w in wounds for s in (w.radius, w.profile))))
    alt = "each wound's data and fit, residuals, profile likelihoods of the shared material"
    if not result.converged:
        alt = "each wound's data and the model where the fit stopped"
    parts.append(figure_html(figure_png(result), alt))
    return document("Wound-opening fit of several wounds", parts, command)


def write_report(path, result, wounds, *, command: str | None = None) -> Path:
    """Write render(...) to `path` (UTF-8); returns the path."""
    path = Path(path)
    path.write_text(render(result, wounds, command=command), encoding="utf-8")
    return path
