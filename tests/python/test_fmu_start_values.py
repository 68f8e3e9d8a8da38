"""From a fit to a simulation: `wound_opening.fmu_start_values` gives the WoundOpening FMU's
start values (by the names of its modelDescription.xml) from material constants, from a
FitResult and from one wound of a TissueFitResult; `fmpy.simulate_fmu` with them gives the
curve `wound_opening.simulate` gives, and the exact solution (python/wound_exact.py), to the
FMU's stated accuracy: |R - R_exact| <= 1e-10 (R_final - R1) for t >= 0.01 T."""

from __future__ import annotations

import math

import numpy as np
import pytest
import wound_exact as we
from bench.tissue_designs import draw
from fmpy import read_model_description, simulate_fmu

import wound_opening as wo

FMU_TOL = 1e-10
#: A tissue with no round numbers: G 250 Pa, eta 300 Pa s, zeta 12 Pa s/um^2, tension 80 Pa.
MATERIAL = dict(G_pa=250.0, eta_pa_s=300.0, zeta_pa_s_per_um2=12.0, tension_pa=80.0, R0_um=8.0)
OUTER = 90.0


def _fmu_radius(start: dict, stop: float, step: float):
    r = simulate_fmu(
        str(wo.fmu_path("WoundOpening.fmu")),
        fmi_type="CoSimulation",
        start_values=start,
        stop_time=stop,
        output_interval=step,
        output=["wound_radius"],
    )
    return r["time"], r["wound_radius"]


def _check_against_simulate_and_exact(start: dict, R0, sigma, lam, T, outer):
    t, radius = _fmu_radius(start, stop=6 * T, step=0.25 * T)
    keep = t >= 0.01 * T
    t, radius = t[keep], radius[keep]
    opening = R0 * (we.final_radius(sigma, outer / R0) - we.initial_radius(sigma))
    exact = R0 * we.edge(lam, sigma, outer / R0, t / T)[0]
    ours = wo.simulate(t, lam=lam, sigma=sigma, T_s=T, R0_um=R0, outer_radius_um=outer).radius_um
    assert np.abs(radius - exact).max() <= FMU_TOL * opening
    assert np.abs(radius - ours).max() <= FMU_TOL * opening
    return t, radius


def test_the_names_are_the_fmus_parameters(fmu_path):
    names = {
        v.name
        for v in read_model_description(fmu_path).modelVariables
        if v.causality == "parameter"
    }
    start = wo.fmu_start_values(**MATERIAL, outer_radius_um=OUTER)
    assert set(start) == {"lambda", "sigma", "R_inf", "R0", "T", "G"}
    assert set(start) <= names


def test_from_material_the_fmu_gives_the_curve_of_simulate_and_the_exact_solution():
    start = wo.fmu_start_values(**MATERIAL, outer_radius_um=OUTER)
    G, eta, zeta, tension, R0 = MATERIAL.values()
    lam, T = 2 * math.sqrt(eta / zeta) / R0, zeta * R0**2 / (4 * G)
    assert start == pytest.approx(
        {"lambda": lam, "sigma": tension / G, "R_inf": OUTER / R0, "R0": R0, "T": T, "G": G},
        rel=1e-15,
    )
    t, radius = _check_against_simulate_and_exact(start, R0, tension / G, lam, T, OUTER)
    # and the material form of `simulate` is the same curve
    ours = wo.simulate(t, **MATERIAL, outer_radius_um=OUTER).radius_um
    opening = R0 * (we.final_radius(tension / G, OUTER / R0) - we.initial_radius(tension / G))
    assert np.abs(radius - ours).max() <= FMU_TOL * opening


def test_from_a_fit_the_fmu_reproduces_the_fitted_curve():
    """A fit of exact radii with noise: the FMU run from `fmu_start_values(result)` is the
    fitted curve (simulate at the estimates) and the exact solution at the estimates."""
    lam, sigma, R0, T, outer = 0.5, 0.5, 10.0, 10.0, 100.0
    t = np.linspace(0.5, 60, 30)
    noise = 0.05 * np.random.default_rng(3).standard_normal(t.size)
    radius = R0 * we.edge(lam, sigma, outer / R0, t / T)[0] + noise
    series = wo.RadiusSeries(t, radius, noise_um=0.05)
    result = wo.fit(series, outer_radius_um=outer, intervals=False, derived=False)
    start = wo.fmu_start_values(result)
    R0_f, sigma_f, lam_f, T_f = result.theta
    assert start == {
        "lambda": lam_f,
        "sigma": sigma_f,
        "R_inf": outer / R0_f,
        "R0": R0_f,
        "T": T_f,
    }  # no G given to the fit: the FMU's default (edge_stress in units of G)
    _check_against_simulate_and_exact(start, R0_f, sigma_f, lam_f, T_f, outer)
    assert wo.fmu_start_values(result, G_pa=100.0)["G"] == 100.0


def test_from_one_wound_of_a_tissue_fit():
    result = wo.fit_wounds(draw(1e-3, 100), intervals=False)
    names = result.names
    assert len(names) == 3
    with pytest.raises(ValueError, match="3 wounds.*wound="):
        wo.fmu_start_values(result)
    with pytest.raises(ValueError, match="no wound named 'nope'"):
        wo.fmu_start_values(result, wound="nope")
    for k in (1, names[1]):
        start = wo.fmu_start_values(result, wound=k)
        row = result.wounds[1]
        R0, sigma, lam, T = row["theta"]
        assert start["R0"] == R0 and start["lambda"] == lam and start["T"] == T
        assert start["R_inf"] == row["outer_radius_um"] / R0
    _check_against_simulate_and_exact(start, R0, sigma, lam, T, row["outer_radius_um"])


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(MATERIAL), "missing outer_radius_um"),
        (dict(MATERIAL, outer_radius_um=8.0), "must exceed R0_um"),
        (dict(MATERIAL, outer_radius_um=OUTER, eta_pa_s=-1.0), "eta_pa_s = -1.0 is invalid"),
        (dict(MATERIAL, outer_radius_um=OUTER, R0_um=float("nan")), "R0_um = nan is invalid"),
    ],
)
def test_invalid_material_is_refused_with_the_reason(kwargs, message):
    with pytest.raises(ValueError, match=message):
        wo.fmu_start_values(**kwargs)


def test_a_fit_and_material_together_or_another_object_are_refused():
    with pytest.raises(ValueError, match="not both: got eta_pa_s"):
        wo.fmu_start_values(object(), eta_pa_s=1.0)
    with pytest.raises(TypeError, match="expected a FitResult"):
        wo.fmu_start_values(object())
