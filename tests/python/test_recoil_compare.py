"""python/bench/recoil_compare.py (docs/fitting.md, "What the usual recoil fit reads"): its
truth is the exact solution, its recoil fit is a correct least-squares fit, and two claims of
its table hold: with T fixed in the friction regime the recoil's tau is the friction time T,
not eta/G, and its v0 a small part of v(0+); two tissues that differ only in friction read as
different "tension" and "viscosity" to the recoil fit, while this model's intervals of
tension/G and eta/G cover the (equal) truths of both (on the long recording)."""

from __future__ import annotations

import numpy as np
import pytest
import wound_exact as we
from bench import recoil_compare as rc


@pytest.mark.parametrize("lam", [0.1, 1.0, 10.0])
def test_the_true_initial_velocity_is_the_exact_edge_velocity_just_after_the_cut(lam):
    T = 10.0
    t = np.array([1e-9, 1e-8]) * min(1.0, lam**2)  # in T, well inside the first viscous time
    v = we.edge(lam, rc.SIGMA, rc.OUTER / rc.R0, t)[1] * rc.R0 / T
    assert rc.initial_velocity(lam, T) == pytest.approx(v[0], rel=1e-6)


def test_the_recoil_fit_recovers_an_exponential():
    t = np.linspace(0.5, 30, 60)
    got = rc.recoil_fit(t, rc.exponential(t, 11.0, 2.0, 7.0))
    assert (got["R1"], got["D"], got["tau"]) == pytest.approx((11.0, 2.0, 7.0), rel=1e-8)
    assert got["v0"] == pytest.approx(2.0 / 7.0, rel=1e-8)


def test_with_T_fixed_in_the_friction_regime_tau_reads_T_and_v0_a_fraction_of_v0_true():
    row = rc.case("T fixed", 0.1, "short", model=False)
    assert row["eta_over_G_s"] == pytest.approx(0.1)  # eta/G = lambda^2 T
    assert row["tau_over_eta_G"] > 50  # the table: 115
    assert 0.8 < row["tau_over_T"] < 1.5  # the table: 1.15
    assert row["v0_over_true"] < 0.2  # the table: 10 %


def test_two_tissues_differing_in_friction_only():
    """The long window (the short one identifies neither tension/G nor eta/G at lambda 0.3:
    this model then says so, with intervals that still cover the truth)."""
    rows = [rc.case(rc.DESIGNS[0], lam, "long") for lam in rc.CONDITIONS]
    ratios = rc.two_conditions(rows)["long"]
    assert ratios["v0"] > 2 and ratios["tau"] < 0.8  # the table: x3.7 and x0.36; truth x1
    assert ratios["tension_over_G"] == pytest.approx(1, abs=0.1)
    for row in rows:
        value, (lo, hi), identified = row["model"]["tension_over_G"]
        assert identified and lo < rc.SIGMA < hi, row
        value, (lo, hi), identified = row["model"]["eta_over_G_s"]
        assert (lo is None or lo < rc.TAU) and (hi is None or rc.TAU < hi), row
        assert identified or row["lambda"] < 1, row  # identified at lambda = 1
