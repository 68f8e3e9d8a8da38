"""Impossible input is refused with the row and the reason (ValueError; exit 2 from the
command line), and a fit that the model cannot stand behind says so ("converged": false,
exit 1), never a table of estimates with standard errors 0."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import wound_exact as we

from wound_opening.fitting.single import fit
from wound_opening.inputs.series import RadiusSeries, VelocityProfile

EXE = str(Path(sys.executable).with_name("wound-opening"))
R0, SIGMA, LAM, T, OUTER = 10.0, 0.5, 0.5, 10.0, 100.0
TIMES = np.linspace(0.5, 60, 40)
RADIUS = R0 * we.edge(LAM, SIGMA, OUTER / R0, TIMES / T)[0]


def piv(r_um, times=(1.0,), v=(0.1,), noise=0.01):
    return VelocityProfile(
        np.asarray(times, float), np.asarray(r_um, float), np.asarray(v, float), noise
    )


@pytest.mark.parametrize(
    "make, message",
    [
        (
            lambda: (RadiusSeries(TIMES, np.where(TIMES == TIMES[3], -1.0, RADIUS)), None, OUTER),
            "row 4: radius_um = -1",
        ),
        (lambda: (RadiusSeries(TIMES, RADIUS, 0.0), None, OUTER), "noise = 0"),
        (lambda: (RadiusSeries(TIMES, RADIUS, -0.08), None, OUTER), "noise = -0.08"),
        (lambda: (RadiusSeries(TIMES, RADIUS, float("nan")), None, OUTER), "must be finite"),
        (
            lambda: (RadiusSeries(TIMES, RADIUS), None, 12.0),
            "not larger than the largest wound radius",
        ),
        (
            lambda: (RadiusSeries(TIMES, RADIUS), piv([5.0]), OUTER),
            "row 1: r_um = 5 is inside the measured wound",
        ),
        (
            lambda: (RadiusSeries(TIMES, RADIUS), piv([150.0]), OUTER),
            "row 1: r_um = 150 is beyond the tissue",
        ),
        (lambda: (RadiusSeries(TIMES, RADIUS), piv([-3.0]), OUTER), "row 1: r_um = -3"),
        (
            lambda: (RadiusSeries(TIMES, RADIUS), piv([20.0], noise=None), OUTER),
            "too few to estimate their own noise",
        ),
        (
            lambda: (RadiusSeries(TIMES[:6], RADIUS[:6]), None, OUTER),
            "too few to estimate their own noise",
        ),
        (
            lambda: (
                RadiusSeries(TIMES, RADIUS, sd_um=np.where(TIMES > 30, 0.0, 0.1)),
                None,
                OUTER,
            ),
            "row 21: uncertainty 0",
        ),
    ],
)
def test_impossible_input_is_refused_with_the_row_and_the_reason(make, message):
    with pytest.raises(ValueError, match=None) as e:
        radius, profile, outer = make()
        fit(radius, profile, outer_radius_um=outer, intervals=False)
    assert message in str(e.value), str(e.value)


def test_per_point_uncertainties_are_used():
    sd = np.where(TIMES < 30, 0.01, 0.03)
    noisy = RADIUS + sd * np.random.default_rng(2).standard_normal(TIMES.size)
    result = fit(RadiusSeries(TIMES, noisy, sd_um=sd), outer_radius_um=OUTER, intervals=False)
    assert result.converged and result.noise_given and result.p_value > 1e-3, result.reasons


def test_outliers_are_flagged_by_a_robust_loss_and_fail_a_least_squares_fit():
    sd = 0.01
    noisy = RADIUS + sd * np.random.default_rng(3).standard_normal(TIMES.size)
    noisy[[10, 25]] += 1.5  # two segmentation outliers
    plain = fit(RadiusSeries(TIMES, noisy, sd), outer_radius_um=OUTER, intervals=False)
    assert not plain.converged and "does not describe the data" in plain.reasons[0]
    robust = fit(
        RadiusSeries(TIMES, noisy, sd), outer_radius_um=OUTER, loss="soft_l1", intervals=False
    )
    assert robust.converged, robust.reasons
    assert {11, 26} <= set(robust.outliers["radius"]) and len(robust.outliers["radius"]) <= 3, (
        robust.outliers
    )
    assert abs(robust.theta[1] - SIGMA) < 0.01


def test_outliers_in_a_lab_file_are_reported_by_their_file_line(tmp_path):
    """Rows 11 and 26 of the data, after a header and a comment line, are file lines 13 and 28."""
    from wound_opening.inputs.lab_files import read_radius

    noisy = RADIUS + 0.01 * np.random.default_rng(3).standard_normal(TIMES.size)
    noisy[[10, 25]] += 1.5  # two segmentation outliers
    path = tmp_path / "radius.csv"
    path.write_text(
        "time_s,radius_um\n# segmented by hand\n"
        + "".join(f"{t},{r}\n" for t, r in zip(TIMES, noisy))
    )
    result = fit(
        read_radius(str(path), noise_um=0.01),
        outer_radius_um=OUTER,
        loss="soft_l1",
        intervals=False,
    )
    assert result.converged, result.reasons
    assert {11, 26} <= set(result.outliers["radius"]), result.outliers
    assert {f"{path}: line 13", f"{path}: line 28"} <= set(result.outliers["where"]), (
        result.outliers
    )
    assert f"{path}: line 28" in " ".join(result.warnings)


def test_the_command_line_refuses_with_exit_2_and_reports_a_failed_fit_with_exit_1(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("time_s,radius_um\n" + "".join(f"{t},{r}\n" for t, r in zip(TIMES, RADIUS)))
    done = subprocess.run(
        [EXE, "fit", str(bad), "--outer-radius-um", "12"], capture_output=True, text=True
    )
    assert done.returncode == 2 and "not larger than the largest wound radius" in done.stderr, (
        done.stderr
    )
    jump = np.where(TIMES > 30, RADIUS + 2.0, RADIUS)  # no parameter values give a jump
    bad.write_text("time_s,radius_um\n" + "".join(f"{t},{r}\n" for t, r in zip(TIMES, jump)))
    out = tmp_path / "fit.json"
    done = subprocess.run(
        [
            EXE,
            "fit",
            str(bad),
            "--outer-radius-um",
            str(OUTER),
            "--radius-noise-um",
            "0.01",
            "--json",
            str(out),
        ],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 1, (done.stdout, done.stderr)
    assert done.stdout.startswith("FIT FAILED")
    report = json.loads(out.read_text())
    assert report["converged"] is False and report["reasons"] and "parameters" not in report
