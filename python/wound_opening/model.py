"""`simulate`: the model in the units of an experiment (um, s, Pa).

Scales (docs/model.md, "Physical units"): lengths in R0 [um], time in T = zeta R0^2 / (4 G) [s],
stresses in G [Pa]; lambda = 2 sqrt(eta / zeta) / R0 and sigma = tension / G are
dimensionless, R_inf = outer radius / R0. The wound radius just after the cut is
R1 = R0 (1 + sigma / 6), not R0, and the wound opens towards
R_final = R0 (1 + (2 sigma / 3) R_inf^2 / (R_inf^2 - 1)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _native
from .material import model_parameters


@dataclass(frozen=True)
class Simulation:
    """Outputs at the requested times (in the order given) and radii."""

    times_s: np.ndarray
    radius_um: np.ndarray
    edge_velocity_um_s: np.ndarray
    radii_um: np.ndarray | None = None
    #: u of the material point at each current radius, shape (len(times), len(radii)).
    displacement_um: np.ndarray | None = None
    #: Its velocity (what PIV measures at that radius), same shape.
    velocity_um_s: np.ndarray | None = None

    def to_frame(self):
        """Long table: one row per time (and radius, if any)."""
        import pandas as pd

        if self.radii_um is None:
            return pd.DataFrame(
                {
                    "time_s": self.times_s,
                    "radius_um": self.radius_um,
                    "edge_velocity_um_s": self.edge_velocity_um_s,
                }
            )
        nt, nr = self.displacement_um.shape
        return pd.DataFrame(
            {
                "time_s": np.repeat(self.times_s, nr),
                "r_um": np.tile(self.radii_um, nt),
                "radius_um": np.repeat(self.radius_um, nr),
                "edge_velocity_um_s": np.repeat(self.edge_velocity_um_s, nr),
                "displacement_um": self.displacement_um.ravel(),
                "velocity_um_s": self.velocity_um_s.ravel(),
            }
        )


def _positive(name: str, value: float) -> float:
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} = {value} is invalid: expected a finite value > 0")
    return value


def scales(R0_um: float, T_s: float, outer_radius_um: float) -> float:
    """Check the scales; return R_inf = outer_radius_um / R0_um."""
    R0_um, _ = _positive("R0_um", R0_um), _positive("T_s", T_s)
    r_inf = _positive("outer_radius_um", outer_radius_um) / R0_um
    if not r_inf > 1:
        raise ValueError(
            f"outer_radius_um = {outer_radius_um} is invalid: expected > R0_um = {R0_um}"
        )
    return r_inf


def edge_stress_ratio(edge_stress_pa: float | None, G_pa: float | None) -> float:
    """The edge stress in G (0 when none is given)."""
    if edge_stress_pa is None:
        return 0.0
    if G_pa is None:
        raise ValueError(
            "edge_stress_pa needs G_pa (the shear modulus) to be converted to the model's units"
        )
    return float(edge_stress_pa) / _positive("G_pa", G_pa)


def _sorted_times(times_s, T_s: float):
    t = np.atleast_1d(np.asarray(times_s, dtype=float))
    if t.ndim != 1 or not np.all(np.isfinite(t)) or np.any(t < 0):
        raise ValueError(
            "times_s must be a 1-D sequence of finite times >= 0 (seconds since the cut)"
        )
    order = np.argsort(t, kind="stable")
    return t, order, t[order] / T_s


def edge_series(
    lam: float,
    sigma: float,
    r_inf: float,
    tau,
    p: float = 0.0,
    *,
    tolerance: float = _native.TOLERANCE,
):
    """R and dR/dt (dimensionless) at ascending dimensionless times `tau`, on the grid that
    meets `tolerance` (relative to the opening R_final - R1). At lambda = 0 the velocity at
    t = 0 is infinite in the model (unless p = sigma): returned as +-inf."""
    tau = np.asarray(tau, dtype=float)
    if lam == 0 and p != sigma and tau.size and tau[0] == 0:
        r, _ = _native.series(lam, sigma, r_inf, tau, p, velocity=False, tolerance=tolerance)
        v = np.full(tau.size, math.copysign(math.inf, sigma - p))
        later = tau > 0
        if later.any():
            v[later] = _native.series(lam, sigma, r_inf, tau[later], p, tolerance=tolerance)[1]
        return r, v
    return _native.series(lam, sigma, r_inf, tau, p, tolerance=tolerance)


def simulate(
    times_s,
    *,
    R0_um: float,
    outer_radius_um: float,
    lam: float | None = None,
    sigma: float | None = None,
    T_s: float | None = None,
    G_pa: float | None = None,
    eta_pa_s: float | None = None,
    zeta_pa_s_per_um2: float | None = None,
    tension_pa: float | None = None,
    edge_stress_pa: float | None = None,
    radii_um=None,
    tolerance: float = _native.TOLERANCE,
) -> Simulation:
    """Wound radius [um] and edge velocity [um/s] at `times_s` [s since the cut, any order],
    and, if `radii_um` is given, displacement [um] and velocity [um/s] of the tissue at those
    CURRENT distances from the wound centre (as PIV measures them).

    Either the dimensionless set: lam, sigma (lambda = viscous length / R0, sigma =
    tension / G) and T_s (the time scale zeta R0^2 / (4 G)); or the material set: G_pa,
    eta_pa_s, zeta_pa_s_per_um2 (friction, Pa s/um^2) and tension_pa, converted by
    material.from_material. A mix, or an incomplete set, is refused.
    R0_um: radius of the cut (the wound is R1 = R0 (1 + sigma/6) just after it).
    outer_radius_um: the tissue's outer radius (> R0).
    edge_stress_pa with G_pa: a constant stress at the wound edge (default none).
    tolerance: the accuracy target of the wound radius and edge velocity, relative to the
    opening R_final - R1 (the grid is the cheapest that meets it; 1e-11 is the finest
    delivered). The field at `radii_um` is less accurate (wider elements inside the tissue):
    its contract is "The field contract" in section "Interfaces: FMI 2.0 and 3.0,
    co-simulation or Model Exchange" of docs/fmi.md.
    At lambda = 0 the edge velocity at t = 0 is infinite in the model and returned as inf.
    Raises ValueError for invalid input (a radius inside the wound or beyond the tissue at
    some time, with the tissue's span then) and NativeLibraryMissing without the library.
    """
    lam, sigma, T_s = model_parameters(
        dict(
            lam=lam,
            sigma=sigma,
            T_s=T_s,
            G_pa=G_pa,
            eta_pa_s=eta_pa_s,
            zeta_pa_s_per_um2=zeta_pa_s_per_um2,
            tension_pa=tension_pa,
            R0_um=R0_um,
        )
    ).values()
    r_inf = scales(R0_um, T_s, outer_radius_um)
    p = edge_stress_ratio(edge_stress_pa, G_pa)
    t, order, tau = _sorted_times(times_s, T_s)
    back = np.empty_like(order)
    back[order] = np.arange(order.size)
    try:
        radius, velocity = edge_series(lam, sigma, r_inf, tau, p, tolerance=tolerance)
        if radii_um is None:
            return Simulation(t, R0_um * radius[back], R0_um / T_s * velocity[back])
        radii = np.atleast_1d(np.asarray(radii_um, dtype=float))
        u, v = _native.profile_series(lam, sigma, r_inf, tau, radii / R0_um, p, tolerance=tolerance)
    except _native.SolverError as e:
        raise ValueError(
            f"{e} (in the model's units: lengths in R0 = {R0_um} um, times in T = {T_s} s)"
        ) from None
    return Simulation(
        t,
        R0_um * radius[back],
        R0_um / T_s * velocity[back],
        radii,
        R0_um * u[back],
        R0_um / T_s * v[back],
    )


def opening_fraction(
    lam: float, r_inf: float, tau, *, tolerance: float = _native.TOLERANCE
) -> np.ndarray:
    """f = (R - R1) / (R_final - R1) at ascending dimensionless times tau (free edge). With
    no edge stress R - R1 is proportional to sigma, so f depends on lambda and R_inf only:

        f(tau) = (R(tau; sigma = 1) - 7/6) / (2/3 R_inf^2 / (R_inf^2 - 1) - 1/6)."""
    r, _ = _native.series(
        lam, 1.0, r_inf, np.asarray(tau, dtype=float), velocity=False, tolerance=tolerance
    )
    return (r - 7 / 6) / (2 / 3 * r_inf**2 / (r_inf**2 - 1) - 1 / 6)


def half_opening_time(lam: float, r_inf: float, *, tolerance: float = _native.TOLERANCE) -> float:
    """The time (in T) at which the free wound has opened half way from R1 to R_final,
    f(t_half) = 1/2, whatever sigma (opening_fraction). Bracketed on a log grid of 1e-6 ..
    1e8 T (10 points per decade), then Brent's method on ln t to 1e-12; the radius at
    t_half is then half way to within `tolerance` of the opening."""
    from scipy.optimize import brentq

    grid = np.geomspace(1e-6, 1e8, 141)
    f = opening_fraction(lam, r_inf, grid, tolerance=tolerance)
    above = np.flatnonzero(f >= 0.5)
    if above.size == 0 or above[0] == 0:
        raise ValueError(
            f"half_opening_time: lambda = {lam}, R_inf = {r_inf}: no crossing of half the opening "
            "between 1e-6 and 1e8 T"
        )
    k = above[0]
    return math.exp(
        brentq(
            lambda s: opening_fraction(lam, r_inf, [math.exp(s)], tolerance=tolerance)[0] - 0.5,
            math.log(grid[k - 1]),
            math.log(grid[k]),
            xtol=1e-12,
            rtol=1e-12,
        )
    )
