"""What makes fits fast leaves their answers alone, on data from the EXACT solution
(python/wound_exact.py): a fit in asinh(sigma), asinh(lambda) (local.py) reaches the optimum
a fit in (sigma, lambda) reaches; a profile panel fits only the gaps the interval walk left
(plots._gaps); the report's figure and --plot's are one drawing with the same bytes."""

from __future__ import annotations

import io

import numpy as np
import pytest
import wound_exact as we

import wound_opening as wo
from wound_opening.fitting.local import local_fit
from wound_opening.fitting.objective import Objective, to_z
from wound_opening.fitting.parameters import Constrained, specification
from wound_opening.results import plots

R0, SIGMA, LAM, T, OUTER = 8.0, 0.5, 2.5, 1.6, 100.0


@pytest.fixture(scope="module")
def series():
    t = 0.25 * np.arange(1, 121)
    clean = R0 * we.edge(LAM, SIGMA, OUTER / R0, t / T)[0]
    noisy = clean + 0.06 * np.random.default_rng(3).standard_normal(t.size)
    return wo.RadiusSeries(t, noisy, noise_um=0.06)


@pytest.mark.parametrize("fixed, value", [(None, None), (0, np.log(7.7)), (3, np.log(30.0))])
def test_a_fit_in_asinh_coordinates_reaches_the_optimum_of_the_plain_coordinates(
    series, fixed, value
):
    """Free, and held at R0 = 7.7 um or T = 30 s (where the fit runs along lambda^2 T =
    const to large lambda): the same optimum, chi^2 to 1e-9 of it, from the same start."""
    data = Objective(series, None, OUTER)
    stretched = Constrained(data, specification(None, data.coordinates))
    assert stretched.stretched == (1, 2)
    start = to_z((R0 * 1.05, 0.6, 1.5, 2.0))
    plain = local_fit(data, start, fixed, value, max_nfev=2000)
    bent = local_fit(stretched, start, fixed, value, max_nfev=2000)
    assert plain[2].status > 0 and bent[2].status > 0
    assert bent[1] == pytest.approx(plain[1], rel=1e-9, abs=1e-9)
    np.testing.assert_allclose(bent[0][[0, 1, 3]], plain[0][[0, 1, 3]], atol=1e-4)


def test_a_panel_fits_only_the_values_far_from_the_walk():
    values = np.linspace(0.0, 10.0, 11)
    known = np.array([2.1, 7.0])
    kept = plots._gaps(values, known, "linear", 10.0)
    assert list(kept) == [0, 1, 3, 4, 5, 6, 8, 9, 10]
    logs = np.geomspace(1.0, 1e4, 5)  # 1, 10, .. 1e4: 1.2e3 is near 1e3 on the log axis
    assert list(plots._gaps(logs, np.array([1.2e3]), "log", 1e4)) == [1.0, 10.0, 100.0, 1e4]


def test_the_report_and_the_plot_are_one_drawing(series, monkeypatch, tmp_path):
    result = wo.fit(series, outer_radius_um=OUTER, derived=False)
    assert result.converged, result.reasons
    drawn = []
    draw = plots._draw
    monkeypatch.setattr(plots, "_draw", lambda *a: drawn.append(1) or draw(*a))
    buf = io.BytesIO()
    plots.fit_figure(result, path=buf)
    plots.fit_figure(result, series, None, tmp_path / "fit.png")
    assert len(drawn) == 1
    assert (tmp_path / "fit.png").read_bytes() == buf.getvalue()
    fig = plots.fit_figure(result, series, None, tmp_path / "other.png", profile_points=4)
    assert len(drawn) == 2 and fig is not None


def _fake_fits(monkeypatch, module, ends):
    """Replace `module.local_fit` by a record of its calls: `ends(z0, max_nfev)` gives
    (z, cost, status) of each fit (its watching, `below` and `ends`, not imitated)."""
    from scipy.optimize import OptimizeResult

    calls = []

    def fake(obj, z0, fixed=None, value=None, loss="linear", tol=1e-12, max_nfev=200, **watch):
        z0 = np.array(z0, dtype=float)
        calls.append((z0.copy(), max_nfev))
        z, c, status = ends(z0, max_nfev)
        return np.asarray(z, float), c, OptimizeResult(status=status, message="", nfev=max_nfev)

    monkeypatch.setattr(module, "local_fit", fake)
    return calls


def test_a_fit_within_flat_of_a_finished_one_is_not_continued(monkeypatch):
    """best_of continues the lowest fit first; once it is finished, a fit less than FLAT
    above it (the same flat valley) is not continued, one further above is."""
    from wound_opening.fitting import stages

    first = {0.0: 10.0, 1.0: 10.0 + 0.5 * stages.FLAT, 2.0: 10.5}  # by the start's z[0]
    then = {0.0: (9.999, 2), 1.0: (9.9985, 2), 2.0: (10.2, 2)}

    def ends(z0, max_nfev):
        k = float(z0[0])
        if max_nfev == 200:
            return z0, first[k], 0
        c, status = then[k]
        return z0, c, status

    calls = _fake_fits(monkeypatch, stages, ends)
    best, _, _ = stages.best_of(None, [np.full(4, k) for k in (2.0, 1.0, 0.0)], "linear")
    continued = [float(z[0]) for z, n in calls if n == 400]
    assert continued == [0.0, 2.0]
    assert best[1] == pytest.approx(9.999) and best[2].status == 2


def test_a_panel_value_is_not_fitted_twice_from_the_same_start(monkeypatch):
    """profile_at retries a value that does not converge from the previous optimum and the
    estimate; where those are the start it tried (no optimum yet), it fits it once."""
    from wound_opening.fitting import intervals

    calls = _fake_fits(monkeypatch, intervals, lambda z0, n: (z0, 1.0, 0))
    out = intervals.profile_at(None, np.zeros(4), 0.0, 2, [0.1, 0.2])
    assert np.all(np.isnan(out))
    assert len(calls) == 2
