"""Several wounds of one tissue (`fit_wounds`, `wound-opening fit A.csv B.csv ...`): on data
from the EXACT solution (bench/tissue_designs.py: R0 = 5, 10, 20 um, viscous length 20 um,
tension/G 0.5, zeta/G 0.1 s/um^2) the shared material and every R0 lie in their profile
intervals; a list of one wound gives the single-wound fit; bad input is refused naming the
wound, the file line and the problem."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from bench.fit_designs import covers
from bench.tissue_designs import R0S, TRUTH, draw, wound_truth

from wound_opening.fitting.single import fit
from wound_opening.fitting.wounds import Wound, fit_wounds
from wound_opening.inputs.series import RadiusSeries

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "examples" / "data"
EXE = str(Path(sys.executable).with_name("wound-opening"))


def _misses(result) -> list:
    """The shared quantities and R0s not identified or whose interval misses the truth."""
    out = [
        n
        for n, v in TRUTH.items()
        if not (result.shared[n].identifiable and covers(result.shared[n].ci95, v))
    ]
    return out + [
        f"R0 {R0:g}"
        for R0, rep in zip(R0S, result.r0)
        if not (rep.identifiable and covers(rep.ci95, R0))
    ]


def test_three_wounds_recover_the_material_within_their_intervals_at_low_noise():
    """4 draws at noise 1e-3 of each opening. The first: every shared quantity and every R0
    identified, in its interval. All 4, a small coverage sample: each of the 7 intervals
    (4 shared, 3 R0) may miss the truth in at most 2 of the 4; for honest 95 % intervals
    P(3 or 4 misses of 4) = 4 (0.05^3)(0.95) + 0.05^4 = 4.8e-4 per quantity, < 3.4e-3 for the
    7, while intervals that miss (a fit stopping short, a bias) fail it."""
    misses = {}
    for seed in range(4):
        result = fit_wounds(draw(1e-3, 100 + seed))
        assert result.converged and result.noise_given, result.reasons
        for name in _misses(result):
            misses[name] = misses.get(name, 0) + 1
        if seed == 0:
            assert _misses(result) == [], result.summary()
            first = result
    assert all(m <= 2 for m in misses.values()), misses
    assert first.p_value > 1e-3 and first.dof == 3 * 40 - 6
    for w, R0 in zip(first.wounds, R0S):  # every wound's own parameters follow from the shared ones
        _, sigma, lam, T = w["theta"]
        truth = wound_truth(R0)
        assert abs(lam / truth["lambda"] - 1) < 0.05 and abs(T / truth["T_s"] - 1) < 0.1, (
            w["name"],
            lam,
            T,
        )
    eta = first.shared["eta_over_G_s"]
    l, zg = (
        first.shared["viscous_length_um"].estimate,
        first.shared["zeta_over_G_s_per_um2"].estimate,
    )
    assert eta.estimate == pytest.approx(l**2 * zg / 4, rel=1e-12)
    out = json.loads(first.to_json())
    assert set(out["shared"]) == set(TRUTH) and [w["name"] for w in out["wounds"]] == first.names


def test_one_wound_in_a_list_gives_the_single_wound_fit():
    """In one wound's fit, l = lambda R0, zeta/G = 4 T / R0^2 and eta/G = tau are the single
    fit's derived quantities and R0, sigma its parameters: the same optimum and the same
    profile intervals (each end located to 2e-3 of the threshold: 1e-2 of the interval)."""
    (wound,) = draw(1e-2, 7, r0s=(10.0,), outers=(100.0,))
    one = fit_wounds([wound])
    alone = fit(wound.radius, outer_radius_um=wound.outer_radius_um)
    assert one.converged and alone.converged
    assert one.chi2 == pytest.approx(alone.chi2, rel=1e-6)
    pairs = {
        "viscous_length_um": "viscous_length_um",
        "zeta_over_G_s_per_um2": "zeta_over_G_s_per_um2",
        "eta_over_G_s": "tau_s",
        "tension_over_G": "tension_over_G",
    }
    for mine, theirs in pairs.items():
        rep = one.shared[mine]
        assert rep.estimate == pytest.approx(alone.derived[theirs], rel=1e-4), mine
        lo, hi = alone.derived_ci95[theirs]
        width = hi - lo
        assert abs(rep.ci95[0] - lo) < 1e-2 * width and abs(rep.ci95[1] - hi) < 1e-2 * width, (
            mine,
            rep.ci95,
            (lo, hi),
        )
    lo, hi = alone.reports["R0_um"].ci95
    assert one.r0[0].estimate == pytest.approx(alone.theta[0], rel=1e-5)
    assert abs(one.r0[0].ci95[0] - lo) < 1e-2 * (hi - lo) and abs(one.r0[0].ci95[1] - hi) < 1e-2 * (
        hi - lo
    )
    quick = fit_wounds(
        [wound], intervals=False
    )  # the same optimum; intervals "not computed", not "not identified"
    assert quick.shared["viscous_length_um"].estimate == pytest.approx(
        one.shared["viscous_length_um"].estimate, rel=1e-6
    )
    assert json.loads(quick.to_json())["shared"]["tension_over_G"]["identifiable"] is None
    assert "(not computed)" in quick.summary() and " no " not in quick.summary()


def _radius(n=40, R0=10.0):
    t = np.linspace(0.5, 60, n)
    return RadiusSeries(t, R0 * (1.1 + 0.05 * (1 - np.exp(-t / 10))), 0.01)


@pytest.mark.parametrize(
    "wounds, message",
    [
        ([], "no wound given"),
        ([(_radius(), 100.0)], "experiment 1 is a tuple, expected a Wound"),
        (
            [Wound(_radius(), 100.0, name="a"), Wound(_radius(), 100.0, name="a")],
            "wound names repeat",
        ),
        (
            [Wound(_radius(), 100.0), Wound(_radius(), 10.5)],
            "wound 2: outer_radius_um = 10.5 is not larger than",
        ),
        (
            [Wound(_radius(), 100.0), Wound(_radius(n=4), 100.0, name="small")],
            "wound small: 4 data points: need at least 5",
        ),
        (
            [
                Wound(_radius(), 100.0),
                Wound(RadiusSeries(np.linspace(0, 9, 8), np.full(8, 11.0)), 100.0),
            ],
            "wound 2: radius: 8 points are too few to estimate their own noise",
        ),
    ],
)
def test_impossible_wounds_are_refused_naming_the_wound(wounds, message):
    with pytest.raises((ValueError, TypeError)) as e:
        fit_wounds(wounds)
    assert message in str(e.value), str(e.value)


def _run(*args, cwd=None):
    return subprocess.run(
        [EXE, *map(str, args)], capture_output=True, text=True, timeout=300, cwd=cwd
    )


def test_the_command_line_fits_a_long_table_of_three_wounds(tmp_path):
    """The README's example files (python/example_wounds.py: 2 % noise, estimated by the fit)."""
    done = _run(
        "fit",
        DATA / "tissue_long.csv",
        "--wound-col",
        "wound",
        "--outer-radius-um",
        "80,100,120",
        "--json",
        tmp_path / "fit.json",
    )
    assert done.returncode == 0, done.stderr
    out = json.loads((tmp_path / "fit.json").read_text())
    assert out["converged"] and [w["name"] for w in out["wounds"]] == ["R5", "R10", "R20"]
    assert [w["outer_radius_um"] for w in out["wounds"]] == [80.0, 100.0, 120.0]
    for name, truth in TRUTH.items():
        p = out["shared"][name]
        assert p["identifiable"] and p["ci95"][0] < truth < p["ci95"][1], (name, p)
    for w, R0 in zip(out["wounds"], R0S):
        assert w["R0_um"]["ci95"][0] < R0 < w["R0_um"]["ci95"][1], w
    assert "shared by 3 wounds" in done.stdout and "eta_over_G_s" in done.stdout


def _long(path, rows):
    path.write_text("wound,time_s,radius_um\n" + "".join(f"{w},{t},{r}\n" for w, t, r in rows))
    return path


@pytest.mark.parametrize(
    "args, message",
    [
        (
            ["A", "B", "--outer-radius-um", "80,100,120"],
            "--outer-radius-um: 3 values for 2 wounds (A.csv, B.csv)",
        ),
        (
            ["A", "B", "--outer-radius-um", "100", "--profile", "P"],
            "--profile: 1 files for 2 wounds",
        ),
        (
            ["A", "B", "--outer-radius-um", "100", "--wound-col", "wound"],
            "--wound-col reads one long table",
        ),
        (
            ["A", "--outer-radius-um", "100,120"],
            "one radius file (one wound) takes one outer radius",
        ),
        (
            ["LONG", "--wound-col", "wound", "--outer-radius-um", "100"],
            "LONG.csv: wound 'b' (lines 8-10): 3 rows: too few",
        ),
        (
            ["BACK", "--wound-col", "wound", "--outer-radius-um", "100"],
            "BACK.csv: line 4: time_s = 1 is before line 3's 2 (times must be ascending within "
            "each wound)",
        ),
        (["LONG", "--wound-col", "id", "--outer-radius-um", "100"], "no column 'id'"),
        (
            ["A", "B", "--outer-radius-um", "100", "--fix", "lambda=2"],
            "--fix 'lambda=2': parameter 'lambda' is unknown for several wounds (lambda is one "
            "wound's parameter: with several wounds use viscous_length_um",
        ),
        (
            ["A", "B", "--outer-radius-um", "100", "--prior", "eta_over_G_s=10:1"],
            "eta_over_G_s is not a coordinate of the fit of several wounds",
        ),
    ],
)
def test_bad_wound_input_is_refused_in_one_line(tmp_path, args, message):
    t = np.linspace(0.5, 60, 12)
    for name in ("A", "B"):
        (tmp_path / f"{name}.csv").write_text(
            "time_s,radius_um\n" + "".join(f"{x},{11 + x / 100}\n" for x in t)
        )
    (tmp_path / "P.csv").write_text("time_s,r_um,velocity_um_s\n1,30,0.1\n")
    a = [("a", x, 11 + x / 100) for x in range(6)]
    _long(tmp_path / "LONG.csv", a + [("b", x, 11) for x in range(3)])
    _long(tmp_path / "BACK.csv", [("a", 0, 11), ("a", 2, 11.1), ("a", 1, 11.2)] + a)
    files = {"A": "A.csv", "B": "B.csv", "P": "P.csv", "LONG": "LONG.csv", "BACK": "BACK.csv"}
    done = _run("fit", *[files.get(a, a) for a in args], cwd=tmp_path)
    assert done.returncode == 2, (done.stdout, done.stderr)
    assert message in done.stderr and len(done.stderr.strip().splitlines()) == 1, done.stderr
