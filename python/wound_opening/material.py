"""Material constants and the model's parameters, both ways, and the absolute material
values of a fit with G known.

Units: G, tension [Pa], eta [Pa s], zeta [Pa s / um^2], R0 [um], T [s].

    lambda = 2 sqrt(eta / zeta) / R0     (viscous length l = lambda R0 = 2 sqrt(eta / zeta))
    sigma  = tension / G
    T      = zeta R0^2 / (4 G)
    tau    = eta / G = lambda^2 T

and back: eta = lambda^2 T G, zeta = 4 T G / R0^2, tension = sigma G. R(t) and every
velocity depend on (R0, sigma, lambda, T) only: multiplying G, eta, zeta and the tension by
one factor changes nothing, so a fit determines the ratios eta/G = tau, zeta/G = 4 T / R0^2
and tension/G = sigma, and the absolute values need G from elsewhere (AFM, say).

Absolute values with G known (`absolute`). G is fixed (then eta = tau G and the interval is
G times tau's), or has a Gaussian prior G = mu +- sd. The data do not depend on G, so the
joint chi^2 of (theta, G) is chi^2_data(theta) + ((G - mu) / sd)^2, and the profile of
eta = tau(theta) G factorises:

    delta_eta(e) = min over theta, G with tau(theta) G = e of [chi^2 - chi^2_min]
                 = min over G > 0 of [ min over theta with tau(theta) = e / G of (chi^2_data
                     - chi^2_min)
                                       + ((G - mu) / sd)^2 ]
                 = min over G > 0 of [ delta_tau(e / G) + ((G - mu) / sd)^2 ]

(the minimum of the sum, delta = 0, is at e = tau_hat mu). delta_tau is the profile the fit
walked (derived.py); no new fit is needed. The signed root sign(tau - tau_hat) sqrt(delta_tau)
is smooth and close to linear in ln tau through the estimate, and is interpolated between
the walked points and the estimate (root 0) by a cubic spline in ln tau (not-a-knot),
continued along its end slope beyond them. The walk puts most points near the interval
ends, few between them and the estimate: straight lines between the points there
underestimate delta by up to 10 % where the minimum over G falls;
`tests/python/test_parameters.py` checks the spline's interval ends against a brute-force
profile over (theta, G). The same
holds for zeta = (zeta/G) G and tension = sigma G (sigma interpolated linearly in sigma).
The 95 % interval is {e : delta_eta(e) < threshold}, the fit's threshold; an end where the
ratio's interval is open is open; with mu - sqrt(threshold) sd <= 0 the prior allows G near
0 and the lower end of a positive quantity is 0.
"""

from __future__ import annotations

import math

import numpy as np

#: The reported material values: name -> (the fit's derived value it is, unit).
RATIOS = {
    "eta_over_G_s": ("tau_s", "s"),
    "zeta_over_G_s_per_um2": ("zeta_over_G_s_per_um2", "s/um^2"),
    "tension_over_G": ("tension_over_G", "1"),
    "viscous_length_um": ("viscous_length_um", "um"),
}
#: With G: absolute name -> (the ratio it is G times, unit).
ABSOLUTE = {
    "eta_pa_s": ("eta_over_G_s", "Pa s"),
    "zeta_pa_s_per_um2": ("zeta_over_G_s_per_um2", "Pa s/um^2"),
    "tension_pa": ("tension_over_G", "Pa"),
}
#: The names `simulate` takes in each set.
DIMENSIONLESS = ("lam", "sigma", "T_s")
MATERIAL = ("G_pa", "eta_pa_s", "zeta_pa_s_per_um2", "tension_pa")


def checked_value(name: str, x, positive: bool = True, zero: bool = False) -> float:
    try:
        x = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {x!r} is not a number") from None
    ok = math.isfinite(x) and (not positive or x > 0 or (zero and x == 0))
    if not ok:
        raise ValueError(
            f"{name} = {x} is invalid: expected a finite value"
            + (" >= 0" if zero else " > 0" if positive else "")
        )
    return x


def from_material(
    *, G_pa: float, eta_pa_s: float, zeta_pa_s_per_um2: float, tension_pa: float, R0_um: float
) -> dict:
    """The model's parameters {lam, sigma, T_s, R0_um} (simulate's keywords) from material
    constants: lambda = 2 sqrt(eta / zeta) / R0, sigma = tension / G, T = zeta R0^2 / (4 G)."""
    G = checked_value("G_pa", G_pa)
    eta = checked_value("eta_pa_s", eta_pa_s, zero=True)
    zeta = checked_value("zeta_pa_s_per_um2", zeta_pa_s_per_um2)
    tension = checked_value("tension_pa", tension_pa, positive=False)
    R0 = checked_value("R0_um", R0_um)
    return {
        "lam": 2.0 * math.sqrt(eta / zeta) / R0,
        "sigma": tension / G,
        "T_s": zeta * R0 * R0 / (4.0 * G),
        "R0_um": R0,
    }


def to_material(*, lam: float, sigma: float, T_s: float, R0_um: float, G_pa: float) -> dict:
    """Material constants {G_pa, eta_pa_s, zeta_pa_s_per_um2, tension_pa, R0_um} from the
    model's parameters and G: eta = lambda^2 T G, zeta = 4 T G / R0^2, tension = sigma G."""
    G, T, R0 = checked_value("G_pa", G_pa), checked_value("T_s", T_s), checked_value("R0_um", R0_um)
    lam, sigma = checked_value("lam", lam, zero=True), checked_value("sigma", sigma, positive=False)
    return {
        "G_pa": G,
        "eta_pa_s": lam * lam * T * G,
        "zeta_pa_s_per_um2": 4.0 * T * G / (R0 * R0),
        "tension_pa": sigma * G,
        "R0_um": R0,
    }


def model_parameters(given: dict) -> dict:
    """{lam, sigma, T_s} from either set of `simulate`'s keywords (None = not given): the
    dimensionless (lam, sigma, T_s) or the material (G_pa, eta_pa_s, zeta_pa_s_per_um2,
    tension_pa, with R0_um). ValueError when the sets are mixed or one is incomplete."""
    dim = [k for k in DIMENSIONLESS if given.get(k) is not None]
    mat = [k for k in MATERIAL[1:] if given.get(k) is not None]
    if dim and mat:
        raise ValueError(
            f"give either the dimensionless parameters ({', '.join(DIMENSIONLESS)}) or the "
            f"material "
            f"constants ({', '.join(MATERIAL)}), not both: got {', '.join(dim + mat)}"
        )
    if mat:
        missing = [k for k in MATERIAL if given.get(k) is None]
        if missing:
            raise ValueError(
                f"the material constants need {', '.join(missing)} too "
                f"(all of {', '.join(MATERIAL)}, with R0_um)"
            )
        p = from_material(**{k: given[k] for k in MATERIAL}, R0_um=given["R0_um"])
        return {k: p[k] for k in DIMENSIONLESS}
    missing = [k for k in DIMENSIONLESS if given.get(k) is None]
    if missing:
        raise ValueError(
            f"missing {', '.join(missing)}: give lam, sigma and T_s, or the material constants "
            f"{', '.join(MATERIAL)}"
        )
    return {k: float(given[k]) for k in DIMENSIONLESS}


#: delta chi^2 beyond a bound the user set on the ratio: excluded (finite, for the root finder).
WALL = 1e12


def _delta_function(estimate: float, points, log: bool, bounded=(False, False)):
    """delta(v) from the walked profile points: the signed root sign(v - estimate) sqrt(delta)
    by a cubic spline (not-a-knot) through the points and the estimate (root 0), in ln v when
    `log`; beyond the outermost points, continued along the spline's end slope, or WALL on a
    side that ends at a user's bound (`bounded`: lower, upper)."""
    from scipy.interpolate import CubicSpline

    def u_of(v):
        return math.log(v / estimate) if log else v - estimate

    nodes = {}
    for v, d in list(points) + [(estimate, 0.0)]:
        if log and not v > 0:
            continue
        u = u_of(v)
        nodes[round(u, 12)] = math.copysign(math.sqrt(max(d, 0.0)), u)
    x = np.array(sorted(nodes))
    s = np.array([nodes[k] for k in x])
    if x.size < 2:
        return lambda v: 0.0 if v == estimate else math.inf
    spline = CubicSpline(x, s) if x.size >= 3 else None

    def root(u: float) -> float:
        if x[0] <= u <= x[-1]:
            return float(spline(u)) if spline is not None else float(np.interp(u, x, s))
        end = 0 if u < x[0] else -1
        if bounded[end]:
            return math.sqrt(WALL)
        slope = float(spline(x[end], 1)) if spline is not None else (s[1] - s[0]) / (x[1] - x[0])
        return float(s[end] + max(slope, 0.0) * (u - x[end]))

    def delta(v: float) -> float:
        if log and not v > 0:
            return math.inf
        return root(u_of(v)) ** 2

    return delta


def absolute_interval(
    estimate: float,
    lower,
    upper,
    points,
    G: tuple[float, float],
    threshold: float,
    log: bool = True,
    bounded=(False, False),
) -> tuple:
    """(value, lower, upper) of ratio x G: see the module docstring. `lower`, `upper`: the
    ratio's interval (None = open); `points`: its profile (value, delta chi^2); `G` = (mu, sd),
    sd = 0 for a fixed G. An end is None where open."""
    from scipy import optimize

    mu, sd = G
    value = estimate * mu
    if sd == 0:
        ends = [None if e is None else e * mu for e in (lower, upper)]
        return value, *ends
    delta_q = _delta_function(estimate, points, log, bounded)
    root = math.sqrt(threshold)
    g_lo, g_hi = max(mu - root * sd, 0.0), mu + root * sd

    def delta(e: float) -> float:
        """min over G of delta_q(e / G) + ((G - mu) / sd)^2, over the G the prior allows."""
        grid = np.linspace(max(g_lo, 1e-12 * mu), g_hi, 401)
        vals = [delta_q(e / g) + ((g - mu) / sd) ** 2 for g in grid]
        k = int(np.argmin(vals))
        a, b = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
        best = optimize.minimize_scalar(
            lambda g: delta_q(e / g) + ((g - mu) / sd) ** 2,
            bounds=(a, b),
            method="bounded",
            options={"xatol": 1e-10 * mu},
        )
        return min(float(best.fun), vals[k])

    out = []
    for side, end in ((-1, lower), (1, upper)):
        if end is None:
            out.append(None)
            continue
        if side < 0 and g_lo == 0.0 and estimate > 0:
            out.append(0.0)  # G -> 0 is inside the prior's interval: eta, zeta, tension -> 0 too
            continue
        # beyond every product of the ratio's end and a G the prior allows: delta > threshold there
        far = side * max(side * end * g for g in (g_lo, g_hi))
        far += side * 1e-3 * max(abs(far), abs(value))
        if not delta(far) > threshold:
            out.append(None)
            continue
        out.append(
            optimize.brentq(
                lambda e: delta(e) - threshold, *sorted((value, far)), xtol=1e-12 * abs(value)
            )
        )
    return value, out[0], out[1]


def material_report(result) -> dict:
    """The material values of a fit: eta/G, zeta/G, tension/G and the viscous length with
    their profile intervals, and with G given (fixed or a prior) G, eta, zeta and the
    tension with theirs. name -> {estimate, ci95, identifiable, unit, interval_computed}."""
    derived, computed = result.derived_values(), result.derived_computed()
    out = {}
    for name, (ratio, unit) in RATIOS.items():
        v, ci, ok = derived[ratio]
        out[name] = {
            "estimate": v,
            "ci95": list(ci),
            "identifiable": bool(ok),
            "unit": unit,
            "interval_computed": computed[ratio],
        }
    if result.G is None:
        return out
    profiles = dict(result.derived_profiles) | {"tension_over_G": result.reports["sigma"].profile}
    return out | absolute_values(
        out, {r: profiles.get(RATIOS[r][0]) for r in RATIOS}, result.G, result.threshold
    )


def absolute_values(ratios: dict, profiles: dict, G: tuple, threshold: float) -> dict:
    """G and the absolute eta, zeta and tension of a fit's material ratios (`ratios`: name
    -> {estimate, interval_computed}; `profiles`: ratio -> its Profile or None), one wound's
    or several's: each the ratio times G, its interval by absolute_interval over the ratio's
    profile and G's prior (a ratio held fixed: G's sqrt(threshold) sd band)."""
    mu, sd = G
    out = {"G_pa": {"estimate": mu, "sd": sd, "fixed": sd == 0, "unit": "Pa"}}
    for name, (ratio, unit) in ABSOLUTE.items():
        q = ratios[ratio]["estimate"]
        profile = profiles.get(ratio)
        lo = hi = None
        if profile is not None and not profile.at_bound:
            if profile.lower is not None and profile.lower == profile.upper:  # held fixed
                k = math.sqrt(threshold) * sd
                lo, hi = sorted((q * (mu - k), q * (mu + k)))
            else:
                _, lo, hi = absolute_interval(
                    q,
                    profile.lower,
                    profile.upper,
                    profile.points,
                    G,
                    threshold,
                    log=ratio != "tension_over_G",
                    bounded=profile.bounded,
                )
        out[name] = {
            "estimate": q * mu,
            "ci95": [lo, hi],
            "identifiable": lo is not None and hi is not None and not getattr(profile, "doubt", ""),
            "unit": unit,
            "interval_computed": ratios[ratio]["interval_computed"],
        }
    return out
