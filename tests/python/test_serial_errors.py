"""Serially correlated radius errors (fitting/serial.py): the innovations of an AR(1) series
are independent with unit variance, and an outline series' correlation is estimated with its
noise at the fit."""

from __future__ import annotations

import numpy as np
import pytest
import wound_exact as we

from wound_opening.fitting import serial
from wound_opening.fitting.objective import Objective, to_z
from wound_opening.inputs.series import RadiusSeries


def _ar1(rng, n, rho, gap=None):
    gap = np.ones(n - 1) if gap is None else gap
    e = np.empty(n)
    e[0] = rng.standard_normal()
    for i in range(1, n):
        r = rho ** gap[i - 1]
        e[i] = r * e[i - 1] + np.sqrt(1 - r * r) * rng.standard_normal()
    return e


def test_innovations_of_an_ar1_series_with_gaps_are_white():
    rng = np.random.default_rng(3)
    t = np.delete(np.arange(4000.0), rng.choice(4000, 300, replace=False))
    gap = serial.gaps(t)
    e = _ar1(rng, t.size, 0.7, gap)
    w = serial.whiten(e, 0.7, gap)
    assert np.var(w) == pytest.approx(1.0, abs=0.06)
    assert abs(np.corrcoef(w[1:], w[:-1])[0, 1]) < 0.05
    assert serial.lag1(e, gap) == pytest.approx(0.7, abs=0.05)


@pytest.mark.parametrize("rho", [0.0, 0.6])
def test_an_outline_series_correlation_is_estimated_with_its_noise(rho):
    """80 frames of the exact radius plus AR(1) errors (sd 0.05 um): at the truth, the fit's
    noise step reads rho within 0.15 and the innovations' scale, 0.05 um, within 20 %; a
    series not flagged serial keeps rho 0."""
    R0, sigma, lam, T = 8.0, 0.5, 1.0, 2.0
    t = np.arange(1, 81) * 0.25
    r = R0 * we.edge(lam, sigma, 100 / R0, t / T)[0]
    e = 0.05 * _ar1(np.random.default_rng(11), t.size, rho)
    z = to_z((R0, sigma, lam, T))
    fits = []
    for flagged in (True, False):
        obj = Objective(RadiusSeries(t, r + e, serial=flagged), None, 100.0)
        obj.estimate_noise(z, robust=False)
        fits.append(obj)
    assert fits[0].radius_rho == pytest.approx(rho, abs=0.15)
    assert fits[0].sd[0] == pytest.approx(0.05, rel=0.2)
    assert fits[1].radius_rho == 0.0
    w = fits[0].residuals(z)
    assert np.std(w) == pytest.approx(1.0, abs=0.2)
