"""One vocabulary for one wound and several: every form of what the user knows (Parameters,
an lmfit-style dict, a list of Parameter objects, None) is read, or refused with the same
reason, by `fit` and by `fit_wounds`, since both read it against the coordinates their
problem declares (fitting/parameters.py, fitting/parameters.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import wound_exact as we

import wound_opening as wo
from wound_opening.fitting.objective import wound_coordinates
from wound_opening.fitting.parameters import Parameter, Parameters, specification
from wound_opening.fitting.wounds import Wound, fit_wounds, tissue_coordinates

OUTER = 100.0
#: The same knowledge named in each fit: sigma is tension/G in both.
ONE, SEVERAL = "sigma", "tension_over_G"


def _series(r0: float, seed: int) -> wo.RadiusSeries:
    t = np.linspace(0.5, 60, 30)
    lam, T = 20.0 / r0, 0.1 * r0**2 / 4
    r = r0 * we.edge(lam, 0.5, OUTER / r0, t / T)[0]
    return wo.RadiusSeries(t, r + 0.02 * np.random.default_rng(seed).standard_normal(t.size))


class Lmfit:
    """The attributes of an lmfit.Parameter."""

    def __init__(self, name, value=None, vary=True, min=-math.inf, max=math.inf, expr=None):
        self.name, self.value, self.vary, self.min, self.max, self.expr = (
            name,
            value,
            vary,
            min,
            max,
            expr,
        )


def _forms(name: str) -> dict:
    """Each form of the user's knowledge, about `name` (the pre-stress) and G."""
    p = Parameters()
    p.add(name, min=0.1, max=2.0, prior=(0.5, 0.2))
    p.add("G_pa", value=1000.0, vary=False)
    return {
        "Parameters": p,
        "dict of Parameter": {name: Parameter(name, min=0.1, max=2.0, prior=(0.5, 0.2))},
        "list of Parameter": [Parameter("G_pa", 1000.0, vary=False), Parameter(name, min=0.1)],
        "lmfit-style dict": {name: Lmfit(name, min=0.1, max=2.0)},
        "none": None,
    }


@pytest.mark.parametrize("form", list(_forms(ONE)))
def test_each_form_is_read_alike_for_one_wound_and_several(form):
    one = specification(_forms(ONE)[form], wound_coordinates(OUTER))
    several = specification(_forms(SEVERAL)[form], tissue_coordinates(["A", "B"], [OUTER] * 2))
    # sigma is coordinate 1 of both problems
    assert (one.fixed, one.bounds, one.priors, one.G) == (
        several.fixed,
        several.bounds,
        several.priors,
        several.G,
    )
    if form in ("Parameters", "list of Parameter"):
        assert one.G == (1000.0, 0.0)


def _bad(name: str) -> list:
    """(Parameters-like, the reason both fits must give)."""
    return [
        ({name: Parameter(name, prior=(0.5, 0.1, 5))}, r"prior = \(0.5, 0.1, 5\): expected"),
        ({"G_pa": Parameter("G_pa", prior=(1000, 100, 5))}, r"expected \(mean, sd\)"),
        ([Parameter(name, min=2.0, max=1.0)], "min = 2 is not below max = 1"),
        ({name: Lmfit(name, expr="2 * x")}, "expressions"),
        ({name: Parameter(name, min=math.nan)}, "a bound is NaN"),
        ({name: Parameter(name, prior=(0.5, 0.0))}, "sd = 0"),
        ({name: Parameter(name, value=0.5, vary=False, prior=(0.5, 0.1))}, "takes no bounds"),
        ({name: Parameter(name, value=math.inf, vary=False)}, "must be finite"),
        ([Parameter("G_pa", min=1.0)], "bounds are not supported"),
        ([Parameter("G_pa", value=-5.0, vary=False)], "must be > 0"),
        ([Parameter("G_pa")], "give a fixed value"),
    ]


@pytest.mark.parametrize("k", range(len(_bad(ONE))))
def test_each_refusal_is_the_same_for_one_wound_and_several(k):
    (one, reason), (several, reason_too) = _bad(ONE)[k], _bad(SEVERAL)[k]
    assert reason == reason_too
    with pytest.raises(ValueError, match=reason) as single:
        wo.fit(_series(10.0, 1), outer_radius_um=OUTER, params=one, intervals=False)
    wounds = [Wound(_series(r, s), OUTER, name=n) for r, s, n in ((5.0, 2, "A"), (10.0, 3, "B"))]
    with pytest.raises(ValueError, match=reason) as tissue:
        fit_wounds(wounds, params=several, intervals=False)
    assert str(single.value).replace(ONE, "NAME") == str(tissue.value).replace(SEVERAL, "NAME")


@pytest.mark.parametrize(
    "name, coordinates",
    [
        ("R0_um", wound_coordinates(OUTER)),
        ("R0_um[B]", tissue_coordinates(["A", "B"], [80.0, OUTER])),
        ("R0_um[2]", tissue_coordinates(["A", "B"], [80.0, OUTER])),
    ],
)
def test_a_cut_radius_beyond_its_tissue_is_refused_alike(name, coordinates):
    """R0 held outside (0, outer / 1.001): the same range and note for a wound alone and for
    wound B of several, by its name or its number."""
    with pytest.raises(ValueError) as e:
        specification({name: Parameter(name, 150.0, vary=False)}, coordinates)
    assert str(e.value) == (
        f"{name} = 150: outside the accepted range (0, 99.9001) um "
        "(R0 below the outer radius / 1.001)"
    )
