"""A fit whose outlines the reader warns are not round (inputs/fiji.py) reports its numbers
and intervals but identifies nothing: the radius of such outlines is not the edge's, and on
the rendered movies of docs/fitting.md ("Coverage on rendered movies") their fits' values
reported identified missed the truth. Each interval carries the doubt (results/profiles.py,
DOUBT); the same interval without it identifies R0 and sigma here, so the doubt, not the
data, is what withdraws the claim."""

from __future__ import annotations

import dataclasses
import json

import make_lab_examples as lab
from test_lab_readers import R0, _perimeters_scaled, fiji

from wound_opening import Parameters, Wound, fit, fit_wounds
from wound_opening.inputs.fiji import ROUND_CIRCULARITY
from wound_opening.results.profiles import DOUBT


def _would_identify(profile) -> bool:
    return dataclasses.replace(profile, doubt="").identifies


def test_outlines_that_are_not_round_identify_nothing_but_keep_their_intervals(tmp_path):
    path = tmp_path / "Results.csv"
    lab.write_fiji(path, R0)
    n = len(fiji(path).times_s)
    _perimeters_scaled(path, n // 2 + 1, ROUND_CIRCULARITY - 0.01)  # the same areas, ragged
    read = fiji(path)
    assert len(read.warnings) == 1 and "not round" in read.warnings[0]
    params = Parameters()
    params.add("G_pa", prior=(1000.0, 100.0))
    bad = fit(read, outer_radius_um=lab.OUTER_UM, params=params)
    assert bad.converged and bad.doubts == list(read.warnings)
    reps = bad.reports
    assert _would_identify(reps["R0_um"].profile) and _would_identify(reps["sigma"].profile)
    for name, rep in reps.items():
        assert rep.profile.doubt == DOUBT, name
        assert not rep.identifiable and bad.advice(name).endswith(DOUBT), name
    # eta/G's own profile (derived.py) identifies it, the doubt withdraws it with its eta
    assert _would_identify(bad.derived_profiles["tau_s"])
    for k in ("eta_over_G_s", "tension_over_G", "eta_pa_s", "tension_pa"):
        m = bad.material[k]
        assert None not in m["ci95"] and not m["identifiable"], (k, m)
    assert all(v is None for v in bad.derived.values()), bad.derived
    out = json.loads(bad.to_json())
    assert read.warnings[0] in out["warnings"]
    assert not any(m.get("identifiable") for m in out["material"].values()), out["material"]
    assert DOUBT in bad.summary()


def test_one_wound_with_outlines_not_round_withdraws_the_shared_values(tmp_path):
    """A several-wound fit shares the material values: one wound's doubted outlines bias
    them all, so neither a shared value nor any wound's R0 is reported identified."""
    wounds = []
    for R in (4.0, 8.0):
        path = tmp_path / f"Results_{R:g}.csv"
        lab.write_fiji(path, R)
        wounds.append(Wound(fiji(path), lab.OUTER_UM, name=f"R{R:g}"))
    said = "3 of 4 outlines are not round (a warning as the reader writes it)"
    ragged = dataclasses.replace(wounds[1].radius, warnings=(said,))
    bad = fit_wounds([wounds[0], dataclasses.replace(wounds[1], radius=ragged)])
    assert bad.converged and bad.doubts == [f"wound R8: {said}"]
    assert any(_would_identify(rep.profile) for rep in bad.shared.values() if rep.profile)
    assert all(_would_identify(rep.profile) for rep in bad.r0)
    for name, rep in bad.shared.items():
        assert not rep.identifiable, name
        if rep.profile is not None:
            assert rep.profile.doubt == DOUBT and bad.advice(name).endswith(DOUBT), name
    assert not any(rep.identifiable for rep in bad.r0)
    assert not any(m.get("identifiable") for m in bad.material.values()), bad.material
