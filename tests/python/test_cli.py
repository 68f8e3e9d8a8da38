"""The command line `wound-opening` through subprocess: fit (JSON in its documented format, a
figure), sweep (CSV and Parquet), simulate, and bad input: one line naming the file, the
file line and the problem, exit code 2, no traceback."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import wound_exact as we

EXE = str(Path(sys.executable).with_name("wound-opening"))
LAM, SIGMA, R0, T, OUTER = 0.5, 0.5, 10.0, 10.0, 100.0


def run(*args, cwd=None):
    return subprocess.run(
        [EXE, *map(str, args)], capture_output=True, text=True, timeout=300, cwd=cwd
    )


def write_radius(path, noise=0.05, seed=3):
    t = np.linspace(0.5, 60, 30)
    radius = R0 * we.edge(LAM, SIGMA, OUTER / R0, t / T)[0] + noise * np.random.default_rng(
        seed
    ).standard_normal(t.size)
    pd.DataFrame({"time_s": t, "radius_um": radius}).to_csv(path, index=False)


def write_profile(path, seed=4):
    x, times = np.linspace(1.05, 6, 10), np.array([1.0, 3.0])
    u, v = we.profile(LAM, SIGMA, OUTER / R0, x, times / T)
    noise = 0.05 * np.abs(v).max() * np.random.default_rng(seed).standard_normal(v.shape)
    pd.DataFrame(
        {
            "time_s": np.repeat(times, x.size),
            "r_um": (R0 * (x + u)).ravel(),
            "velocity_um_s": (R0 / T * v + noise).ravel(),
        }
    ).to_csv(path, index=False)


def test_fit_writes_the_json_of_the_issue_and_a_figure(tmp_path):
    write_radius(tmp_path / "radius.csv")
    write_profile(tmp_path / "profile.csv")
    done = run(
        "fit",
        tmp_path / "radius.csv",
        "--profile",
        tmp_path / "profile.csv",
        "--outer-radius-um",
        OUTER,
        "--json",
        tmp_path / "fit.json",
        "--plot",
        tmp_path / "fit.png",
    )
    assert done.returncode == 0, done.stderr
    out = json.loads((tmp_path / "fit.json").read_text())
    assert set(out["parameters"]) == {"R0_um", "sigma", "lambda", "T_s"}
    for name, truth in {"R0_um": R0, "sigma": SIGMA, "lambda": LAM, "T_s": T}.items():
        p = out["parameters"][name]
        assert {"estimate", "stderr", "ci95", "identifiable"} <= set(p)
        assert p["identifiable"] is True, (name, p)
        # 7 standard errors: a draw this far off would be a bug, not noise.
        assert abs(p["estimate"] - truth) < 7 * p["stderr"], (name, p)
    assert {
        "tau_s",
        "viscous_length_um",
        "zeta_over_G_s_per_um2",
        "tension_over_G",
        "R1_um",
        "R_final_um",
    } <= set(out["derived"])
    tau_lo, tau_hi = out["derived_ci95"]["tau_s"]
    assert tau_lo < LAM**2 * T < tau_hi, out["derived_ci95"]
    assert out["derived"]["tau_s"] == pytest.approx(
        out["parameters"]["lambda"]["estimate"] ** 2 * out["parameters"]["T_s"]["estimate"]
    )
    assert 0.02 < out["residual_rms_um"] < 0.1  # the noise is 0.05 um
    assert (tmp_path / "fit.png").stat().st_size > 10_000


def test_fit_of_the_radius_alone_says_lambda_is_not_identified_and_what_would(tmp_path):
    write_radius(tmp_path / "radius.csv", noise=0.2)  # 2 % noise on the radius
    done = run(
        "fit", tmp_path / "radius.csv", "--outer-radius-um", OUTER, "--json", tmp_path / "fit.json"
    )
    assert done.returncode == 0, done.stderr
    lam = json.loads((tmp_path / "fit.json").read_text())["parameters"]["lambda"]
    assert lam["identifiable"] is False
    assert (
        "not identified (95 % interval [0, " in lam["advice"]
        and "add a velocity profile within" in lam["advice"]
    )


def test_sweep_and_simulate_write_their_tables(tmp_path):
    done = run(
        "sweep",
        "--lambda",
        "0.1,1,10",
        "--sigma",
        "0.5,1",
        "--R-inf",
        "10",
        "--times",
        "0,1,10",
        "--csv",
        tmp_path / "s.csv",
        "--parquet",
        tmp_path / "s.parquet",
        "--plot",
        tmp_path / "s.png",
    )
    assert done.returncode == 0, done.stderr
    df = pd.read_csv(tmp_path / "s.csv")
    assert list(df.columns) == ["lambda", "sigma", "R_inf", "time", "wound_radius", "edge_velocity"]
    assert len(df) == 3 * 2 * 3
    pd.testing.assert_frame_equal(
        pd.read_parquet(tmp_path / "s.parquet"), df.astype(float), check_exact=True
    )
    done = run(
        "simulate",
        "--lambda",
        1,
        "--sigma",
        1,
        "--R0-um",
        10,
        "--T-s",
        10,
        "--outer-radius-um",
        100,
        "--times",
        "0,5,50",
        "--radii-um",
        "20,30",
        "--csv",
        tmp_path / "m.csv",
        "--plot",
        tmp_path / "m.png",
    )
    assert done.returncode == 0, done.stderr
    m = pd.read_csv(tmp_path / "m.csv")
    assert m.radius_um.iloc[0] == pytest.approx(10 * (1 + 1 / 6))
    assert len(m) == 6 and (tmp_path / "m.png").is_file()


BAD = [  # line = the file line, 1 = the header
    ("time_s,radius\n0,1\n", "line 1: no column 'radius_um'"),
    ("time_s,radius_um\n0,10\n1,abc\n", "line 3: radius_um = 'abc' is not a number"),
    ("time_s,radius_um\n0,10\n-1,10\n", "line 3: time_s = -1 is before the cut at 0"),
    (
        "time_s,radius_um\n0,10\n2,10\n1,10\n",
        "line 4: time_s = 1 is before line 3's 2 (times must be ascending)",
    ),
    ("time_s,radius_um\n0,10\n1,nan\n", "line 3: radius_um = 'nan' is not a finite number"),
    ("time_s,radius_um\n0,10\n1,10.1\n2,10.2\n", "3 data rows: too few points, need at least 5"),
    ("time_s,radius_um\n0,10,3\n", "line 2: 3 cells, expected 2"),
]


@pytest.mark.parametrize("content, message", BAD)
def test_bad_input_is_one_line_with_exit_code_2(tmp_path, content, message):
    path = tmp_path / "radius.csv"
    path.write_text(content)
    done = run("fit", path, "--outer-radius-um", OUTER)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in done.stderr, done.stderr
    assert lines[0].startswith(f"wound-opening fit: error: {path}: ") and message in lines[0], (
        lines[0]
    )


def test_a_bad_profile_file_and_a_missing_file_are_named(tmp_path):
    write_radius(tmp_path / "radius.csv")
    (tmp_path / "p.csv").write_text("time_s,r_um,velocity_um_s\n1,12,x\n")
    done = run(
        "fit", tmp_path / "radius.csv", "--profile", tmp_path / "p.csv", "--outer-radius-um", OUTER
    )
    assert (
        done.returncode == 2
        and f"{tmp_path / 'p.csv'}: line 2: velocity_um_s = 'x' is not a number" in done.stderr
    )
    done = run("fit", tmp_path / "none.csv", "--outer-radius-um", OUTER)
    assert (
        done.returncode == 2
        and "none.csv: cannot read the file (No such file or directory)" in done.stderr
    )
    done = run(
        "sweep",
        "--lambda",
        "1,x",
        "--sigma",
        "1",
        "--R-inf",
        "10",
        "--times",
        "1",
        "--csv",
        tmp_path / "s.csv",
    )
    assert (
        done.returncode == 2
        and "--lambda: '1,x' is not a comma-separated list of numbers" in done.stderr
    )


README_BLOCK = "<!-- quick start: one wound, a known R0 and G from AFM"


def readme_quick_start() -> list[str]:
    """The README's one-wound quick-start command (the sh block after its marker) as
    arguments to `wound-opening`."""
    import shlex

    text = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    block = text[text.index(README_BLOCK) :]
    command = block[block.index("```sh\n") + 6 : block.index("\n```", block.index("```sh\n"))]
    args = shlex.split(command.replace("\\\n", " "))
    assert args[0] == "wound-opening", args
    return args[1:]


def check_quick_start(work: Path) -> None:
    """The quick start's fit.json: R0 fixed, G's prior, and the material values of the
    example export (python/example_export.py) inside their 95 % intervals."""
    import example_export as ex

    out = json.loads((work / "fit.json").read_text())
    assert out["converged"] is True
    p = out["parameters"]
    assert p["R0_um"]["estimate"] == ex.R0_UM and p["R0_um"]["fixed"] is True
    lam, sigma, T = ex.parameters()
    for name, truth in (("sigma", sigma), ("lambda", lam), ("T_s", T)):
        lo, hi = p[name]["ci95"]
        assert lo < truth < hi, (name, lo, truth, hi)
    m = out["material"]
    assert m["G_pa"] == {"estimate": 1100.0, "sd": 150.0, "fixed": False, "unit": "Pa"}
    G, mat = ex.MATERIAL["G_pa"], ex.MATERIAL
    truth = {
        "eta_over_G_s": mat["eta_pa_s"] / G,
        "zeta_over_G_s_per_um2": mat["zeta_pa_s_per_um2"] / G,
        "tension_over_G": mat["tension_pa"] / G,
        "viscous_length_um": lam * ex.R0_UM,
        "eta_pa_s": mat["eta_pa_s"],
        "zeta_pa_s_per_um2": mat["zeta_pa_s_per_um2"],
        "tension_pa": mat["tension_pa"],
    }
    for name, value in truth.items():
        lo, hi = m[name]["ci95"]
        assert m[name]["identifiable"] and lo < value < hi, (name, lo, value, hi)
    assert m["eta_pa_s"]["estimate"] == pytest.approx(
        1100.0 * m["eta_over_G_s"]["estimate"], rel=1e-14
    )


def test_the_readme_quick_start_fits_a_microscope_export_with_a_fixed_r0_and_a_prior_on_g(tmp_path):
    args = readme_quick_start()
    data = Path(__file__).resolve().parents[2] / "examples" / "data" / "ablation_export.csv"
    (tmp_path / "examples" / "data").mkdir(parents=True)
    (tmp_path / "examples" / "data" / "ablation_export.csv").write_bytes(data.read_bytes())
    done = run(*args, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "eta_pa_s = " in done.stdout and "G_pa = 1100 Pa (prior, sd 150 Pa)" in done.stdout
    check_quick_start(tmp_path)


def test_the_example_export_is_the_one_its_script_makes(tmp_path):
    """examples/data/ablation_export.csv is reproducible from python/example_export.py."""
    import example_export as ex

    ex.export(tmp_path / "a.csv")
    data = Path(__file__).resolve().parents[2] / "examples" / "data" / "ablation_export.csv"
    assert (tmp_path / "a.csv").read_bytes() == data.read_bytes()


def test_simulate_takes_the_material_constants_or_refuses_a_mix(tmp_path):
    material = run(
        "simulate",
        "--G-pa",
        100,
        "--eta-pa-s",
        1000,
        "--zeta-pa-s-per-um2",
        40,
        "--tension-pa",
        100,
        "--R0-um",
        10,
        "--outer-radius-um",
        100,
        "--times",
        "0.5,3,20",
        "--csv",
        tmp_path / "m.csv",
    )
    assert material.returncode == 0, material.stderr
    got = pd.read_csv(tmp_path / "m.csv")
    exact = 10.0 * we.edge(1.0, 1.0, 10.0, np.array([0.5, 3.0, 20.0]) / 10.0)[0]
    opening = 10.0 * (we.final_radius(1.0, 10.0) - we.initial_radius(1.0))
    assert np.max(np.abs(got["radius_um"].to_numpy() - exact)) < 1e-9 * opening
    mixed = run(
        "simulate",
        "--G-pa",
        100,
        "--eta-pa-s",
        1000,
        "--sigma",
        1,
        "--R0-um",
        10,
        "--outer-radius-um",
        100,
        "--csv",
        tmp_path / "x.csv",
    )
    assert mixed.returncode == 2 and "not both" in mixed.stderr and "Traceback" not in mixed.stderr
    write_radius(tmp_path / "radius.csv")
    bad = run("fit", tmp_path / "radius.csv", "--outer-radius-um", 100, "--fix", "R0_um=500")
    assert bad.returncode == 2 and "outside the accepted range" in bad.stderr, bad.stderr
