"""Every fit publishable: the several-wound fit from the command line with --fix, --bound,
--prior, --plot, --report and --export on three wounds from the EXACT solution
(python/wound_exact.py; bench/tissue_designs.py's material: viscous length 20 um, tension/G
0.5, zeta/G 0.1 s/um^2, eta/G 10 s; G = 1000 Pa known from a prior), the recording's
settings in the report, interval ends printed to the digits that decide whether a value is
inside, and a red status for a value the physics forbids."""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest
from bench.tissue_designs import OUTERS, R0S, TRUTH, clean, opening

from wound_opening.cli import main
from wound_opening.results.numbers import end, interval
from wound_opening.results.status import forbidden, judge, status
from wound_opening.results.tissue_report import render

G_MEAN, G_SD = 1000.0, 100.0
CUT_MS = 1000.0
TIMES_S = np.geomspace(0.3, 60, 10)
ABSOLUTE = {
    "eta_pa_s": TRUTH["eta_over_G_s"] * G_MEAN,
    "zeta_pa_s_per_um2": TRUTH["zeta_over_G_s_per_um2"] * G_MEAN,
    "tension_pa": TRUTH["tension_over_G"] * G_MEAN,
}


def _covers(ci, v) -> bool:
    lo, hi = ci
    return lo is not None and hi is not None and lo <= v <= hi


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The three-wound CLI fit once: times in ms after a cut at 1000 ms, the noise (1 % of
    each opening) as a column, R0 of the third wound fixed at its truth, tension/G bounded,
    a G prior."""
    d = tmp_path_factory.mktemp("publish")
    rng = np.random.default_rng(7)
    files = []
    for R0, outer in zip(R0S, OUTERS):
        sd = 0.01 * opening(R0, outer)
        r = clean(R0, outer, TIMES_S) + sd * rng.standard_normal(TIMES_S.size)
        path = d / f"wound{R0:g}.csv"
        rows = [
            f"{float(1000 * t + CUT_MS)!r},{float(x)!r},{float(sd)!r}" for t, x in zip(TIMES_S, r)
        ]
        path.write_text("time_ms,radius_um,radius_sd_um\n" + "\n".join(rows) + "\n")
        files.append(str(path))
    out = {k: d / f"tissue.{k}" for k in ("json", "png", "html")}
    argv = files + [
        "--outer-radius-um",
        ",".join(f"{o:g}" for o in OUTERS),
        "--time-col",
        "time_ms",
        "--time-unit",
        "ms",
        "--cut-time",
        f"{CUT_MS:g}",
        "--fix",
        f"R0_um[3]={R0S[2]:g}",
        "--bound",
        "tension_over_G=0:5",
        "--prior",
        f"G_pa={G_MEAN:g}:{G_SD:g}",
        "--json",
        str(out["json"]),
        "--plot",
        str(out["png"]),
        "--report",
        str(out["html"]),
        "--export",
        str(d / "tissue"),
    ]
    code = main(["fit"] + argv)
    return code, d, out, json.loads(out["json"].read_text())


def test_three_wound_cli_with_constraints_writes_every_output(run):
    code, d, out, result = run
    assert code == 0, result.get("reasons")
    assert out["png"].stat().st_size > 10_000 and out["png"].read_bytes()[:4] == b"\x89PNG"
    for R0 in R0S:
        for table in ("radius", "curve"):
            assert (d / f"tissue_wound{R0:g}_{table}.csv").exists()
    radius = (d / "tissue_wound5_radius.csv").read_text().splitlines()
    assert radius[0].startswith("row,file_line,time_s,radius_um,sd_um,model_radius_um,residual_um")
    assert len(radius) == 1 + TIMES_S.size
    third = result["wounds"][2]["R0_um"]
    assert third["estimate"] == R0S[2] and third["fixed"] is True
    assert result["shared"]["tension_over_G"]["bounds"] == [0.0, 5.0]
    assert result["material"]["G_pa"] == {
        "estimate": G_MEAN,
        "sd": G_SD,
        "fixed": False,
        "unit": "Pa",
    }


def test_material_values_cover_the_truth_with_g_from_the_prior(run):
    """Ratios and absolute values (G from the prior) identified, each interval covering the
    truth; printed in the report to the digits that decide it."""
    _, _, out, result = run
    report = out["html"].read_text()
    for name, truth in list(TRUTH.items()) + list(ABSOLUTE.items()):
        m = result["material"][name]
        assert m["identifiable"] and _covers(m["ci95"], truth), (name, m, truth)
        lo, hi = m["ci95"]
        assert f">{end(lo, -1, m['estimate'])}<" in report, name
        assert f">{end(hi, 1, m['estimate'])}<" in report, name
    assert "Material values" in report and "Shared coordinates of the fit" in report
    assert report.count("<h3>Wound ") == 3
    assert result["status"] == {"level": "green", "text": "converged"}


def test_report_records_the_recording_settings(run):
    _, d, out, result = run
    report = out["html"].read_text()
    s = result["settings"]
    assert s["cut_time"] == CUT_MS and s["time_unit"] == "ms" and s["length_unit"] == "um"
    assert [f["path"] for f in s["files"]] == [str(d / f"wound{R0:g}.csv") for R0 in R0S]
    assert s["files"][0]["columns"] == {"time": "time_ms", "radius": "radius_um"}
    assert "<td>cut time (files&#x27; time unit)</td><td>1000</td>" in report
    assert "<td>time unit</td><td>ms</td>" in report
    assert "time: time_ms, radius: radius_um" in report


def test_ends_are_printed_to_the_digits_that_decide():
    """An upper end at 2.4977 with the truth at 2.5 must not read 2.5 or 2.50."""
    assert interval(2.28, 2.4977, 2.4) == "[2.28, 2.498]"
    assert end(2.4977, 1) == "2.498" and end(2.4977, -1) == "2.49"
    assert end(2.4997, 1) == "2.4997"  # 2.50, 2.500 both rounded onto a round number
    assert end(1.9996, -1) == "1.99" and end(1.9996, 1) == "1.9996"
    assert end(2.5, 1) == "2.50"  # exactly a round number: printed so
    assert end(5.004, -1, 5.006) == "5.004"  # 5.00: rounded to a zero
    assert end(0.10004, -1, 0.10001) == "0.10004"  # distinct from the estimate
    assert end(None, 1) == "open" and end(-0.0052, -1) == "-0.00520"
    assert end(12345.6, 1) == "12400" and end(9.96e-7, 1) == "9.96e-7"


def test_a_forbidden_value_gives_a_red_status_naming_it(run):
    """A tension/G <= 0 (and so a final radius below the cut's) is physically impossible: the
    status is red and names it; the report shows no green "converged"."""
    assert forbidden("tension_over_G", -5.4).startswith("tension_over_G = -5.4: must be > 0")
    assert forbidden("R_final_um", -1.7e5) and not forbidden("eta_over_G_s", 0.0)
    bad, edge = judge([("", "sigma", 0.3)], [("", "tension_over_G", -0.1, 0.5)])
    assert bad == [] and "reaches -0.1" in edge[0]
    _, _, _, result = run
    from wound_opening.fitting.wounds import Wound
    from wound_opening.inputs.lab_files import read_radius

    paths = [f["path"] for f in result["settings"]["files"]]
    wounds = [
        Wound(read_radius(p, time_col="time_ms", time_unit="ms", cut_time=CUT_MS), o, name=p)
        for p, o in zip(paths, OUTERS)
    ]
    fitted = _fitted(wounds)
    broken = copy.deepcopy(fitted)
    broken.shared["tension_over_G"].estimate = -5.4
    for w in broken.wounds:
        w["theta"] = (w["theta"][0], -5.4) + tuple(w["theta"][2:])
    st = status(broken)
    assert st.level == "red" and "tension_over_G = -5.4" in st.text, st
    assert "R_final_um" in st.text
    page = render(broken, wounds, command="test")
    assert "physically impossible: tension_over_G = -5.4" in page
    assert "color:#a00" in page and ">converged<" not in page
    assert status(fitted).level == "green"


def _fitted(wounds):
    from wound_opening.fitting.wounds import fit_wounds

    return fit_wounds(wounds, intervals=False)
