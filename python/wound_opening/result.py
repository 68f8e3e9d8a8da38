"""The result of `fit`: estimates, intervals, identifiability with advice, derived values."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

from .objective import NAMES
from .likelihood import Profile


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
    converged: bool = True
    reasons: list = field(default_factory=list)
    optimizer: dict = field(default_factory=dict)
    dof: int = 0
    p_value: float | None = None
    noise_given: bool = False
    loss: str = "linear"
    outliers: dict = field(default_factory=dict)
    piv_at_edge: int = 0
    derived_profiles: dict = field(default_factory=dict)
    #: The fitted time scale against the sampling (plausibility.py).
    plausibility: list = field(default_factory=list)

    @property
    def warnings(self) -> list:
        """The model fits, but not as well as the given noise says it should; flagged points;
        a time scale at the edge of what the sampling resolves or implausible for a recoil."""
        out = list(self.plausibility)
        if self.converged and self.p_value is not None and self.p_value < 1e-3:
            out.append(f"chi^2 / dof = {self.chi2 / self.dof:.3g} (p = {self.p_value:.2g}): the model describes the "
                       "data worse than the given noise allows")
        n_out = len(self.outliers.get("radius", [])) + len(self.outliers.get("profile", []))
        if n_out:
            out.append(f"{n_out} points down-weighted by the {self.loss} loss (|residual| > 3 noise): "
                       + "; ".join(self.outliers.get("where", [])))
        return out

    def _derived_all(self) -> dict:
        """name -> (value, (lower, upper), identified). tau, zeta/G and the viscous length have
        their own profile intervals (derived.py); tension/G is sigma; R1 and R_final count as
        identified when R0 and sigma are."""
        R0, sigma, lam, T = self.theta
        r_inf = self.outer_radius_um / R0
        out = {}
        for name, value in (("tau_s", lam**2 * T), ("zeta_over_G_s_per_um2", 4 * T / R0**2),
                            ("viscous_length_um", lam * R0)):
            p = self.derived_profiles.get(name)
            ok = p is not None and p.lower is not None and p.upper is not None and not p.at_bound
            out[name] = (value, (None, None) if p is None else (p.lower, p.upper), ok)
        s = self.reports["sigma"]
        out["tension_over_G"] = (sigma, s.ci95, s.identifiable)
        both = self.reports["R0_um"].identifiable and s.identifiable
        out["R1_um"] = (R0 * (1 + sigma / 6), (None, None), both)
        out["R_final_um"] = (R0 * (1 + 2 * sigma / 3 * r_inf**2 / (r_inf**2 - 1)), (None, None), both)
        return out

    @property
    def derived(self) -> dict:
        """Derived values, None where not identified: tau = eta/G [s], zeta/G = 4 T / R0^2
        [s/um^2], tension/G = sigma, the viscous length lambda R0 [um], R1 and R_final [um]."""
        return {k: (v if ok else None) for k, (v, _, ok) in self._derived_all().items()}

    @property
    def derived_ci95(self) -> dict:
        return {k: list(ci) for k, (_, ci, _) in self._derived_all().items() if ci != (None, None)}

    def advice(self, name: str) -> str:
        """Why a parameter is not identified and which data would identify it ("" if it is)."""
        rep = self.reports[name]
        if rep.identifiable or rep.profile is None:
            return ""
        lo, hi = rep.ci95
        flat = f"{name}: not identified (95 % interval [{_fmt(lo)}, {_fmt(hi)}])"
        if name == "lambda":
            where = "within a few viscous lengths (lambda R0) of the edge, as early after the cut as possible"
            if self.has_profile:
                return f"{flat}; measure the velocity profile {where}, with less noise"
            return f"{flat}; add a velocity profile {where}"
        if name == "T_s":
            return (f"{flat}; sample R(t) densely from the first frames to the plateau, and add a velocity "
                    "profile to separate lambda and T (in the viscous regime R(t) depends on lambda^2 T only)")
        return f"{flat}; sample the radius right after the cut (R1) and on the plateau (R_final)"

    def to_dict(self) -> dict:
        status = {"converged": self.converged, "reasons": self.reasons, "warnings": self.warnings,
                  "optimizer": self.optimizer, "chi2": self.chi2, "dof": self.dof, "p_value": self.p_value,
                  "noise_given": self.noise_given, "loss": self.loss, "outliers": self.outliers,
                  "piv_vectors_at_edge": self.piv_at_edge}
        if not self.converged:
            return status | {"estimate_at_stop": dict(zip(NAMES, self.theta))}
        params = {}
        for name in NAMES:
            rep = self.reports[name]
            params[name] = {"estimate": rep.estimate, "stderr": rep.stderr if math.isfinite(rep.stderr) else None,
                            "ci95": list(rep.ci95), "identifiable": rep.identifiable}
            if self.advice(name):
                params[name]["advice"] = self.advice(name)
        return status | {"parameters": params, "derived": self.derived, "derived_ci95": self.derived_ci95, "residual_rms_um": self.residual_rms_um,
                "correlation": {"order": list(NAMES), "matrix": np.nan_to_num(self.correlation).tolist()},
                "outer_radius_um": self.outer_radius_um, "delta_chi2_95": self.threshold,
                "noise": {"radius_um": self.noise[0], "velocity_um_s": self.noise[1] if self.has_profile else None}}

    def to_json(self, **kwargs) -> str:
        return json.dumps(self.to_dict(), **({"indent": 2} | kwargs))

    def summary(self) -> str:
        if not self.converged:
            return "FIT FAILED: " + "; ".join(self.reasons)
        lines = [f"{'parameter':<10} {'estimate':>11} {'stderr':>10}   95 % interval (profile)   identified"]
        for name in NAMES:
            rep = self.reports[name]
            lo, hi = rep.ci95
            lines.append(f"{name:<10} {rep.estimate:>11.5g} {rep.stderr:>10.3g}   "
                         f"[{_fmt(lo):>9}, {_fmt(hi):>9}]        {'yes' if rep.identifiable else 'no'}")
        lines += [f"  {self.advice(n)}" for n in NAMES if self.advice(n)]
        lines.append("derived: " + ", ".join(
            f"{k} = {_fmt(v)} [{_fmt(ci[0])}, {_fmt(ci[1])}]" if ok and ci != (None, None) else
            f"{k} = {_fmt(v)}" if ok else f"{k} not identified" for k, (v, ci, ok) in self._derived_all().items()))
        fit = f"chi^2 = {self.chi2:.4g} for {self.dof} dof" + (f", p = {self.p_value:.3g}" if self.p_value is not None else
                                                               " (noise estimated from the residuals)")
        lines.append(f"residual rms {self.residual_rms_um:.3g} um; {fit}; optimiser: {self.optimizer.get('message', '')}")
        if self.has_profile:
            lines.append(f"PIV vectors at or inside the model's wound edge (compared with the edge velocity): {self.piv_at_edge}")
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)
