"""A fit whose outlines the reader warns are not round (inputs/fiji.py) reports its numbers
and intervals but identifies nothing: the radius of such outlines is not the edge's, and on
the rendered movies of docs/fitting.md ("Coverage on rendered movies") their fits' values
reported identified missed the truth. The same table with round outlines identifies R0
and sigma, so the doubt, not the data, is what takes the identification away."""

from __future__ import annotations

import dataclasses
import json
import math

import make_lab_examples as lab
import pytest
from test_lab_readers import R0, _perimeters_scaled, fiji

from wound_opening import Parameters, Wound, fit, fit_wounds
from wound_opening.inputs.fiji import ROUND_CIRCULARITY
from wound_opening.results.profiles import DOUBT

MATERIAL = ("eta_over_G_s", "tension_over_G", "eta_pa_s", "tension_pa")


def test_outlines_that_are_not_round_identify_nothing_but_keep_their_intervals(tmp_path):
    path = tmp_path / "Results.csv"
    lab.write_fiji(path, R0)
    params = Parameters()
    params.add("G_pa", prior=(1000.0, 100.0))
    good = fit(fiji(path), outer_radius_um=lab.OUTER_UM, params=params)
    n = len(fiji(path).times_s)
    _perimeters_scaled(path, n // 2 + 1, ROUND_CIRCULARITY - 0.01)  # same areas, ragged
    read = fiji(path)
    assert len(read.warnings) == 1 and "not round" in read.warnings[0]
    bad = fit(read, outer_radius_um=lab.OUTER_UM, params=params)
    assert good.reports["R0_um"].identifiable and good.reports["sigma"].identifiable
    assert all(good.material[k]["identifiable"] for k in MATERIAL), good.material
    assert bad.converged and bad.doubts == list(read.warnings)
    for name, rep in bad.reports.items():
        # the same data, so the same interval; only the claim is withdrawn
        assert rep.ci95 == good.reports[name].ci95, name
        assert not rep.identifiable and bad.advice(name).endswith(DOUBT), name
    for k in MATERIAL:
        assert bad.material[k]["ci95"] == good.material[k]["ci95"], k
        assert not bad.material[k]["identifiable"], k
    assert all(v is None for v in bad.derived.values()), bad.derived
    out = json.loads(bad.to_json())
    assert read.warnings[0] in out["warnings"]
    assert not any(m.get("identifiable") for m in out["material"].values()), out["material"]
    summary = bad.summary()
    assert "identified" in summary and DOUBT in summary, summary


def test_one_wound_with_outlines_not_round_withdraws_the_shared_values(tmp_path):
    """A several-wound fit shares the material values: one wound's doubted outlines bias
    them all, so neither a shared value nor any wound's R0 is reported identified."""
    wounds = []
    for R in (4.0, 8.0):
        path = tmp_path / f"Results_{R:g}.csv"
        lab.write_fiji(path, R)
        wounds.append(Wound(fiji(path), lab.OUTER_UM, name=f"R{R:g}"))
    good = fit_wounds(wounds)
    said = "3 of 4 outlines are not round (a warning as the reader writes it)"
    ragged = dataclasses.replace(wounds[1].radius, warnings=(said,))
    bad = fit_wounds([wounds[0], dataclasses.replace(wounds[1], radius=ragged)])
    assert good.converged and bad.converged
    assert any(rep.identifiable for rep in good.shared.values()), good.shared
    assert all(rep.identifiable for rep in good.r0)
    assert bad.doubts == [f"wound R8: {said}"]
    for name, rep in bad.shared.items():
        assert rep.ci95 == good.shared[name].ci95 and not rep.identifiable, name
        if rep.profile is not None:
            assert bad.advice(name).endswith(DOUBT), name
    assert not any(rep.identifiable for rep in bad.r0)
    assert not any(m.get("identifiable") for m in bad.material.values()), bad.material
    assert math.isfinite(bad.chi2) and bad.chi2 == pytest.approx(good.chi2, rel=1e-12)
