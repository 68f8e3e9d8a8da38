"""Several wounds fit their nuisances (fitting/tissue.py): each wound's cut between two
frames, one outline offset shared by their outlines, each field's gain, against the EXACT
solution (python/wound_exact.py)."""

from __future__ import annotations

import json

import numpy as np
import pytest
import wound_exact as we

import wound_opening as wo
from wound_opening.fitting.tissue import Tissue, TissueNuisances

# One tissue: zeta/G 0.08 s/um^2, eta/G 2 s, tension/G 1; wounds of 4 and 10 um.
ZG, ETA, SIGMA, OUTER = 0.08, 2.0, 1.0, 100.0
L = 2 * np.sqrt(ETA / ZG)
WOUNDS = {"A": (4.0, 0.35), "B": (10.0, 0.1)}  # R0 [um], the laser's time after frame N [s]
OFFSET, FRAME = 0.12, 0.5


def _wound(name: str, noise: float, seed: int) -> wo.Wound:
    """Frames every FRAME s counted from frame N, the wound cut `cut` after it, its outline
    OFFSET outside the edge."""
    r0, cut = WOUNDS[name]
    t = FRAME * np.arange(1, 61)
    lam, T = L / r0, ZG * r0**2 / 4
    r = r0 * we.edge(lam, SIGMA, OUTER / r0, (t - cut) / T)[0] + OFFSET
    r = r + noise * np.random.default_rng(seed).standard_normal(t.size)
    return wo.Wound(wo.RadiusSeries(t, r, noise_um=noise or 1e-4), OUTER, name=name)


def _params() -> wo.Parameters:
    p = wo.Parameters()
    for name in WOUNDS:
        p.add(f"cut_s[{name}]", min=0.0, max=FRAME)
    p.add("outline_offset_um", prior=(0.0, 0.2))
    return p


def test_a_nuisance_column_of_the_tissue_is_its_derivative():
    """d residuals / d y of each nuisance against central differences; a nuisance of one
    wound leaves the other's rows alone."""
    wounds = [_wound(n, 0.0, 1) for n in WOUNDS]
    nuisances = TissueNuisances(True, ("A", "B"))
    parts = [
        wo.fitting.objective.Objective(w.radius, None, OUTER, nuisances.of(w.name)) for w in wounds
    ]
    tissue = Tissue(parts, list(WOUNDS), nuisances)
    assert tissue.coordinates.names[-3:] == ("outline_offset_um", "cut_s[A]", "cut_s[B]")
    y = np.array([L, SIGMA, np.log(ZG), np.log(4.0), np.log(10.0), 0.05, 0.2, 0.3])
    jac = tissue.jacobian(y)
    for i in (5, 6, 7):
        e = np.zeros(y.size)
        e[i] = 1e-6
        diff = (tissue.residuals(y + e) - tissue.residuals(y - e)) / 2e-6
        np.testing.assert_allclose(jac[:, i], diff, rtol=0, atol=1e-5 * np.max(np.abs(diff)))
    n_a = parts[0].size
    assert not np.any(jac[n_a:, 6]) and not np.any(jac[:n_a, 7])


def test_each_cut_and_the_shared_offset_are_recovered_with_the_material():
    """Exact radii: each cut, the offset and the material to 1e-4 of the truth; at noise 0.05
    um every shared value and R0 is covered by its 95 % interval, the nuisances reported with
    standard errors in the summary and the JSON."""
    exact = wo.fit_wounds([_wound(n, 0.0, 1) for n in WOUNDS], params=_params(), intervals=False)
    assert exact.converged, exact.reasons
    for name, (r0, cut) in WOUNDS.items():
        assert exact.nuisances[f"cut_s[{name}]"].estimate == pytest.approx(cut, abs=1e-4)
    assert exact.nuisances["outline_offset_um"].estimate == pytest.approx(OFFSET, abs=1e-4)
    truth = {"viscous_length_um": L, "tension_over_G": SIGMA, "zeta_over_G_s_per_um2": ZG}
    for name, value in truth.items():
        assert exact.shared[name].estimate == pytest.approx(value, rel=1e-4), name

    noisy = [_wound(n, 0.05, k + 7) for k, n in enumerate(WOUNDS)]
    got = wo.fit_wounds(noisy, params=_params())
    assert got.converged, got.reasons
    for name, value in {**truth, "eta_over_G_s": ETA}.items():
        lo, hi = got.shared[name].ci95
        assert (lo is None or lo <= value) and (hi is None or value <= hi), (name, lo, hi)
    for rep, (r0, _) in zip(got.r0, WOUNDS.values()):
        assert rep.ci95[0] <= r0 <= rep.ci95[1], (rep.ci95, r0)
    assert "cut_s[A] = " in got.summary() and "outline_offset_um = " in got.summary()
    doc = json.loads(got.to_json())
    assert set(doc["nuisances"]) == {"outline_offset_um", "cut_s[A]", "cut_s[B]"}
    assert doc["correlation"]["order"][-1] == "cut_s[B]"


def test_a_one_wound_name_is_refused_naming_each_wounds_own():
    """cut_s alone means no wound's cut in a fit of several: refused, naming cut_s[NAME]."""
    p = wo.Parameters()
    p.add("cut_s", min=0.0, max=FRAME)
    with pytest.raises(ValueError, match=r"each wound has its own: cut_s\[NAME\]"):
        wo.fit_wounds([_wound(n, 0.0, 1) for n in WOUNDS], params=p, intervals=False)
