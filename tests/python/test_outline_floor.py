"""The outline's noise floor (inputs/fiji.py, OUTLINE_FLOOR_PX): a thresholded outline's
radius noise, estimated from a fit's residuals, is taken as half a pixel at least, since its
error drifts with the cells the outline takes in, which the residuals absorb. Fiji tables
written from the EXACT solution (python/make_lab_examples.py): with no noise but the
table's rounding the fit's radius noise is the floor, said in the summary and the JSON; with
a noise above the floor, or a noise given, the floor plays no part. The report says it too.
And a decisive sample of the coverage study on rendered movies (docs/fitting.md)."""

from __future__ import annotations

import dataclasses
import json
import shlex

import make_lab_examples as lab
import numpy as np
import pytest
from bench.lab_coverage import KEYS, movie
from bench.lab_movies import measure, radius_only, run_fit
from bench.lab_render import render
from test_lab_readers import fiji, in_um2

from wound_opening.cli import main
from wound_opening.fitting.single import fit
from wound_opening.fitting.wounds import Wound, fit_wounds
from wound_opening.inputs.fiji import OUTLINE_FLOOR_PX, PIXEL_UM
from wound_opening.inputs.series import RadiusSeries
from wound_opening.results.report import write_report

R0 = 8.0


def test_the_floor_is_half_a_pixel_of_the_table_or_none_with_a_noise_given(tmp_path):
    path = tmp_path / "Results.csv"
    lab.write_fiji(path, R0)
    assert OUTLINE_FLOOR_PX == 0.5
    assert fiji(path).noise_floor_um == pytest.approx(0.5 * lab.PIXEL_UM, rel=1e-15)
    assert fiji(path, pixel_size_um=0.13).noise_floor_um == pytest.approx(0.065, rel=1e-15)
    assert fiji(path, noise_um=0.01).noise_floor_um is None
    # a table in um^2 (no pixel size can be given): PIXEL_UM's half
    um2 = tmp_path / "um2.csv"
    um2.write_text(in_um2(path.read_text()))
    series = fiji(um2, length_unit="um", pixel_size_um=None)
    assert series.noise_floor_um == pytest.approx(0.5 * PIXEL_UM, rel=1e-15)


@pytest.mark.parametrize("noise_px, floored", [(0.0, True), (1.0, False)])
def test_the_fit_takes_the_floor_only_where_the_residuals_are_below_it(tmp_path, noise_px, floored):
    path = tmp_path / "Results.csv"
    lab.write_fiji(path, R0, noise_px=noise_px)
    series = fiji(path)
    result = fit(series, outer_radius_um=lab.OUTER_UM, intervals=False, derived=False)
    assert result.converged, result.reasons
    floor = 0.5 * lab.PIXEL_UM
    report = write_report(tmp_path / "r.html", result, series).read_text(encoding="utf-8")
    said = "radius 0.1 µm (the outline's floor of half a pixel, above the residuals'"
    assert (said in report) == floored
    if floored:  # the table's rounding alone: residuals ~1e-6 um
        assert result.residual_rms_um < 1e-3 * floor
        assert result.radius_floor_um == pytest.approx(floor, rel=1e-15)
        np.testing.assert_allclose(result.noise[0], floor, rtol=1e-15)
    else:  # 1 px = 0.2 um of white noise: the residuals' scale, above the floor
        assert result.radius_floor_um is None
        assert 0.15 < result.noise[0] < 0.25, result.noise
    assert json.loads(result.to_json())["noise"]["radius_at_floor_um"] == result.radius_floor_um


def test_the_command_says_the_floor_and_a_given_noise_sets_it_aside(tmp_path, capsys):
    path = tmp_path / "Results.csv"
    lab.write_fiji(path, R0)
    base = (
        f"fit {path} --area-col Area --frame-interval-s {lab.FRAME_S} --cut-after-frame "
        f"{lab.CUT_AFTER} --length-unit px --pixel-size-um {lab.PIXEL_UM} --outer-radius-um "
        f"{lab.OUTER_UM} --fix cut_s=0 --fix outline_offset_um=0"
    )
    assert main(shlex.split(base + f" --json {tmp_path / 'a.json'}")) == 0
    said = capsys.readouterr().out
    assert "radius noise 0.1 um, the outline's floor of half a pixel" in said
    assert json.loads((tmp_path / "a.json").read_text())["noise"]["radius_at_floor_um"] == 0.1
    given = base + f" --radius-noise-um 0.01 --json {tmp_path / 'b.json'}"
    assert main(shlex.split(given)) == 0
    assert "the outline's floor" not in capsys.readouterr().out
    noise = json.loads((tmp_path / "b.json").read_text())["noise"]
    assert noise == {"radius_um": 0.01, "velocity_um_s": None, "radius_at_floor_um": None}


def test_a_rendered_movie_radius_fit_publishes_no_wrong_identified_value(tmp_path):
    """Draw 9 of the coverage study (bench/lab_coverage.py: R0 3.96 um, lambda 1.16, 0.25 s
    frames, T 0.31 s), its outline measured as ImageJ measures it and fitted from the radius
    alone by the documented command. Its residuals read 0.01 um; at that noise the fit
    reported the viscous length and zeta/G identified, their intervals missing the truth
    (2026-12-07, commit 622f908). At the floor every interval holds the truth."""
    m = movie(9, 256)
    frames, truth = render(m)
    record = measure(tmp_path, m, frames, truth)
    res = run_fit(tmp_path, record, radius_only(shlex.split(record["fit_command"])), "fit_radius")
    print((tmp_path / "fit_radius.txt").read_text())
    assert res["exit"] == 0, res.get("reasons")
    for key in (*KEYS, "sigma"):
        assert res["estimates"][key]["covers"], (key, res["estimates"][key])
    noise = json.loads((tmp_path / "fit_radius.json").read_text())["noise"]
    assert noise["radius_at_floor_um"] == pytest.approx(0.1, rel=1e-12), noise


def test_a_floor_that_is_no_noise_is_refused():
    t, r = np.linspace(0.25, 30, 50), np.full(50, 8.0)
    for bad in (0.0, -0.1, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="radius noise floor .* expected finite and > 0"):
            RadiusSeries(t, r, noise_floor_um=bad)


def test_a_several_wound_fit_says_the_floor_per_wound(tmp_path):
    wounds = []
    # white noise below the floor (0.2 px = 0.04 um) and above it (1 px = 0.2 um)
    for R, noise_px in ((4.0, 0.2), (8.0, 1.0)):
        path = tmp_path / f"Results_{R:g}.csv"
        lab.write_fiji(path, R, noise_px=noise_px)
        wounds.append(Wound(fiji(path), lab.OUTER_UM, name=f"R{R:g}"))
    result = fit_wounds(wounds, intervals=False)
    assert result.converged, result.reasons
    rows = {w["name"]: w for w in json.loads(result.to_json())["wounds"]}
    assert rows["R4"]["noise"]["radius_at_floor_um"] == pytest.approx(0.1, rel=1e-12)
    assert rows["R8"]["noise"]["radius_at_floor_um"] is None
    assert rows["R8"]["noise"]["radius_um"] > 0.15, rows["R8"]["noise"]
    lines = [s for s in result.summary().splitlines() if "the outline's floor" in s]
    assert len(lines) == 1 and lines[0].startswith("wound R4: radius noise 0.1 um"), lines


def test_a_floor_set_by_hand_is_not_called_half_a_pixel(tmp_path):
    """A Python caller's own floor (RadiusSeries.noise_floor_um, 0.3 um here) is named as
    given, in the summary and the report: only the readers' floor is half a pixel."""
    path = tmp_path / "Results.csv"
    lab.write_fiji(path, R0)
    read = fiji(path)
    assert read.noise_floor_said == "half a pixel"
    series = dataclasses.replace(read, noise_floor_um=0.3, noise_floor_said="")
    result = fit(series, outer_radius_um=lab.OUTER_UM, intervals=False, derived=False)
    assert result.radius_floor_um == pytest.approx(0.3, rel=1e-15)
    summary = result.summary()
    assert "radius noise 0.3 um, the floor given as noise_floor_um, above" in summary, summary
    report = write_report(tmp_path / "r.html", result, series).read_text(encoding="utf-8")
    assert "radius 0.3 µm (the floor given as noise_floor_um, above the residuals'" in report
    assert "half a pixel" not in summary + report
    from wound_opening.results.plots import noise_words

    assert noise_words(result)[0] == "floor given"  # the figure's legend
    floored = fit(read, outer_radius_um=lab.OUTER_UM, intervals=False, derived=False)
    assert noise_words(floored)[0] == "outline's floor"
