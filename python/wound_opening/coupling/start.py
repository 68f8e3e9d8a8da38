"""The WoundOpening FMU's start values, by the names of its modelDescription.xml, from
material constants or from a fit.

    lambda = 2 sqrt(eta / zeta) / R0,  sigma = tension / G,  R_inf = outer radius / R0,
    R0 [um],  T = zeta R0^2 / (4 G) [s],  G [Pa]

With these, `fmpy.simulate_fmu(wound_opening.fmu_path("WoundOpening.fmu"),
start_values=fmu_start_values(...))` gives the wound radius [um] and edge velocity [um/s]
in the experiment's units, the same curve as `wound_opening.simulate` (to the FMU's stated
accuracy, 1e-10 of the opening R_final - R1). G matters only for the input `edge_stress`
[Pa] (the model sees edge_stress / G): R(t) without an edge stress does not depend on it.
"""

from __future__ import annotations

import math

from ..material import checked_value, from_material


def _fmu_values(R0_um, sigma, lam, T_s, outer_radius_um, G_pa) -> dict:
    R0 = checked_value("R0_um", R0_um)
    outer = checked_value("outer_radius_um", outer_radius_um)
    if not outer > R0:
        raise ValueError(
            f"outer_radius_um = {outer} must exceed R0_um = {R0} (the FMU accepts R_inf = "
            f"outer / R0 in [1.001, 1e6])"
        )
    out = {
        "lambda": checked_value("lambda", lam, zero=True),
        "sigma": checked_value("sigma", sigma, positive=False),
        "R_inf": outer / R0,
        "R0": R0,
        "T": checked_value("T_s", T_s),
    }
    if G_pa is not None:
        out["G"] = checked_value("G_pa", G_pa)
    return out


def _from_fit(result, wound, outer_radius_um, G_pa) -> dict:
    """(R0, sigma, lambda, T), outer radius and G of a FitResult or of one wound of a
    TissueFitResult (by its name or its index)."""
    wounds = getattr(result, "wounds", None)
    if wounds is not None:  # TissueFitResult: one wound's (R0, sigma, lambda, T)
        names = [w["name"] for w in wounds]
        if wound is None:
            if len(wounds) != 1:
                raise ValueError(
                    f"the fit has {len(wounds)} wounds ({', '.join(names)}): choose one with "
                    f"wound= (its name or its index 0..{len(wounds) - 1})"
                )
            wound = 0
        if isinstance(wound, int) and not isinstance(wound, bool):
            if not 0 <= wound < len(wounds):
                raise ValueError(f"wound = {wound}: the indices are 0..{len(wounds) - 1}")
            row = wounds[wound]
        elif str(wound) in names:
            row = wounds[names.index(str(wound))]
        else:
            raise ValueError(f"no wound named {wound!r}; the wounds are {', '.join(names)}")
        theta, outer, G = row["theta"], row["outer_radius_um"], None
    elif hasattr(result, "theta") and hasattr(result, "outer_radius_um"):
        if wound is not None:
            raise ValueError("wound= is for a fit of several wounds (fit_wounds)")
        theta, outer = result.theta, result.outer_radius_um
        G = None if result.G is None else result.G[0]
    else:
        raise TypeError(f"expected a FitResult or a TissueFitResult, got {type(result).__name__}")
    R0, sigma, lam, T = theta
    outer = outer if outer_radius_um is None else outer_radius_um
    return _fmu_values(R0, sigma, lam, T, outer, G if G_pa is None else G_pa)


def fmu_start_values(
    result=None,
    *,
    wound=None,
    G_pa: float | None = None,
    eta_pa_s: float | None = None,
    zeta_pa_s_per_um2: float | None = None,
    tension_pa: float | None = None,
    R0_um: float | None = None,
    outer_radius_um: float | None = None,
) -> dict:
    """The WoundOpening FMU's start values {lambda, sigma, R_inf, R0, T[, G]} by name.

    From material constants: fmu_start_values(G_pa=, eta_pa_s=, zeta_pa_s_per_um2=,
    tension_pa=, R0_um=, outer_radius_um=) (Pa, Pa s, Pa s/um^2, Pa, um, um).

    From a fit: fmu_start_values(result), a FitResult (its estimates; G the fit's G if one
    was given, else omitted: the FMU's default G = 1 Pa, so edge_stress is then in units of
    G) or a TissueFitResult with wound= the name or index of one wound (its R0, lambda = l /
    R0, T = (zeta/G) R0^2 / 4, and the shared sigma). G_pa= and outer_radius_um= override
    the fit's.

    ValueError for a value the FMU would refuse (not finite, R0 or T not > 0, lambda < 0,
    an outer radius not beyond R0) or a mix of the two ways.
    """
    if result is not None:
        given = [
            k
            for k, v in (
                ("eta_pa_s", eta_pa_s),
                ("zeta_pa_s_per_um2", zeta_pa_s_per_um2),
                ("tension_pa", tension_pa),
                ("R0_um", R0_um),
            )
            if v is not None
        ]
        if given:
            raise ValueError(
                f"give a fit result or material constants, not both: got {', '.join(given)}"
            )
        return _from_fit(result, wound, outer_radius_um, G_pa)
    missing = [
        k
        for k, v in (
            ("G_pa", G_pa),
            ("eta_pa_s", eta_pa_s),
            ("zeta_pa_s_per_um2", zeta_pa_s_per_um2),
            ("tension_pa", tension_pa),
            ("R0_um", R0_um),
            ("outer_radius_um", outer_radius_um),
        )
        if v is None
    ]
    if missing:
        raise ValueError(
            f"fmu_start_values needs a fit result, or all material constants: missing "
            f"{', '.join(missing)}"
        )
    if wound is not None:
        raise ValueError("wound= is for a fit of several wounds (fit_wounds)")
    p = from_material(
        G_pa=G_pa,
        eta_pa_s=eta_pa_s,
        zeta_pa_s_per_um2=zeta_pa_s_per_um2,
        tension_pa=tension_pa,
        R0_um=R0_um,
    )
    if not math.isfinite(p["T_s"]) or not p["T_s"] > 0:
        raise ValueError(f"T = zeta R0^2 / (4 G) = {p['T_s']} is not a positive number")
    return _fmu_values(p["R0_um"], p["sigma"], p["lam"], p["T_s"], outer_radius_um, G_pa)
