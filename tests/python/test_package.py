"""The wound_opening package's `simulate` in physical units, against the exact solution
(python/wound_exact.py, independent of the solver): radius and edge velocity at any times,
displacement and velocity at CURRENT distances from the wound centre (as PIV measures)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import wound_exact as we

import wound_opening as wo

R0, T, OUTER = 10.0, 10.0, 100.0  # um, s, um: R_inf = 10


@pytest.mark.parametrize("lam", [0.0, 0.1, 1.0, 10.0])
def test_radius_and_edge_velocity_match_the_exact_solution_at_any_times(lam):
    times = np.array([30.0, 0.1, 5.0, 60.0, 0.5, 12.5])  # any order, not a grid
    sim = wo.simulate(times, lam=lam, sigma=0.5, R0_um=R0, T_s=T, outer_radius_um=OUTER)
    radius, velocity = we.edge(lam, 0.5, OUTER / R0, times / T)
    amplitude = R0 * (we.final_radius(0.5, OUTER / R0) - we.initial_radius(0.5))
    # The solver's tolerance (1e-10 of the opening) with a margin for the reference's 1e-13.
    assert np.max(np.abs(sim.radius_um - R0 * radius)) < 1e-9 * amplitude
    v_scale = np.maximum(np.abs(velocity), 1e-2 * amplitude / R0) * R0 / T
    assert np.max(np.abs(sim.edge_velocity_um_s - R0 / T * velocity) / v_scale) < 1e-6
    np.testing.assert_array_equal(sim.times_s, times)


def test_the_wound_starts_at_r1_not_r0_and_lambda_zero_velocity_at_the_cut_is_infinite():
    sim = wo.simulate([0.0, 1.0], lam=0.0, sigma=0.6, R0_um=R0, T_s=T, outer_radius_um=OUTER)
    assert sim.radius_um[0] == pytest.approx(R0 * (1 + 0.6 / 6), rel=1e-12)
    assert sim.edge_velocity_um_s[0] == np.inf and np.isfinite(sim.edge_velocity_um_s[1])


@pytest.mark.parametrize("lam", [0.3, 3.0])
def test_profiles_at_current_positions_match_the_exact_solution(lam):
    sigma, r_inf, times = 0.8, OUTER / R0, np.array([2.0, 20.0])
    x = np.array([1.0001, 1.5, 3.0, 7.0])  # reference radii, in R0
    u, v = we.profile(lam, sigma, r_inf, x, times / T)
    for i, t in enumerate(times):
        current_um = R0 * (x + u[i])  # where PIV sees these material points at t
        sim = wo.simulate(
            [t], lam=lam, sigma=sigma, R0_um=R0, T_s=T, outer_radius_um=OUTER, radii_um=current_um
        )
        amplitude = R0 * sigma
        # The grid's tolerance (1e-10) is promised at the edge; inside the tissue, where the
        # elements are coarser, the measured error is ~5e-9 of sigma R0: asserted at 1e-7.
        assert np.max(np.abs(sim.displacement_um[0] - R0 * u[i])) < 1e-7 * amplitude
        assert np.max(np.abs(sim.velocity_um_s[0] - R0 / T * v[i])) < 1e-6 * amplitude / T
        # At the wound edge itself the profile gives the edge velocity.
        edge = wo.simulate(
            [t],
            lam=lam,
            sigma=sigma,
            R0_um=R0,
            T_s=T,
            outer_radius_um=OUTER,
            radii_um=sim.radius_um,
        )
        assert edge.velocity_um_s[0, 0] == pytest.approx(sim.edge_velocity_um_s[0], rel=1e-12)


def test_an_edge_stress_in_pascals_scales_the_opening_by_superposition():
    common = dict(lam=1.0, sigma=1.0, R0_um=R0, T_s=T, outer_radius_um=OUTER)
    times = [0.0, 5.0, 50.0]
    free = wo.simulate(times, **common)
    held = wo.simulate(times, edge_stress_pa=30.0, G_pa=100.0, **common)
    r1 = R0 * (1 + 1 / 6)
    np.testing.assert_allclose(
        held.radius_um - r1, 0.7 * (free.radius_um - r1), rtol=1e-9, atol=1e-12
    )
    with pytest.raises(ValueError, match="needs G_pa"):
        wo.simulate(times, edge_stress_pa=30.0, **common)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(times_s=[1.0, -1.0]), "times_s must be"),
        (dict(times_s=[np.nan]), "times_s must be"),
        (dict(R0_um=0.0), "R0_um = 0.0 is invalid"),
        (dict(outer_radius_um=5.0), "outer_radius_um = 5.0 is invalid: expected > R0_um"),
        (dict(lam=-1.0), "lambda"),
        (dict(radii_um=[10.5]), r"inside the wound .* lengths in R0 = 10.0 um"),
        (dict(radii_um=[150.0]), "outside the tissue"),
    ],
)
def test_bad_input_is_refused_with_the_reason(kwargs, message):
    args = dict(times_s=[1.0], lam=1.0, sigma=0.5, R0_um=R0, T_s=T, outer_radius_um=OUTER) | kwargs
    with pytest.raises(ValueError, match=message):
        wo.simulate(args.pop("times_s"), **args)


@pytest.mark.parametrize("override", [None, "/nonexistent/libwound_opening.so"])
def test_a_missing_native_library_is_a_clear_error(tmp_path, override):
    """The package copied outside the repository: the library is in neither the package nor a
    checkout, and the error names both; with $WOUND_OPENING_LIB set, that path alone is
    looked at (an explicit choice is never silently replaced) and named."""
    shutil.copytree(
        Path(wo.__file__).parent,
        tmp_path / "wound_opening",
        ignore=shutil.ignore_patterns("__pycache__", "*.so", "fmu"),
    )
    env = {k: v for k, v in os.environ.items() if k != "WOUND_OPENING_LIB"}
    env["PYTHONPATH"] = str(tmp_path)
    if override:
        env["WOUND_OPENING_LIB"] = override
    code = (
        "import wound_opening as w; w.simulate([1.0], lam=1, sigma=1, R0_um=1, T_s=1, "
        "outer_radius_um=10)"
    )
    done = subprocess.run(
        [sys.executable, "-c", code],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode != 0
    looked_at = (
        [override]
        if override
        else [
            tmp_path / "wound_opening" / "libwound_opening.so",
            tmp_path.parent / "target" / "release" / "libwound_opening.so",
        ]
    )
    assert (
        f"native library not found at {' or '.join(map(str, looked_at))}; build it with `cargo "
        f"build --release`" in done.stderr
    )


def test_the_environment_variable_overrides_the_library_found(tmp_path, monkeypatch):
    """$WOUND_OPENING_LIB names the library to load even where the package would find one."""
    from wound_opening import _native

    monkeypatch.setenv("WOUND_OPENING_LIB", str(tmp_path / "chosen.so"))
    assert _native.library_paths() == [tmp_path / "chosen.so"]
    monkeypatch.delenv("WOUND_OPENING_LIB")
    assert tmp_path / "chosen.so" not in _native.library_paths()


@pytest.mark.parametrize("seed", range(4))
def test_the_tolerance_sets_the_accuracy_of_the_radius(seed):
    """simulate(tolerance=...) picks the grid of the radius and edge velocity too: the radius
    error relative to the opening stays within each tolerance, and grows as it is loosened
    (with the finest grid whatever was asked, a loose tolerance would change nothing)."""
    rng = np.random.default_rng(seed)
    lam, sigma, r_inf = 10 ** rng.uniform(-1, 1), rng.uniform(0.05, 3), 10 ** rng.uniform(0.5, 2)
    R0_um, T_s = rng.uniform(4, 12), rng.uniform(0.3, 3)
    times = T_s * np.sort(
        np.concatenate([10 ** rng.uniform(-2, 0, 8), 10 ** rng.uniform(0, 2.5, 8)])
    )
    radius, _ = we.edge(lam, sigma, r_inf, times / T_s)
    amplitude = we.final_radius(sigma, r_inf) - we.initial_radius(sigma)
    errors = {}
    for tolerance in (1e-2, 1e-4, 1e-6, 1e-8, 1e-10):
        sim = wo.simulate(
            times,
            lam=lam,
            sigma=sigma,
            R0_um=R0_um,
            T_s=T_s,
            outer_radius_um=R0_um * r_inf,
            tolerance=tolerance,
        )
        errors[tolerance] = np.max(np.abs(sim.radius_um / R0_um - radius)) / amplitude
        assert errors[tolerance] <= tolerance, (tolerance, errors)
    assert errors[1e-2] > 100 * errors[1e-10], errors


def test_a_tolerance_out_of_range_is_refused_for_the_radius_too():
    with pytest.raises(ValueError, match="tolerance"):
        wo.simulate(
            [1.0], lam=1.0, sigma=1.0, R0_um=R0, T_s=T, outer_radius_um=OUTER, tolerance=0.0
        )


def test_the_package_exports_functions_whatever_was_imported_first():
    """`wound_opening.fit` and `.sweep` are the functions even after their modules were
    imported directly (a module named like the function it exports would replace it)."""
    import importlib

    import wound_opening

    importlib.import_module("wound_opening.fitting.single")
    importlib.import_module("wound_opening.sweeping")
    from wound_opening import fit, sweep

    assert callable(fit) and callable(sweep)
    assert callable(wound_opening.fit) and callable(wound_opening.sweep)
