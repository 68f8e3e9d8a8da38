"""Outputs to reuse and the report: the export tables against the exact solution, the HTML
report's content and its rendering in headless Chromium (as the FMU pages are), the figures'
contents, the half-opening time against the exact solution, profile points on the
threshold, and the command line's tables, units and help."""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import wound_exact as we
from test_cli import LAM, OUTER, R0, SIGMA, T, run
from test_fmu_pages import render

import wound_opening as wo
from wound_opening.model import half_opening_time
from wound_opening.results.numbers import ends
from wound_opening.results.report import render as report_html

NOISE = 0.05
OUTLIER_ROW = 12  # 1-based data row made an outlier (+1 um = 20 noise)

ROOT = Path(__file__).resolve().parents[2]


def write_experiment(path):
    """30 radii from the exact solution with 0.05 um noise and one outlier, after a comment
    line (so that file lines and rows differ by 2)."""
    t = np.linspace(0.5, 60, 30)
    r = R0 * we.edge(LAM, SIGMA, OUTER / R0, t / T)[0] + NOISE * np.random.default_rng(
        7
    ).standard_normal(t.size)
    r[OUTLIER_ROW - 1] += 1.0
    path.write_text(
        "# recorded 2026-11-30\n" + pd.DataFrame({"time_s": t, "radius_um": r}).to_csv(index=False)
    )


@pytest.fixture(scope="module")
def robust(tmp_path_factory):
    """(result, radius, path) of a soft_l1 fit with the noise given."""
    path = tmp_path_factory.mktemp("report") / "radius.csv"
    write_experiment(path)
    radius = wo.read_radius(str(path), noise_um=NOISE)
    return wo.fit(radius, outer_radius_um=OUTER, loss="soft_l1", derived=False), radius, path


def drawn(fig):
    """The renderer of `fig` drawn again (a figure the package returns is closed)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def exact_radius_um(theta, t):
    R0_, sigma, lam, T_ = theta
    t = np.asarray(t, float)
    r = np.full(t.size, R0_ * we.initial_radius(sigma))
    later = t > 0
    r[later] = R0_ * we.edge(lam, sigma, OUTER / R0_, t[later] / T_)[0]
    return r


def test_the_export_tables_hold_the_data_the_exact_model_and_the_flag(robust, tmp_path):
    result, radius, _ = robust
    tabs = result.tables()
    pts = tabs["radius"]
    assert list(pts.columns) == [
        "row",
        "file_line",
        "time_s",
        "radius_um",
        "sd_um",
        "model_radius_um",
        "residual_um",
        "normalised_residual",
        "flagged",
    ]
    np.testing.assert_array_equal(pts.row, np.arange(1, 31))
    np.testing.assert_array_equal(pts.file_line, np.arange(3, 33))  # comment line, header
    np.testing.assert_array_equal(pts.radius_um, radius.radius_um)
    assert np.all(pts.sd_um == NOISE)
    # the model column is the model at the estimate, to the solver's accuracy: 1e-10 of the opening
    R0_, sigma = result.theta[:2]
    opening = R0_ * (we.final_radius(sigma, OUTER / R0_) - we.initial_radius(sigma))
    np.testing.assert_allclose(
        pts.model_radius_um, exact_radius_um(result.theta, pts.time_s), rtol=0, atol=1e-10 * opening
    )
    np.testing.assert_array_equal(pts.residual_um, pts.radius_um - pts.model_radius_um)
    np.testing.assert_array_equal(pts.normalised_residual, pts.residual_um / pts.sd_um)
    assert list(np.flatnonzero(pts.flagged) + 1) == [OUTLIER_ROW] == result.outliers["radius"]
    curve = tabs["curve"]
    assert list(curve.columns) == ["time_s", "radius_um", "edge_velocity_um_s"]
    assert (
        curve.time_s.iloc[0] == 0
        and curve.time_s.iloc[-1] == pytest.approx(60)
        and len(curve) > 300
    )
    assert (
        np.all(np.diff(curve.time_s) > 0) and curve.time_s[curve.time_s > 0].min() <= 0.05 + 1e-12
    )
    pick = curve.iloc[::37]
    np.testing.assert_allclose(
        pick.radius_um, exact_radius_um(result.theta, pick.time_s), rtol=0, atol=1e-10 * opening
    )
    paths = result.export(tmp_path / "out.csv")
    assert [p.name for p in paths] == ["out_radius.csv", "out_curve.csv"]
    for p, name in zip(paths, ("radius", "curve")):  # every double read back exactly
        pd.testing.assert_frame_equal(pd.read_csv(p), tabs[name], check_exact=True)


def test_a_profile_exports_its_points_and_curves():
    t = np.linspace(0.5, 60, 20)
    x, times = np.linspace(1.05, 6, 8), np.array([1.0, 3.0])
    u, v = we.profile(LAM, SIGMA, OUTER / R0, x, times / T)
    radius = wo.RadiusSeries(t, R0 * we.edge(LAM, SIGMA, OUTER / R0, t / T)[0], noise_um=1e-3)
    rows = np.repeat(times, x.size)
    profile = wo.VelocityProfile(
        rows[::-1], (R0 * (x + u)).ravel()[::-1], (R0 / T * v).ravel()[::-1], noise_um_s=1e-4
    )
    result = wo.fit(radius, profile, outer_radius_um=OUTER, intervals=False)
    tabs = result.tables()
    p = tabs["profile"]
    assert list(p.columns) == [
        "row",
        "time_s",
        "r_um",
        "velocity_um_s",
        "sd_um_s",
        "model_velocity_um_s",
        "residual_um_s",
        "normalised_residual",
        "flagged",
    ]
    np.testing.assert_array_equal(p.velocity_um_s, profile.velocity_um_s)  # the input's order
    np.testing.assert_allclose(p.model_velocity_um_s, profile.velocity_um_s, rtol=0, atol=3e-4)
    c = tabs["profile_curve"]
    assert list(c.columns) == ["time_s", "r_um", "velocity_um_s"] and set(c.time_s) == {1.0, 3.0}


def test_the_report_records_inputs_noise_estimates_flags_and_versions(robust):
    result, radius, path = robust
    text = report_html(result, radius, command="wound-opening fit radius.csv")
    assert hashlib.sha256(path.read_bytes()).hexdigest() in text and str(path) in text
    assert "<td>30</td>" in text and "radius 0.05 µm (given)" in text and "soft_l1" in text
    assert f"χ² = {result.chi2:.5g} for {result.dof} degrees of freedom" in text
    for name in ("R0_um", "sigma", "lambda", "T_s"):
        rep = result.reports[name]
        assert f'<td class="n">{rep.estimate:.5g}</td>' in text
        for e, printed in zip(rep.ci95, ends(*rep.ci95, rep.estimate)):
            if e is not None:  # to the digits that decide whether a value is inside
                assert f'<td class="n">{printed}</td>' in text
    assert text.count("interval not computed") == 3  # tau, zeta/G, viscous length (derived=False)
    assert re.search(rf"<td>radius</td><td>{OUTLIER_ROW}</td><td>{OUTLIER_ROW + 2}</td>", text)
    assert wo.__version__ in text and "SHA-256" in text and "wound-opening fit radius.csv" in text
    assert 'src="data:image/png;base64,' in text
    # self-contained: no reference to anything outside the file
    assert (
        not re.search(r'(src|href)="(?!data:)', text)
        and "<script" not in text
        and "url(" not in text
    )


def test_a_failed_fit_is_reported_as_such(robust):
    _, radius, _ = robust
    bad = wo.RadiusSeries(radius.times_s, radius.radius_um, noise_um=1e-4)  # 500 x too small
    result = wo.fit(bad, outer_radius_um=OUTER)
    assert not result.converged
    text = report_html(result, bad)
    assert (
        "NOT converged" in text and "does not describe the data" in text and "No estimates" in text
    )
    assert "given in Python (no file)" in text
    assert "data:image/png" in text and "data and the model where the fit stopped" in text
    with pytest.raises(ValueError, match="did not converge"):
        result.tables()
    curve = result.tables(stopped=True)["curve"]  # the figure's: the model where it stopped
    R0, sigma, lam, T = result.theta
    assert curve.radius_um.iloc[-1] == pytest.approx(
        float(
            wo.simulate(
                [curve.time_s.iloc[-1]],
                lam=lam,
                sigma=sigma,
                R0_um=R0,
                T_s=T,
                outer_radius_um=OUTER,
            ).radius_um[0]
        ),
        rel=1e-9,
    )


def test_a_failed_fit_writes_its_figure_and_report_from_the_command_line(robust, tmp_path, capsys):
    """The radius file with a noise 500 times too small given: exit 1, and the figure and the
    report are written, the report saying why (chi^2) and holding the figure; no export."""
    from wound_opening.cli import main

    _, _, path = robust
    png, page = tmp_path / "fit.png", tmp_path / "fit.html"
    argv = ["fit", str(path), "--outer-radius-um", str(OUTER), "--radius-noise-um", "1e-4"]
    argv += ["--plot", str(png), "--report", str(page), "--export", str(tmp_path / "x")]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert "the figure shows the model where it stopped; no export" in err, err
    assert png.read_bytes().startswith(b"\x89PNG") and not list(tmp_path.glob("x_*.csv"))
    text = page.read_text()
    assert "NOT converged" in text and "does not describe the data" in text
    assert "data:image/png" in text and "where the fit stopped" in text


def test_a_failed_fit_of_several_wounds_draws_where_it_stopped():
    """A several-wound result marked failed (the drawing and the report read only its
    verdict, reasons and each wound's point): its figure and report are written, the report
    saying why; its tables stand only as `stopped`. Exact radii of two wounds of one tissue."""
    from wound_opening.fitting.wounds import Wound, fit_wounds
    from wound_opening.results.tissue_plots import tissue_figure
    from wound_opening.results.tissue_report import render as tissue_html

    t = np.linspace(0.5, 60, 30)
    wounds = []
    for r0 in (6.0, 12.0):
        r = r0 * we.edge(20 / r0, SIGMA, OUTER / r0, t / (0.025 * r0 * r0))[0]
        wounds.append(Wound(wo.RadiusSeries(t, r, noise_um=1e-3), OUTER, name=f"R0 {r0:g}"))
    result = fit_wounds(wounds, intervals=False)
    result.converged, result.reasons = False, ["a reason the verdict gives"]
    with pytest.raises(ValueError, match="did not converge"):
        result.tables()
    assert set(result.tables(stopped=True)) == {"R0 6", "R0 12"}
    fig = tissue_figure(result)
    (strip,) = [t for t in fig.texts if "profile-likelihood intervals" in t.get_text()]
    renderer = drawn(fig)  # the shared values under every panel, on no data
    assert all(
        strip.get_window_extent(renderer).y1 < ax.get_tightbbox(renderer).y0 for ax in fig.axes
    )
    text = tissue_html(result, wounds, command="test")
    assert "a reason the verdict gives" in text and "where the fit stopped" in text
    assert "data:image/png" in text


def test_the_report_renders_in_headless_chromium(robust, tmp_path):
    result, radius, _ = robust
    page = wo.write_report(
        tmp_path / "report.html", result, radius, command="wound-opening fit radius.csv"
    )
    check = """<script>window.addEventListener("load", () => {
      const imgs = [...document.images].map(i => [i.complete, i.naturalWidth, i.naturalHeight]);
      console.log("report-check: images=" + JSON.stringify(imgs));
    });</script>"""
    console, dom = render(page, tmp_path / "profile", check)
    checks = [line for line in console if "report-check:" in line]
    assert [line for line in console if "report-check:" not in line] == [], console
    assert len(checks) == 1, console
    images = json.loads(re.search(r"images=(\[.*\])", checks[0]).group(1))
    assert len(images) == 1 and images[0][0] and images[0][1] > 1000 and images[0][2] > 500, images
    for name in ("R0_um", "lambda", "T_s"):
        assert f"{result.reports[name].estimate:.5g}" in dom


def test_the_fit_figure_has_a_log_time_axis_error_bars_flags_estimates_and_fine_profiles(robust):
    from matplotlib.container import ErrorbarContainer

    from wound_opening.results.plots import PROFILE_POINTS, fit_figure

    result, radius, _ = robust
    fig = fit_figure(result)
    radius_ax = fig.axes[0]
    assert radius_ax.get_xscale() == "symlog" and radius_ax.get_ylabel() == "wound radius (µm)"
    assert any(isinstance(c, ErrorbarContainer) for c in radius_ax.containers)
    assert "flagged (down-weighted)" in radius_ax.get_legend_handles_labels()[1]
    (strip,) = [t for t in fig.texts if "profile-likelihood intervals" in t.get_text()]
    text = strip.get_text()
    for name, symbol in (("R0_um", "R₀"), ("sigma", "σ"), ("lambda", "λ"), ("T_s", "T")):
        assert f"{symbol} = {result.reports[name].estimate:.4g}" in text
    # nothing drawn over the data: the estimates under every panel, the legend off the points
    renderer = drawn(fig)
    box = strip.get_window_extent(renderer)
    assert all(box.y1 < ax.get_tightbbox(renderer).y0 for ax in fig.axes)
    legend = radius_ax.get_legend().get_window_extent(renderer)
    points = radius_ax.transData.transform(np.column_stack([radius.times_s, radius.radius_um]))
    assert not any(legend.contains(x, y) for x, y in points)
    labels = [ax.get_xlabel() for ax in fig.axes]
    assert "distance from the wound centre (µm)" not in labels  # no PIV, no velocity panel
    assert all(
        ax.get_xlabel() and ax.get_ylabel() for ax in fig.axes[1:]
    )  # [0] shares [1]'s time axis
    assert (
        fig.axes[1].get_xlabel() == "time since the cut (s)"
        and fig.axes[1].get_xscale() == "symlog"
    )
    profiles = fig.axes[2:]
    assert len(profiles) == 4
    for ax in profiles:
        assert len(ax.lines[0].get_xdata()) >= PROFILE_POINTS


def test_profile_at_is_zero_at_the_estimate_and_on_the_threshold_at_the_interval_ends(robust):
    result, _, _ = robust
    for name in ("R0_um", "T_s"):
        lo, hi = result.reports[name].ci95
        d = result.profile_at(name, [lo, result.reports[name].estimate, hi])
        assert d[1] == pytest.approx(0, abs=1e-6)
        # the ends are located to delta within ~2e-3 of the threshold (intervals.ROOT_TOL)
        # its own threshold where lambda's bound 0 is within reach (fitting/bounds.py)
        threshold = result.reports[name].profile.threshold or result.threshold
        np.testing.assert_allclose(d[[0, 2]], threshold, rtol=5e-3)


@pytest.mark.parametrize(
    "lam, r_inf", [(0.0, 10.0), (0.37, 3.3), (1.0, 10.0), (5.3, 2.0), (30.0, 10.0)]
)
def test_the_half_opening_time_against_the_exact_solution(lam, r_inf):
    t_half = half_opening_time(lam, r_inf)
    r, _ = we.edge(lam, 0.8, r_inf, np.array([t_half]))
    f = (r[0] - we.initial_radius(0.8)) / (we.final_radius(0.8, r_inf) - we.initial_radius(0.8))
    assert f == pytest.approx(0.5, abs=1e-9)


def test_the_summary_says_not_computed_without_intervals(robust):
    _, radius, _ = robust
    result = wo.fit(radius, outer_radius_um=OUTER, loss="soft_l1", intervals=False)
    text = result.summary()
    assert (
        "[open" not in text and "open]" not in text and text.count("not computed") >= 8
    )  # (the path may hold "popen")
    assert all(
        result.to_dict()["parameters"][n]["interval_computed"] is False for n in ("R0_um", "lambda")
    )


def test_fit_writes_the_export_and_the_report(tmp_path):
    write_experiment(tmp_path / "radius.csv")
    done = run(
        "fit",
        tmp_path / "radius.csv",
        "--outer-radius-um",
        OUTER,
        "--radius-noise-um",
        NOISE,
        "--loss",
        "soft_l1",
        "--export",
        tmp_path / "fit",
        "--report",
        tmp_path / "fit.html",
    )
    assert done.returncode == 0, done.stderr
    pts = pd.read_csv(tmp_path / "fit_radius.csv")
    assert (
        list(np.flatnonzero(pts.flagged) + 1) == [OUTLIER_ROW]
        and (tmp_path / "fit_curve.csv").is_file()
    )
    html = (tmp_path / "fit.html").read_text()
    assert (
        "--report" in html
        and hashlib.sha256((tmp_path / "radius.csv").read_bytes()).hexdigest() in html
    )


def test_simulate_prints_a_table_without_csv_and_sweep_columns_carry_units(tmp_path):
    done = run(
        "simulate",
        "--lambda",
        0.5,
        "--sigma",
        0.6,
        "--R0-um",
        10,
        "--T-s",
        10,
        "--outer-radius-um",
        100,
        "--times",
        "0,0.24,5",
    )
    assert done.returncode == 0, done.stderr
    header, *rows = done.stdout.split("\n")[:4]
    assert header.split() == ["time_s", "radius_um", "edge_velocity_um_s"]
    assert (
        rows[0].split()[:2] == ["0", "11"] and rows[1].split()[0] == "0.24"
    )  # R1 = 10 (1 + 0.6 / 6)
    r = float(rows[2].split()[1])
    assert r == pytest.approx(
        10 * we.edge(0.5, 0.6, 10.0, np.array([0.5]))[0][0], rel=1e-5
    )  # 6 digits
    done = run(
        "sweep",
        "--lambda",
        "0.24,1",
        "--sigma",
        "0.3",
        "--R-inf",
        "10",
        "--times",
        "0,0.7,3",
        "--R0-um",
        10,
        "--T-s",
        5,
        "--csv",
        tmp_path / "s.csv",
        "--plot",
        tmp_path / "s.png",
    )
    assert done.returncode == 0, done.stderr
    text = (tmp_path / "s.csv").read_text()
    assert text.splitlines()[0] == "lambda,sigma,R_inf,time_s,wound_radius_um,edge_velocity_um_s"
    assert (
        "0.24," in text
        and "0.7," in text
        and "999999" not in text.split("\n", 1)[1].split(",0.3,")[0]
    )
    df = pd.read_csv(tmp_path / "s.csv")
    np.testing.assert_allclose(df.wound_radius_um[df.time_s == 0], 10 * (1 + 0.3 / 6), rtol=1e-14)
    assert (tmp_path / "s.png").stat().st_size > 10000


def test_every_option_of_every_subcommand_shows_its_default_and_unit():
    """A number's help names its unit (or says it is dimensionless, or a count); an option
    with a default shows it."""
    from wound_opening.cli import parser

    sub = next(a for a in parser()._actions if a.dest == "command")
    units = re.compile(
        r"\bum\b|µm|\(s\)|\bs\b|\bin s\b|Pa\b|um/s|dimensionless|in T\b|time unit|number "
        r"of|processes"
    )
    checked = 0
    for name, p in sub.choices.items():
        text = " ".join(p.format_help().split())
        for action in p._actions:
            numeric = action.type in (float, int) or ",.." in (action.metavar or "")
            if numeric:
                checked += 1
                assert action.help and units.search(action.help), (name, action.dest, action.help)
            if action.default not in (None, False, "==SUPPRESS=="):
                default = (
                    f"{action.default:g}"
                    if isinstance(action.default, float)
                    else f"{action.default}"
                )
                assert re.search(rf"default:? {re.escape(default)}", text), (name, action.dest)
    assert checked >= 20


def test_the_sweep_figure_shows_the_opening_coloured_by_lambda_and_the_half_opening_time(tmp_path):
    from wound_opening.results.sim_plots import sweep_figure

    df = wo.sweep(
        {"lambda": [0.0, 0.3, 3.0, 30.0], "sigma": [0.5, 1.0], "R_inf": [10.0]},
        times=[0, 1, 10, 100],
        processes=1,
    )
    fig = sweep_figure(df, tmp_path / "s.png")
    a, b = fig.axes[:2]
    assert len({tuple(line.get_color()) for line in a.lines}) == 4  # one colour per lambda
    x, y = b.lines[0].get_data()
    np.testing.assert_allclose(y, [half_opening_time(lam, 10.0) for lam in x], rtol=1e-12)
    assert b.get_xscale() == "symlog" and b.get_yscale() == "log"
    assert np.all(np.diff(y) > 0)  # viscosity slows the opening


def test_a_printed_table_cut_short_by_its_reader_is_not_an_error():
    import subprocess

    from test_cli import EXE

    done = subprocess.run(
        f"'{EXE}' simulate --lambda 1 --sigma 1 --R0-um 10 --T-s 10 --outer-radius-um 100 "
        "--points 20000 | head -1",
        shell=True,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert (
        done.stdout.split() == ["time_s", "radius_um", "edge_velocity_um_s"] and done.stderr == ""
    ), done.stderr


def test_a_fixed_parameter_is_said_fixed_in_the_summary_figure_and_report(
    robust, tmp_path, recwarn
):
    """R0 held at the radius of the cut: no profile to draw (its panel says so, with no
    matplotlib warning about an empty axis range), the summary and the figure's text say
    "fixed", and the report renders."""
    _, radius, _ = robust
    params = wo.Parameters()
    params.add("R0_um", value=R0, vary=False)
    result = wo.fit(radius, outer_radius_um=OUTER, loss="soft_l1", params=params, derived=False)
    assert result.converged, result.reasons
    assert re.search(r"^R0_um\s+10\s+fixed$", result.summary(), re.M), result.summary()
    from wound_opening.results.plots import estimates_text, fit_figure

    assert "R₀ = 10 µm  (fixed)" in estimates_text(result)
    fit_figure(result, radius, None, tmp_path / "fit.png", profile_points=4)
    assert not [w for w in recwarn if "xlim" in str(w.message)], [str(w.message) for w in recwarn]
    wo.write_report(tmp_path / "fit.html", result, radius)
    page = (tmp_path / "fit.html").read_text()
    assert (
        '<td>R0_um</td><td class="n">10</td><td>—</td><td>—</td><td>—</td><td>fixed (given)</td>'
        in page
    ), page


def test_intervals_are_printed_to_their_own_precision():
    """An interval's ends to a tenth of its width, rounded outward: [12.155, 12.203] as
    such (not [12.1, 12.3]); over random intervals the printed one holds the computed one
    and is at most a fifth wider."""
    from wound_opening.results.numbers import interval

    assert interval(12.155, 12.203, 12.18) == "[12.155, 12.203]"
    rng = np.random.default_rng(5)
    for _ in range(2000):
        centre = 10 ** rng.uniform(-3, 4) * rng.choice([-1, 1])
        width = abs(centre) * 10 ** rng.uniform(-5, 0.5)
        lo = centre - width * rng.uniform(0.2, 0.8)
        hi = lo + width
        text = interval(lo, hi, centre)
        a, b = (float(x) for x in text.strip("[]").split(", "))
        assert a <= lo and hi <= b and b - a <= 1.2 * width, (lo, hi, text)
