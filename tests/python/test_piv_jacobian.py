"""The PIV columns of `Objective.jacobian` against the EXACT solution (python/wound_exact.py).

A vector at current radius r [um] at time t is modelled by the velocity of the tissue there,
R0 / T u_t(X, t / T) with X + u(X, t / T) = r / R0, or by the edge velocity dR/dt when r is
inside the wound (objective.py). The exact counterpart finds X by Brent's method on the
Laplace-domain displacement and is differentiated by fourth-order central differences (step
1e-3: truncation ~1e-12, rounding ~1e-13 / 1e-3). Every column is the exact derivative of the
solver's velocities (src/solver/profile_rates.rs; ln R0 through R_inf, the moving mesh and
the current radius r / R0), which differ from the exact ones by up to 1e-7 of the largest
(lambda = 0, the far field early on: the solver's grid is chosen for the wound radius).
Measured worst, relative to the column's largest value: 6e-8 (lambda > 0) and 1.1e-7
(lambda = 0) in sigma, lambda and ln T; 7e-8 (lambda > 0) and 1.2e-7 (lambda = 0) in ln R0;
the velocities themselves 2e-9 and 8e-8."""

from __future__ import annotations

import numpy as np
import pytest
import wound_exact as we
from scipy.optimize import brentq

from wound_opening.fitting.objective import Objective, to_z
from wound_opening.inputs.series import RadiusSeries, VelocityProfile

OUTER = 87.0
TIMES = (1.0, 4.0)  # frame times [s]
RADII = (6.0, 19.0, 30.0, 55.0)  # current radii [um]; 6 um is inside the wound


def exact_rows(z):
    """R0 / T times the exact velocity of each profile row (edge velocity inside the wound)."""
    R0, sigma, lam, T = np.exp(z[0]), z[1], abs(z[2]), np.exp(z[3])
    r_inf, out = OUTER / R0, []
    for t in TIMES:
        tau = np.array([t / T])
        edge_r, edge_v = (a[0] for a in we.edge(lam, sigma, r_inf, tau))
        for r in RADII:
            x = r / R0
            if x <= edge_r:
                out.append(R0 / T * edge_v)
                continue
            gap = lambda X: X + we.profile(lam, sigma, r_inf, [X], tau)[0][0, 0] - x  # noqa: E731
            X = brentq(gap, 1.0, r_inf, xtol=1e-15, rtol=1e-15)
            out.append(R0 / T * we.profile(lam, sigma, r_inf, [X], tau)[1][0, 0])
    return np.array(out)


@pytest.mark.parametrize(
    "theta", [(10.3, 0.37, 0.3, 7.0), (9.1, 0.8, 2.0, 12.0), (11.0, 0.5, 0.0, 3.0)]
)
def test_the_piv_columns_match_differences_of_the_exact_solution(theta):
    t = np.linspace(0.5, 10, 5)
    radius = RadiusSeries(t, 10 + 0 * t, 1.0)
    pt = np.repeat(TIMES, len(RADII))
    profile = VelocityProfile(pt, np.tile(RADII, len(TIMES)), 0 * pt, 1.0)
    obj = Objective(radius, profile, OUTER)
    z = to_z(theta)
    model = obj.model(z)[obj.n_radius :]
    assert obj.inside_edge == len(TIMES)  # the 6 um rows
    value_err = np.max(np.abs(model - exact_rows(z))) / np.max(np.abs(model))
    assert value_err < 3e-7
    jac = obj.jacobian(z)[obj.n_radius :]
    for i in range(4):
        if i == 2 and theta[2] == 0.0:
            assert np.all(jac[:, i] == 0.0)  # the velocity depends on lambda^2 only
            continue
        e = np.zeros(4)
        e[i] = 1e-3 * (1 if i != 2 else theta[2])
        rows = [exact_rows(z + k * e) for k in (2, 1, -1, -2)]
        ref = (-rows[0] + 8 * rows[1] - 8 * rows[2] + rows[3]) / (12 * e[i])
        err = np.max(np.abs(jac[:, i] - ref)) / np.max(np.abs(ref))
        assert err < 3e-7, (theta, i, err)
