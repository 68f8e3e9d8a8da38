"""A profile's crossing stands only if no constrained fit beyond it, from starts on the other
branch (fitting/valleys.py), falls back under the threshold: exact-solution data of the
viscous regime (lambda = 10, T = 10 s, eta/G = 1000 s) recorded 0.2-50 s, 100 frames, while
the opening is 5 % done (noise 5 % of the opening)."""

from __future__ import annotations

import math

import numpy as np
import wound_exact as we

from wound_opening.fitting.intervals import Walk, walk_side
from wound_opening.fitting.local import local_fit
from wound_opening.fitting.objective import Objective, to_z
from wound_opening.inputs.series import RadiusSeries

R0, SIGMA, OUTER = 10.0, 0.5, 100.0


def viscous_short_recording(noise: float, seed: int) -> Objective:
    t = np.linspace(0.2, 50.0, 100)
    exact = R0 * we.edge(10.0, SIGMA, OUTER / R0, t / 10.0)[0]
    sd = noise * R0 * (we.final_radius(SIGMA, OUTER / R0) - we.initial_radius(SIGMA))
    radius = exact + sd * np.random.default_rng(seed).standard_normal(t.size)
    return Objective(RadiusSeries(t, radius, sd), None, OUTER)


def test_a_crossing_with_a_valley_beyond_it_does_not_stand():
    """From the small-lambda optimum (lambda = 0.15, T = 37 s) the profile of R0 walked down
    meets a barrier (delta chi^2 = 6.7 at R0 = 3.5 um on that branch), but a fit there started
    along the invariant curves reaches delta chi^2 = 3.05 < 3.84: R0 = 3.5 um lies inside the
    confidence set, and the end must not be placed above it (without the check: 3.93 um)."""
    obj = viscous_short_recording(5e-2, 8)
    z, chi2, _ = local_fit(obj, to_z((10.8, 0.5, 0.02, 8e4)))
    assert z[2] < 0.5, z  # the small-lambda branch
    J = obj.jacobian(z)
    cov = np.linalg.inv(J.T @ J)
    walk = Walk(obj, 0, chi2, 3.84, math.sqrt(cov[0, 0]), cov[:, 0] / cov[0, 0], "linear")
    end, _, points = walk_side(walk, z, -1, z[0] - math.log(3.0))
    inside = [v for v, d in points if d < 3.84]
    assert end is None or end <= min(inside), (end, points)
    assert min(inside) < math.log(3.6), points


def test_a_crossing_of_t_on_the_small_lambda_branch_is_tested_on_the_viscous_one():
    """T walked down from lambda = 0.1, T = 8e4 s (tau = 800 s) and crossing at 1188 s: the
    starts include T = 8 s with lambda = 10 (tau kept), beyond the crossing and beyond the
    walk's limit (x100: 801 s), where a valley leaves the lower end open."""
    from wound_opening.fitting.valleys import starts

    obj = viscous_short_recording(1e-2, 0)
    z_in = to_z((10.8, 0.4, 0.1, 8e4))
    got = starts(obj, 3, z_in, math.log(1188.0), -1)
    viscous = [(u, w) for u, w in got if w[2] == 10.0 and abs(math.exp(u) - 8.0) < 1e-6]
    assert viscous and np.allclose(viscous[0][1][[0, 1]], z_in[[0, 1]]), got
    along_tau = [w for u, w in got if u == math.log(1188.0)]
    assert any(abs(w[2] ** 2 * 1188.0 - 800.0) < 1e-6 for w in along_tau), got


def test_a_regime_lambdas_own_interval_excludes_is_not_searched():
    """With lambda's interval [0.05, 0.5] walked (valleys.py), the starts carried to the
    viscous point (lambda = 10) and the friction point (lambda = 0) lie where no point is
    under the threshold and are left out; the starts moved along tau within the branch stay.
    An interval reaching 0 keeps the friction point, an open upper end the viscous one."""
    from wound_opening.fitting.valleys import starts

    obj = viscous_short_recording(1e-2, 0)
    z_in, v = to_z((10.8, 0.4, 0.1, 8e4)), math.log(1188.0)
    every = starts(obj, 3, z_in, v, -1)
    lambdas = {float(w[2]) for _, w in every}
    assert 10.0 in lambdas and 0.0 in lambdas, every
    kept = starts(obj, 3, z_in, v, -1, lambda_range=(0.05, 0.5))
    assert [w.tolist() for _, w in kept] == [
        w.tolist() for _, w in every if w[2] not in (0.0, 10.0)
    ], (kept, every)
    assert any(abs(w[2] ** 2 * 1188.0 - 800.0) < 1e-6 for _, w in kept), kept  # tau kept
    both_open = {float(w[2]) for _, w in starts(obj, 3, z_in, v, -1, lambda_range=(0.0, None))}
    assert 10.0 in both_open and 0.0 in both_open


def test_a_watched_fit_stops_where_its_question_is_answered():
    """local_fit's watching (what valleys.beyond and the walks' second fits use): a fit stops
    at its first point under `below`, and where it comes within NEAR of a point of `ends`,
    returning that point; one whose watch never triggers is the plain fit, bit for bit."""
    from wound_opening.fitting.local import NEAR

    obj = viscous_short_recording(5e-2, 8)
    start = to_z((10.8, 0.5, 0.02, 8e4))
    z, chi2, res = local_fit(obj, start, fixed=0, value=math.log(10.0), tol=1e-7)
    assert res.status > 0 and res.nfev > 5, res
    first = obj.residuals(np.r_[math.log(10.0), start[1:]])
    below = chi2 + 0.5 * (float(first @ first) - chi2)  # passed on the way down
    w, c, stopped = local_fit(obj, start, fixed=0, value=math.log(10.0), tol=1e-7, below=below)
    assert stopped.status == -2 and c < below and stopped.nfev < res.nfev, stopped
    assert c == float(np.sum(obj.residuals(w) ** 2)) and w[0] == math.log(10.0)
    w, c, arrived = local_fit(obj, start, fixed=0, value=math.log(10.0), tol=1e-7, ends=[z])
    assert arrived.status == -2 and arrived.nfev < res.nfev and np.array_equal(w, z), arrived
    assert c == chi2
    far = z + 10 * NEAR
    w, c, same = local_fit(
        obj, start, fixed=0, value=math.log(10.0), tol=1e-7, below=chi2 - 1.0, ends=[far]
    )
    assert np.array_equal(w, z) and c == chi2 and same.nfev == res.nfev
