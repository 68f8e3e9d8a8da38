"""The values the physics forbids, in one place, and the status a figure or report shows.

A laser cut in a tissue under tension opens passively: after the cut the radius jumps to
R1 = R0 (1 + sigma / 6) and opens towards R_final = R0 (1 + (2 sigma / 3) R_inf^2 /
(R_inf^2 - 1)). The model's material is a shear modulus G > 0, a viscosity eta >= 0, a
friction zeta > 0 and a pre-tension; its values are forbidden where

    tension/G = sigma <= 0     no opening: the wound of a passive recoil opens (a shrinking
                               wound is active closure, or a cut time or unit wrong)
    R0, R1, R_final <= 0       a wound has a positive radius
    eta/G < 0, zeta/G <= 0, T <= 0, lambda < 0, viscous length < 0
    eta, zeta, tension (Pa) as their ratios, with G > 0

A converged fit whose estimate is forbidden is not a result: its status is red, naming the
value ("physically impossible: tension/G = -5.4 <= 0 ..."). A fit whose estimate is allowed
but one of whose 95 % intervals reaches a forbidden value is amber ("check: ..."). Otherwise
green ("converged"). A converged fit whose residuals are systematic at the warning level
(runs and Durbin-Watson tests, fitting/gof.py) is amber too, and so is one whose data a
reader doubts (Outcome.doubts: outlines that are not round, inputs/fiji.py). The fit's own
verdict (`converged`) is left as the optimiser and chi^2 judged it: the status is what the
figure and report print beside the values.
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass

from .numbers import number

#: A doubt on the data (Outcome.doubts) in the status line: its start (the warning says all).
DOUBT_CHARS = 120

#: name -> (the allowed region as text, whether a value is allowed).
RULES = {
    "tension_over_G": ("> 0 (a passive opening needs tension)", lambda v: v > 0),
    "sigma": ("> 0 (a passive opening needs tension)", lambda v: v > 0),
    "tension_pa": ("> 0 (a passive opening needs tension)", lambda v: v > 0),
    "R0_um": ("> 0", lambda v: v > 0),
    "R1_um": ("> 0", lambda v: v > 0),
    "R_final_um": ("> 0 (a final radius)", lambda v: v > 0),
    "eta_over_G_s": (">= 0", lambda v: v >= 0),
    "eta_pa_s": (">= 0", lambda v: v >= 0),
    "zeta_over_G_s_per_um2": ("> 0", lambda v: v > 0),
    "zeta_pa_s_per_um2": ("> 0", lambda v: v > 0),
    "T_s": ("> 0", lambda v: v > 0),
    "lambda": (">= 0", lambda v: v >= 0),
    "viscous_length_um": (">= 0", lambda v: v >= 0),
}
COLOURS = {"green": "#060", "amber": "#b60", "red": "#a00"}


def forbidden(name: str, value) -> str:
    """ "" if `value` of quantity `name` is allowed (or not judged), else the problem."""
    rule = RULES.get(name)
    if rule is None or value is None:
        return ""
    text, ok = rule
    return "" if ok(float(value)) else f"{name} = {number(value)}: must be {text}"


@dataclass(frozen=True)
class Status:
    """level: "green", "amber" or "red"; text: what the figure and report print."""

    level: str
    text: str
    problems: tuple = ()

    @property
    def colour(self) -> str:
        return COLOURS[self.level]


def radii(R0: float, sigma: float, outer: float) -> dict:
    """R1 and R_final of a wound of cut radius R0 in a tissue of outer radius `outer`."""
    r_inf2 = (outer / R0) ** 2
    return {
        "R1_um": R0 * (1 + sigma / 6),
        "R_final_um": R0 * (1 + 2 * sigma / 3 * r_inf2 / (r_inf2 - 1)),
    }


def judge(values, intervals=()) -> tuple[list, list]:
    """(problems of the estimates, problems of the intervals): `values` (where, name, value),
    `intervals` (where, name, lower, upper); `where` prefixes the message ("" or "wound A")."""
    bad, edge = [], []
    for where, name, v in values:
        msg = forbidden(name, v)
        if msg:
            bad.append(f"{where}: {msg}" if where else msg)
    for where, name, lo, hi in intervals:
        for e in (lo, hi):
            msg = forbidden(name, e)
            if msg:
                what = f"the 95 % interval of {name} reaches {number(e)}: allowed {RULES[name][0]}"
                edge.append(f"{where}: {what}" if where else what)
                break
    return bad, edge


def status(result) -> Status:
    """The status of a FitResult or TissueFitResult (module docstring)."""
    if not result.converged:
        return Status("red", "NOT converged: " + "; ".join(result.reasons), tuple(result.reasons))
    bad, edge = result.physics()
    if bad:
        return Status("red", "converged, but physically impossible: " + "; ".join(bad), tuple(bad))
    runs = [
        f"{r['series']}: systematic residuals ({r['runs']} runs of signs where "
        f"{r['expected']:.1f} are expected, Durbin-Watson {r['durbin_watson']:.2f}; "
        f"p = {r['p_value']:.2g})"
        for r in getattr(result, "residual_runs", ())
        if r["level"] == "warn"
    ]
    doubts = [
        textwrap.shorten(d, DOUBT_CHARS, placeholder=" ...") for d in getattr(result, "doubts", ())
    ]
    if edge or runs or doubts:
        said = edge + runs + doubts
        return Status("amber", "converged; check: " + "; ".join(said), tuple(said))
    return Status("green", "converged")
