"""The result of `fit`: estimates, intervals, identifiability with advice, derived values."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import numpy as np

from .objective import NAMES
from .profile import Profile


@dataclass
class ParameterReport:
    name: str
    estimate: float
    stderr: float
    profile: Profile | None

    @property
    def ci95(self) -> tuple[float | None, float | None]:
        p = self.profile
        return (None, None) if p is None else (p.lower, p.upper)

    @property
    def identifiable(self) -> bool:
        """Both interval ends set by the data (a rise of the profile by the threshold);
        lambda's interval reaching its bound 0 does not identify it (only bounds it above)."""
        p = self.profile
        return p is not None and p.lower is not None and p.upper is not None and not p.at_bound


def _fmt(x) -> str:
    return "open" if x is None else f"{x:.4g}"


@dataclass
class FitResult:
    theta: tuple[float, float, float, float]
    reports: dict
    correlation: np.ndarray
    chi2: float
    threshold: float
    outer_radius_um: float
    residual_rms_um: float
    noise: tuple[float, float]
    n_points: tuple[int, int]
    has_profile: bool
    evaluations: int

    @property
    def derived(self) -> dict:
        R0, sigma, lam, T = self.theta
        r_inf = self.outer_radius_um / R0
        return {"tau_s": lam**2 * T, "viscous_length_um": lam * R0, "R1_um": R0 * (1 + sigma / 6),
                "R_final_um": R0 * (1 + 2 * sigma / 3 * r_inf**2 / (r_inf**2 - 1))}

    def advice(self, name: str) -> str:
        """Why a parameter is not identified and which data would identify it ("" if it is)."""
        rep = self.reports[name]
        if rep.identifiable or rep.profile is None:
            return ""
        R0, _, lam, T = self.theta
        lo, hi = rep.ci95
        flat = f"{name}: profile likelihood flat over [{_fmt(lo)}, {_fmt(hi)}]"
        if name == "lambda":
            reach = 5 * max(lam if hi is None else hi, 1.0) * R0
            where = f"within {reach:.3g} um (5 lambda R0) of the edge in the first {T:.3g} s (T)"
            if self.has_profile:
                return f"{flat}; measure the velocity profile earlier and closer: {where}, with less noise"
            return f"{flat}; add a velocity profile {where}"
        if name == "T_s":
            tau = self.derived["tau_s"]
            return (f"{flat}; only tau = lambda^2 T = {tau:.3g} s may be determined (viscous regime): sample "
                    f"R(t) from {0.1 * T:.3g} s to {10 * T:.3g} s and add a velocity profile to separate lambda and T")
        return f"{flat}; sample the radius right after the cut (R1) and on the plateau (R_final)"

    def to_dict(self) -> dict:
        params = {}
        for name in NAMES:
            rep = self.reports[name]
            params[name] = {"estimate": rep.estimate, "stderr": rep.stderr if math.isfinite(rep.stderr) else None,
                            "ci95": list(rep.ci95), "identifiable": rep.identifiable}
            if self.advice(name):
                params[name]["advice"] = self.advice(name)
        return {"parameters": params, "derived": self.derived, "residual_rms_um": self.residual_rms_um,
                "correlation": {"order": list(NAMES), "matrix": np.nan_to_num(self.correlation).tolist()},
                "outer_radius_um": self.outer_radius_um, "chi2": self.chi2, "delta_chi2_95": self.threshold,
                "noise": {"radius_um": self.noise[0], "velocity_um_s": self.noise[1] if self.has_profile else None}}

    def to_json(self, **kwargs) -> str:
        return json.dumps(self.to_dict(), **({"indent": 2} | kwargs))

    def summary(self) -> str:
        lines = [f"{'parameter':<10} {'estimate':>11} {'stderr':>10}   95 % interval (profile)   identified"]
        for name in NAMES:
            rep = self.reports[name]
            lo, hi = rep.ci95
            lines.append(f"{name:<10} {rep.estimate:>11.5g} {rep.stderr:>10.3g}   "
                         f"[{_fmt(lo):>9}, {_fmt(hi):>9}]        {'yes' if rep.identifiable else 'no'}")
        lines += [f"  {self.advice(n)}" for n in NAMES if self.advice(n)]
        lines.append("derived: " + ", ".join(f"{k} = {v:.4g}" for k, v in self.derived.items()))
        lines.append(f"residual rms {self.residual_rms_um:.3g} um")
        return "\n".join(lines)
