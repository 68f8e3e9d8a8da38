"""Answers that mean something: a run that leaves the linear model's validity (wound radius
<= 0, a folded ring, strains beyond 1 at the wound edge) is told so with fmi2Warning, the
reason and the time; a run inside it is not. Parameter sets that are no radius from the
start (sigma <= -6) are refused (tests/python/test_domain.py)."""

from __future__ import annotations

import numpy as np
import pytest
import wound_exact as we


def warnings(slave):
    return [m.message for m in slave.log if m.status == 1]


def _run(make_slave, params, times):
    s = make_slave()
    s.initialize(params)
    for t in times:
        s.step_to(t)
    return s


TIMES = [0.01, 0.1, 1.0, 10.0, 100.0, 1000.0]


@pytest.mark.parametrize(
    "params, reason",
    [
        (
            {"sigma": -2.0},
            "the wound radius is -0.",
        ),  # R -> 1 + (2 sigma / 3) R_inf^2 / (R_inf^2 - 1) = -0.35
        ({"sigma": 1.0, "R_inf": 1.01}, "strain at the wound edge"),  # a thin ring opens to 34.8 R0
        ({"sigma": 2.0, "lambda": 0.3}, "strain at the wound edge"),  # R_final - 1 = 1.35
        ({"sigma": -5.9}, "the wound radius is"),  # R1 = 0.017 R0, then closing
    ],
)
def test_leaving_the_validity_is_a_warning_with_reason_and_time(make_slave, params, reason):
    s = _run(make_slave, params, TIMES)
    found = warnings(s)
    assert len(found) == 1 and reason in found[0] and "at t = " in found[0], found


@pytest.mark.parametrize("seed", range(6))
def test_runs_inside_the_validity_are_quiet(make_slave, seed):
    """Random parameters whose exact edge strain stays below 1 (checked against the exact
    solution at every step) give no warning."""
    rng = np.random.default_rng(seed)
    lam, r_inf = 10 ** rng.uniform(-1, 1), 10 ** rng.uniform(0.3, 2)
    sigma = rng.uniform(-1.3, 1.3)
    radius, _ = we.edge(lam, sigma, r_inf, np.array(TIMES))
    assert np.all(np.abs(radius - 1) < 0.95) and abs(we.final_radius(sigma, r_inf) - 1) < 0.95
    s = _run(make_slave, {"lambda": lam, "sigma": sigma, "R_inf": r_inf}, TIMES)
    assert warnings(s) == [], (lam, sigma, r_inf, s.log_text())
