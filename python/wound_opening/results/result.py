"""The result of `fit`: estimates, intervals, identifiability with advice, derived values."""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field

import numpy as np

from ..material import material_report
from .export import export as export_csv
from .export import tables as data_tables
from .names import NAMES
from .numbers import interval as interval_text
from .outcome import Outcome, chi2_warning, outlier_warning, verdict_fields
from .profiles import Profile, own_thresholds, threshold_line
from .status import radii


@dataclass
class ParameterReport:
    name: str
    estimate: float
    stderr: float
    profile: Profile | None
    #: The user's specification (parameters.py): {"fixed": True}, {"bounds": [min, max]},
    #: {"prior": [mean, sd]} or {}.
    constraint: dict = field(default_factory=dict)

    @property
    def ci95(self) -> tuple[float | None, float | None]:
        p = self.profile
        return (None, None) if p is None else (p.lower, p.upper)

    @property
    def identifiable(self) -> bool:
        """Its profile identifies it (Profile.identifies). A fixed parameter counts as
        identified."""
        return self.profile is not None and self.profile.identifies


def fmt(x) -> str:
    return "open" if x is None else f"{x:.4g}"


def floor_name(said: str = "") -> str:
    """The floor of a radius noise, named by how it was set (RadiusSeries.noise_floor_said:
    the readers' "half a pixel"; "" a floor given by hand)."""
    return f"the outline's floor of {said}" if said else "the floor given as noise_floor_um"


def floor_line(floor_um: float, rms_um: float, said: str = "") -> str:
    """The summary's line on a radius noise set by its floor (floor_name)."""
    return (
        f"radius noise {floor_um:.3g} um, {floor_name(said)}, above the "
        f"residuals' {rms_um:.3g} um: a thresholded outline's error drifts with the cells it "
        f"takes in, which a fit's residuals absorb (--radius-noise-um sets it)"
    )


@dataclass
class FitResult(Outcome):
    """The result of `fit` (one wound): Outcome's verdict and these."""

    theta: tuple[float, float, float, float]
    reports: dict
    correlation: np.ndarray
    outer_radius_um: float
    residual_rms_um: float
    noise: tuple[float, float]
    n_points: tuple[int, int]
    has_profile: bool
    outliers: dict = field(default_factory=dict)
    piv_at_edge: int = 0
    derived_profiles: dict = field(default_factory=dict)
    #: The data in the input's order with the model, the noise used and the flags (export.py).
    points: dict = field(default_factory=dict)
    #: The radius noise's floor [um] where it, not the residuals, set the noise (an
    #: outline's half pixel: inputs/fiji.py), else None.
    radius_floor_um: float | None = None
    #: How that floor was set (RadiusSeries.noise_floor_said).
    radius_floor_said: str = ""
    #: (objective, z, chi^2 at the optimum, loss): for profiles at more values (profile_at).
    #: (i, values of z_i) -> delta chi^2: the profile of coordinate i by constrained fits.
    refit: object = field(default=None, repr=False, compare=False)
    _profile_cache: dict = field(default_factory=dict, repr=False, compare=False)

    def physics(self) -> tuple[list, list]:
        """(forbidden estimates, intervals reaching forbidden values): status.py."""
        from .status import judge, radii

        R0, sigma, lam, T = self.theta
        values = [("", "R0_um", R0), ("", "lambda", lam), ("", "T_s", T)]
        values += [("", k, v) for k, v in radii(R0, sigma, self.outer_radius_um).items()]
        mat = {k: m for k, m in self.material.items() if k != "G_pa"}
        values += [("", k, m["estimate"]) for k, m in mat.items()]
        intervals = [("", k, *m["ci95"]) for k, m in mat.items()]
        return judge(values, intervals)

    @property
    def warnings(self) -> list:
        """The model fits, but not as well as the given noise says it should; flagged points;
        a time scale at the edge of what the sampling resolves or implausible for a recoil."""
        return (
            list(self.plausibility) + chi2_warning(self) + outlier_warning(self.outliers, self.loss)
        )

    def derived_values(self) -> dict:
        """name -> (value, (lower, upper), identified). tau, zeta/G and the viscous length have
        their own profile intervals (derived.py); tension/G is sigma; R1 and R_final count as
        identified when R0 and sigma are."""
        R0, sigma, lam, T = self.theta
        out = {}
        for name, value in (
            ("tau_s", lam**2 * T),
            ("zeta_over_G_s_per_um2", 4 * T / R0**2),
            ("viscous_length_um", lam * R0),
        ):
            p = self.derived_profiles.get(name)
            ok = p is not None and p.identifies
            out[name] = (value, (None, None) if p is None else (p.lower, p.upper), ok)
        s = self.reports["sigma"]
        out["tension_over_G"] = (sigma, s.ci95, s.identifiable)
        both = self.reports["R0_um"].identifiable and s.identifiable
        out |= {
            k: (v, (None, None), both) for k, v in radii(R0, sigma, self.outer_radius_um).items()
        }
        return out

    def derived_computed(self) -> dict:
        """name -> whether the profiles that judge it were computed (intervals=True,
        derived=True)."""
        has = {n: self.reports[n].profile is not None for n in NAMES}
        out = {
            k: k in self.derived_profiles
            for k in ("tau_s", "zeta_over_G_s_per_um2", "viscous_length_um")
        }
        return out | {
            "tension_over_G": has["sigma"],
            "R1_um": has["R0_um"] and has["sigma"],
            "R_final_um": has["R0_um"] and has["sigma"],
        }

    @property
    def derived(self) -> dict:
        """Derived values, None where not identified: tau = eta/G [s], zeta/G = 4 T / R0^2
        [s/um^2], tension/G = sigma, the viscous length lambda R0 [um], R1 and R_final [um]."""
        return {k: (v if ok else None) for k, (v, _, ok) in self.derived_values().items()}

    @property
    def derived_ci95(self) -> dict:
        return {
            k: list(ci) for k, (_, ci, _) in self.derived_values().items() if ci != (None, None)
        }

    def advice(self, name: str) -> str:
        """Why a parameter is not identified and which data would identify it ("" if it is)."""
        rep = self.reports[name]
        if rep.identifiable or rep.profile is None:
            return ""
        lo, hi = rep.ci95
        flat = f"{name}: not identified (95 % interval [{fmt(lo)}, {fmt(hi)}])"
        if rep.profile.doubt:
            return f"{flat}: {rep.profile.doubt}"
        if any(rep.profile.bounded):
            return (
                f"{flat}: the interval ends at the bound you set, not where the data exclude values"
            )
        if name == "lambda":
            where = (
                "within a few viscous lengths (lambda R0) of the edge, as early after the cut "
                "as possible"
            )
            if self.has_profile:
                return f"{flat}; measure the velocity profile {where}, with less noise"
            return f"{flat}; add a velocity profile {where}"
        if name == "T_s":
            return (
                f"{flat}; sample R(t) densely from the first frames to the plateau, and add a "
                f"velocity "
                "profile to separate lambda and T (in the viscous regime R(t) depends on lambda^2 "
                "T only)"
            )
        return f"{flat}; sample the radius right after the cut (R1) and on the plateau (R_final)"

    def profile_at(self, name: str, values) -> np.ndarray:
        """delta chi^2 of the profile of parameter `name` at `values` (in its own units), by
        constrained fits (fitting.intervals.profile_at, which `refit` holds): to draw a
        profile finely."""
        if self.refit is None:
            raise ValueError("profile_at: this result keeps no objective (a failed fit)")
        i = NAMES.index(name)
        v = np.asarray(values, dtype=float)
        key = (name, v.tobytes())
        if (
            key not in self._profile_cache
        ):  # a report and a figure of one result draw the same values
            self._profile_cache[key] = self.refit(i, np.log(v) if i in (0, 3) else v)
        return self._profile_cache[key].copy()

    def _profiles(self) -> dict:
        """Every profile computed, parameters' and derived values', by name."""
        return {n: r.profile for n, r in self.reports.items()} | dict(self.derived_profiles)

    def tables(self, stopped: bool = False) -> dict:
        """The data with the model, residuals and flags, and the fitted curve, as pandas
        DataFrames with units in the column names (export.py; `stopped`: a failed fit's
        curve where it stopped)."""
        return data_tables(self, stopped)

    def export(self, stem) -> list:
        """Write tables() as stem_radius.csv, stem_curve.csv (and the PIV ones); export.py."""
        return export_csv(self, stem)

    def to_dict(self) -> dict:
        status = verdict_fields(self) | {
            "outliers": self.outliers,
            "piv_vectors_at_edge": self.piv_at_edge,
        }
        if not self.converged:
            return status | {
                "estimate_at_stop": dict(zip(NAMES, self.theta)),
                "settings": self.settings,
            }
        params = {}
        for name, rep in self.reports.items():  # the four parameters, then any nuisance
            params[name] = {
                "estimate": rep.estimate,
                "stderr": rep.stderr if math.isfinite(rep.stderr) else None,
                "ci95": list(rep.ci95),
                "identifiable": rep.identifiable,
                "interval_computed": rep.profile is not None,
            } | rep.constraint
            if self.advice(name):
                params[name]["advice"] = self.advice(name)
        from .status import status as physical_status

        st = physical_status(self)
        return status | {
            "status": {"level": st.level, "text": st.text},
            "settings": self.settings,
            "parameters": params,
            "derived": self.derived,
            "derived_ci95": self.derived_ci95,
            "material": self.material,
            "residual_rms_um": self.residual_rms_um,
            "correlation": {
                "order": list(self.reports),
                "matrix": np.nan_to_num(self.correlation).tolist(),
            },
            "outer_radius_um": self.outer_radius_um,
            "delta_chi2_95": self.threshold,
            "delta_chi2_95_own": own_thresholds(self._profiles()),
            "noise": {
                "radius_um": self.noise[0],
                "velocity_um_s": self.noise[1] if self.has_profile else None,
                "radius_at_floor_um": self.radius_floor_um,
            },
        }

    @property
    def material(self) -> dict:
        """eta/G, zeta/G, tension/G, the viscous length and, with G given, G, eta, zeta and
        the tension, with profile intervals (material.py): name -> {estimate, ci95,
        identifiable, unit} (kept while theta, G and the profiles stay the same)."""
        key = (tuple(self.theta), self.G, id(self.derived_profiles), len(self.derived_profiles))
        cached = self._profile_cache.get("material")
        if cached is None or cached[0] != key:
            cached = self._profile_cache["material"] = (key, material_report(self))
        return copy.deepcopy(cached[1])

    def summary(self) -> str:
        if not self.converged:
            return "FIT FAILED: " + "; ".join(self.reasons)
        lines = [
            f"{'parameter':<10} {'estimate':>11} {'stderr':>10}   95 % interval (profile)   "
            f"identified"
        ]
        for name, rep in self.reports.items():  # the four parameters, then any nuisance
            lo, hi = rep.ci95
            if rep.constraint.get("fixed"):
                lines.append(f"{name:<10} {rep.estimate:>11.5g} {'':>10}   fixed")
                continue
            note = (
                "   prior {:g} +- {:g}".format(*rep.constraint["prior"])
                if "prior" in rep.constraint
                else ""
            ) + (
                "   bounds [{:g}, {:g}]".format(*rep.constraint["bounds"])
                if "bounds" in rep.constraint
                else ""
            )
            interval = (
                f"[{fmt(lo):>9}, {fmt(hi):>9}]        {'yes' if rep.identifiable else 'no'}"
                if rep.profile is not None
                else f"{'not computed':<22}{'not computed':>17}"
            )
            lines.append(f"{name:<10} {rep.estimate:>11.5g} {rep.stderr:>10.3g}   {interval}{note}")
        lines += [f"  {self.advice(n)}" for n in NAMES if self.advice(n)]
        computed = self.derived_computed()
        radii = {
            k: d for k, d in self.derived_values().items() if k in ("R1_um", "R_final_um")
        }  # the rest: material
        lines.append(
            "derived: "
            + ", ".join(
                f"{k} = {fmt(v)} (not computed)"
                if not computed[k]
                else f"{k} = {fmt(v)}"
                if ok
                else f"{k} not identified"
                for k, (v, ci, ok) in radii.items()
            )
        )
        lines += _material_lines(self.material)
        fit = f"chi^2 = {self.chi2:.4g} for {self.dof} dof" + (
            f", p = {self.p_value:.3g}"
            if self.p_value is not None
            else " (noise estimated from the residuals)"
        )
        lines.append(
            f"residual rms {self.residual_rms_um:.3g} um; {fit}; optimiser: "
            f"{self.optimizer.get('message', '')}"
        )
        if self.radius_floor_um is not None:
            lines.append(
                floor_line(self.radius_floor_um, self.residual_rms_um, self.radius_floor_said)
            )
        if self.has_profile:
            lines.append(
                f"PIV vectors at or inside the model's wound edge (compared with the edge "
                f"velocity): {self.piv_at_edge}"
            )
        own = threshold_line(self.threshold, self._profiles())
        lines += ([own] if own else []) + [f"warning: {w}" for w in self.warnings]
        from .status import status as physical_status

        st = physical_status(self)
        if st.level != "green":
            lines.append(f"status: {st.text}")
        return "\n".join(lines)


def _material_lines(material: dict) -> list:
    """The summary's material block: one value per line, with its unit and interval."""
    lines = ["material (95 % profile intervals):"]
    for name, m in material.items():
        if name == "G_pa":
            lines.append(
                f"  G_pa = {m['estimate']:.5g} Pa "
                + ("(fixed)" if m["fixed"] else f"(prior, sd {m['sd']:.3g} Pa)")
            )
            continue
        lo, hi = m["ci95"]
        interval = (
            "interval not computed"
            if not m.get("interval_computed", True)
            else interval_text(lo, hi, m["estimate"])
            + ("" if m["identifiable"] else "  not identified")
        )
        unit = "" if m["unit"] == "1" else f" {m['unit']}"
        lines.append(f"  {name} = {fmt(m['estimate'])}{unit}  {interval}")
    return lines
