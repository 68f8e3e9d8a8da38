"""FMI 3.0 probes: the default probe radii follow R0 and R_inf, so `fmpy simulate` works
for every accepted parameter set; probes are reference (undeformed) radii X, and the
material point is at X + displacement, where the Python package's current-position
profiles (what PIV measures) agree with it."""

from __future__ import annotations

import numpy as np
import pytest
import wound_exact as we
from fmpy import simulate_fmu

import wound_opening as wo

FRACTIONS = np.array([0, 1, 2, 4, 8, 18]) / 18


def _run(path, params, stop):
    return simulate_fmu(
        path,
        start_values=params,
        stop_time=stop,
        output_interval=stop / 10,
        output=["wound_radius", "edge_velocity", "probe_radii", "displacement", "velocity"],
    )


def test_physical_parameters_run_with_the_default_probes(fmu3_path):
    """R0 = 6 um, T = 0.72 s, G = 250 Pa: the default probes (1 to 10 um) were inside the
    wound and every read of the arrays failed with fmi3Error."""
    result = _run(fmu3_path, {"R0": 6.0, "T": 0.72, "G": 250.0}, 10.0)
    np.testing.assert_allclose(result["probe_radii"][-1], 6.0 * (1 + FRACTIONS * 9), rtol=1e-15)
    assert np.all(np.isfinite(result["displacement"])) and np.all(np.isfinite(result["velocity"]))


@pytest.mark.parametrize("seed", range(6))
def test_default_probes_follow_the_tissue_and_match_the_exact_field(fmu3_path, seed):
    rng = np.random.default_rng(seed)
    lam, sigma = 10 ** rng.uniform(-1, 1), rng.uniform(-5.5, 3)
    R0, T, r_inf = (
        10 ** rng.uniform(-1, 2),
        10 ** rng.uniform(-1, 1),
        [1.001, 1.5, 10 ** rng.uniform(0.3, 2)][seed % 3],
    )
    result = _run(
        fmu3_path,
        {"R0": R0, "T": T, "G": 250.0, "lambda": lam, "sigma": sigma, "R_inf": r_inf},
        5 * T,
    )
    X = result["probe_radii"][-1]
    np.testing.assert_allclose(X, R0 * (1 + FRACTIONS * (r_inf - 1)), rtol=1e-14)
    assert X[0] >= R0 and X[-1] <= R0 * r_inf
    times = result["time"][1:]
    u, v = we.profile(lam, sigma, r_inf, X / R0, times / T)
    amplitude = abs(we.final_radius(sigma, r_inf) - we.initial_radius(sigma))
    assert np.max(np.abs(result["displacement"][1:] / R0 - u)) < 1e-6 * amplitude
    assert np.max(np.abs(result["velocity"][1:] * T / R0 - v)) < 1e-5 * amplitude
    # The first probe is the wound edge: X = R0 is now at the wound radius.
    np.testing.assert_allclose(
        R0 + result["displacement"][:, 0], result["wound_radius"], rtol=1e-13
    )


def test_probes_are_reference_radii_and_the_package_takes_current_ones(fmu3_path):
    """The FMU's displacement at reference radius X is the package's at the current radius
    X + u(X): the same material point, seen where it is now."""
    R0, T, outer = 8.0, 0.9, 80.0
    result = _run(fmu3_path, {"R0": R0, "T": T, "R_inf": outer / R0, "lambda": 0.5}, 3.0)
    X, u, v = result["probe_radii"][-1], result["displacement"][-1], result["velocity"][-1]
    sim = wo.simulate(
        [3.0], lam=0.5, sigma=1.0, R0_um=R0, T_s=T, outer_radius_um=outer, radii_um=X + u
    )
    np.testing.assert_allclose(sim.displacement_um[0], u, rtol=1e-6, atol=1e-9 * R0)
    np.testing.assert_allclose(sim.velocity_um_s[0], v, rtol=1e-5, atol=1e-9 * R0 / T)
