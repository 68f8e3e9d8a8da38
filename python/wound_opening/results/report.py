"""A fit's report: one self-contained HTML file (the figure embedded as a base64 PNG, the
style inline, no script and no external resource) that records what was fitted, how, and
what came out, so that it can be archived with the data and read in any browser:

- the input files with their SHA-256 and number of points (or "given in Python");
- the noise, given or estimated, per data set; the loss; chi^2 / dof and its p-value;
- the verdict (converged or not, the reasons, the optimiser's message) and the warnings;
- every estimate with its standard error and 95 % profile-likelihood interval, whether it is
  identified (or that its interval was not computed) and the advice; the derived values;
- the points flagged by a robust loss; the figure (plots.fit_figure), a failed fit's too;
- the software: wound_opening's version, the native library's path and SHA-256 (the C API
  has no version call: the hash identifies the build), Python, numpy and scipy; the command
  line and the date (UTC).
"""

from __future__ import annotations

import base64
import datetime
import hashlib
import html
import io
import platform
import sys
from pathlib import Path

import numpy
import scipy

from .._native import library_path
from .names import NAMES
from .numbers import end, own_digits
from .result import floor_name
from .settings import file_rows
from .settings import rows as setting_rows
from .status import status

STYLE = """body{font-family:sans-serif;max-width:70em;margin:1em auto;padding:0 1em;color:#222}
table{border-collapse:collapse;margin:.5em 0}
td,th{border:1px solid #bbb;padding:.2em .6em;text-align:left}
th{background:#eee}td.n{text-align:right;font-family:monospace}.bad{color:#a00;font-weight:bold}
.ok{color:#060;font-weight:bold}img{max-width:100%}code{background:#f4f4f4}"""


def sha256(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def sig(x, digits: int = 5) -> str:
    return "—" if x is None else f"{x:.{digits}g}"


def floor_said(rms_um: float, said: str = "") -> str:
    """How a report says the radius noise's floor set it (result.floor_name)."""
    return f"{floor_name(said)}, above the residuals' {sig(rms_um, 3)} µm"


def html_table(header, rows) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join(
        "<tr>"
        + "".join(c if c.startswith("<td") else f"<td>{html.escape(c)}</td>" for c in row)
        + "</tr>"
        for row in rows
    )
    return f"<table><tr>{head}</tr>{body}</table>"


def number_cell(x, digits: int = 5) -> str:
    return f'<td class="n">{html.escape(sig(x, digits))}</td>'


def end_cell(x, side: int, estimate, other=None) -> str:
    """An interval end to the digits that decide whether a value is inside, and to the
    interval's own precision with its `other` end (numbers.py)."""
    width = None if x is None or other is None else abs(float(other) - float(x))
    text = "—" if x is None else end(x, side, estimate, own_digits(x, width))
    return f'<td class="n">{html.escape(text)}</td>'


def status_html(result) -> str:
    """The status (status.py) in its colour: green converged, amber check, red impossible."""
    st = status(result)
    return f'<span style="color:{st.colour};font-weight:bold">{html.escape(st.text)}</span>'


def settings_html(settings: dict) -> str:
    """The recording's settings (settings.py) and the files with their columns."""
    if not settings:
        return "<p>Recording settings: not recorded (the fit was called from Python).</p>"
    out = "<h3>Recording settings</h3>" + html_table(["setting", "value"], setting_rows(settings))
    files = file_rows(settings)
    if files:
        out += html_table(["wound", "data", "file", "columns"], files)
    return out


def software() -> dict:
    """Versions of the package and its numerics, and the native library that is loaded."""
    from .. import __version__  # the installed distribution's (the package's __getattr__)

    lib = library_path()
    return {
        "wound_opening": __version__,
        "native library": f"{lib} (SHA-256 {sha256(lib)})",
        "Python": platform.python_version(),
        "numpy": numpy.__version__,
        "scipy": scipy.__version__,
    }


def inputs(radius, profile) -> list:
    """(what, file, SHA-256, points) of each data set."""
    out = []
    for what, data, n in (
        ("radius", radius, len(radius.times_s)),
        ("velocity profile", profile, 0 if profile is None else len(profile.times_s)),
    ):
        if data is None:
            continue
        source = getattr(data, "source", None)
        if getattr(data, "files", ()):  # raw lab files: hashed as read (raw_files_section)
            out.append((what, str(source or "lab files"), "see 'Raw files read'", n))
        elif source:
            out.append((what, str(source), sha256(source), n))
        else:
            out.append((what, "given in Python (no file)", "—", n))
    return out


def raw_files_section(*series) -> str:
    """The raw lab files behind the series (a Fiji table, every PIV file): each with the
    SHA-256 of the bytes read, its counts (rows or vectors read, dropped and why, used) and
    the notes (rows skipped, the wound centre, the rings); "" when none were read."""
    rows, notes = [], []
    for s in series:
        for f in getattr(s, "files", ()) if s is not None else ():
            notes += list(f.notes)
            if f.sha256:
                counts = ", ".join(f"{k} {v}" for k, v in f.counts.items())
                rows.append((str(f.path), f.kind, f.sha256, counts))
            elif f.counts:
                counts = ", ".join(f"{k} {v}" for k, v in f.counts.items())
                rows.append((f.kind, "", "", counts))
    if not rows:
        return ""
    items = "".join(f"<li>{html.escape(n)}</li>" for n in notes)
    return (
        "<h3>Raw files read</h3>"
        + html_table(["file", "what", "SHA-256 (of the bytes read)", "counts"], rows)
        + (f"<ul>{items}</ul>" if items else "")
    )


def figure_png(result, profile=None) -> bytes:
    from .plots import fit_figure

    buf = io.BytesIO()
    fit_figure(result, profile=profile, path=buf)
    return buf.getvalue()


def render(result, radius, profile=None, *, command: str | None = None, now=None) -> str:
    """The report as an HTML string (module docstring)."""
    now = now or datetime.datetime.now(datetime.timezone.utc)
    command = command if command is not None else " ".join(sys.argv)
    parts = [
        f"<h1>Wound-opening fit</h1><p>{html.escape(now.strftime('%Y-%m-%d %H:%M:%S UTC'))}</p>",
        "<h2>Input</h2>",
        html_table(
            ["data", "file", "SHA-256", "points"],
            [(w, f, h, str(n)) for w, f, h, n in inputs(radius, profile)],
        ),
        settings_html(result.settings),
    ]
    parts.append(raw_files_section(radius, profile))
    from .plots import noise_words

    floor = floor_said(result.residual_rms_um, result.radius_floor_said)
    said = {
        "estimated": "estimated from the residuals",
        "ring scatter": "the rings' scatter",
        "outline's floor": floor,
        "floor given": floor,
    }
    how = [said.get(w, w) for w in noise_words(result, profile)]
    noise = [f"radius {sig(result.noise[0], 4)} µm ({how[0]})"]
    if result.has_profile:
        noise.append(f"velocity {sig(result.noise[1], 4)} µm/s ({how[1]})")
    parts += [
        "<p>Noise (the median of the per-point standard deviations): "
        + ", ".join(noise)
        + f". Loss: {html.escape(result.loss)}. Outer radius {sig(result.outer_radius_um)} µm.</p>"
    ]
    verdict = status_html(result)
    p = "" if result.p_value is None else f", p = {sig(result.p_value, 3)}"
    dof = f"{result.chi2 / result.dof:.4g}" if result.dof else "—"
    parts += [
        "<h2>Fit</h2>",
        f"<p>Status: {verdict}. Optimiser: {html.escape(result.optimizer.get('message', ''))}</p>",
        f"<p>χ² = {sig(result.chi2)} for {result.dof} degrees of freedom (χ²/dof = {dof}{p}); "
        f"residual rms {sig(result.residual_rms_um, 4)} µm; {result.n_points[0]} radii, "
        f"{result.n_points[1]} velocities.</p>",
    ]
    parts.append(warnings_html(result))
    parts.append("<h2>Estimates</h2>" + _estimates(result))
    parts.append(_flagged(result))
    parts.append(
        figure_html(figure_png(result, profile), "data, fit, residuals and profile likelihoods")
        if result.converged
        else figure_html(figure_png(result, profile), "data and the model where the fit stopped")
    )
    return document("Wound-opening fit", parts, command)


def figure_html(png: bytes, alt: str) -> str:
    """The report's figure section: the PNG inline (base64), `alt` its text."""
    data = base64.b64encode(png).decode("ascii")
    return f'<h2>Figure</h2><img alt="{html.escape(alt)}" src="data:image/png;base64,{data}">'


def document(title: str, parts: list, command: str) -> str:
    """The HTML page of a report: `parts` (HTML), then the software's versions and the
    command that made it."""
    parts = [
        *parts,
        "<h2>Software and command</h2>",
        html_table(["component", "version"], list(software().items())),
        f"<p>Command: <code>{html.escape(command)}</code></p>",
    ]
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>{html.escape(title)}</title>"
        f"<style>{STYLE}</style></head><body>\n" + "\n".join(parts) + "\n</body></html>\n"
    )


def _estimates(result) -> str:
    if not result.converged:
        theta = dict(zip(NAMES, result.theta))
        return (
            "<p>No estimates: the fit did not converge. Where it stopped: "
            + html.escape(", ".join(f"{k} = {sig(v)}" for k, v in theta.items()))
            + "</p>"
        )
    rows = []
    for name in NAMES:
        rep = result.reports[name]
        lo, hi = rep.ci95
        c = rep.constraint
        if c.get("fixed"):
            rows.append((name, number_cell(rep.estimate), "—", "—", "—", "fixed (given)", ""))
            continue
        computed = rep.profile is not None
        state = (
            ("identified" if rep.identifiable else "not identified")
            if computed
            else "interval not computed"
        )
        state += ("; prior {:g} ± {:g}".format(*c["prior"]) if "prior" in c else "") + (
            "; bounds [{:g}, {:g}]".format(*c["bounds"]) if "bounds" in c else ""
        )
        rows.append(
            (
                name,
                number_cell(rep.estimate),
                number_cell(rep.stderr, 3),
                end_cell(lo, -1, rep.estimate, hi) if computed else "—",
                end_cell(hi, 1, rep.estimate, lo) if computed else "—",
                state,
                result.advice(name),
            )
        )
    model = "<h3>Model parameters</h3>" + html_table(
        ["parameter", "estimate", "stderr", "95 % lower", "95 % upper", "", "advice"], rows
    )
    out = material_html(result.material) + model
    computed = result.derived_computed()
    rows = []
    for k, (v, (lo, hi), ok) in result.derived_values().items():
        if k not in ("R1_um", "R_final_um"):  # the others are material values
            continue
        state = (
            "interval not computed" if not computed[k] else "identified" if ok else "not identified"
        )
        rows.append((k, number_cell(v), number_cell(lo), number_cell(hi), state))
    return (
        out
        + "<h3>Derived values</h3>"
        + html_table(["quantity", "value", "95 % lower", "95 % upper", ""], rows)
    )


def material_html(material: dict) -> str:
    """The material values (FitResult.material, TissueFitResult.material) with their
    intervals, each end to the digits that decide whether a value is inside."""
    rows = []
    for k, m in material.items():
        if k == "G_pa":
            rows.append(
                (
                    k,
                    number_cell(m["estimate"]),
                    "—",
                    "—",
                    "Pa",
                    "fixed (given)" if m["fixed"] else f"Gaussian prior, sd {sig(m['sd'], 3)} Pa",
                )
            )
            continue
        computed = m.get("interval_computed", True)
        state = (
            ("identified" if m["identifiable"] else "not identified")
            if computed
            else "interval not computed"
        )
        lo, hi = m["ci95"]
        rows.append(
            (
                k,
                number_cell(m["estimate"]),
                end_cell(lo, -1, m["estimate"], hi) if computed else "—",
                end_cell(hi, 1, m["estimate"], lo) if computed else "—",
                m["unit"],
                state,
            )
        )
    return "<h3>Material values</h3>" + html_table(
        ["quantity", "value", "95 % lower", "95 % upper", "unit", ""], rows
    )


def _flagged(result) -> str:
    tabs = result.points
    rows = []
    for what, key, value, unit in (
        ("radius", "radius", "radius_um", "µm"),
        ("velocity", "profile", "velocity_um_s", "µm/s"),
    ):
        cols = tabs.get(key)
        if not cols:
            continue
        res = "residual_um" if key == "radius" else "residual_um_s"
        for k in [i for i, f in enumerate(cols["flagged"]) if f]:
            line = str(cols["file_line"][k]) if "file_line" in cols else "—"
            rows.append(
                (
                    what,
                    str(cols["row"][k]),
                    line,
                    number_cell(cols["time_s"][k]),
                    f"{sig(cols[value][k])} {unit}",
                    f"{sig(cols[res][k], 3)} {unit}",
                    number_cell(cols["normalised_residual"][k], 3),
                )
            )
    if not rows:
        why = "no robust loss" if result.loss == "linear" else "none beyond 3 noise"
        return f"<p>Flagged points: none ({why}).</p>"
    return "<h3>Flagged points (down-weighted by the robust loss)</h3>" + html_table(
        ["data", "row", "file line", "time (s)", "value", "data − fit", "/ noise"], rows
    )


def write_report(path, result, radius, profile=None, *, command: str | None = None) -> Path:
    """Write render(...) to `path` (UTF-8); returns the path."""
    path = Path(path)
    path.write_text(render(result, radius, profile, command=command), encoding="utf-8")
    return path


def warnings_html(result) -> str:
    """A fit's warnings (one wound's or several's) as a list, or nothing."""
    if not result.warnings:
        return ""
    return (
        "<ul>" + "".join(f"<li>warning: {html.escape(w)}</li>" for w in result.warnings) + "</ul>"
    )
