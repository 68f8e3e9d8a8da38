"""The result of `fit_wounds`: the shared material (viscous length, tension/G, zeta/G, eta/G)
and each wound's R0 with profile intervals and identifiability (result.ParameterReport),
each wound's lambda = l / R0 and T = (zeta/G) R0^2 / 4, the verdict and chi^2."""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field

import numpy as np

from ..material import RATIOS, absolute_values
from .names import ETA, SHARED
from .numbers import ends, material_lines
from .outcome import Outcome, chi2_warning, outlier_warning, verdict_fields
from .result import ParameterReport, floor_line, fmt
from .status import judge, radii
from .status import status as physical_status

#: What would identify a shared quantity that is not.
ADVICE = {
    "viscous_length_um": "add smaller wounds (lambda = l / R0 large: the viscous regime) or a "
    "velocity profile "
    "near the edge early after the cut",
    "tension_over_G": "sample each radius right after the cut (R1) and on the plateau (R_final)",
    "zeta_over_G_s_per_um2": "add larger wounds (T = zeta R0^2 / 4G grows with R0^2: the friction "
    "regime), "
    "sampled densely from the first frames",
    "eta_over_G_s": "add smaller wounds (they open on tau = eta/G alone), sampled to their plateau",
}


@dataclass
class TissueFitResult(Outcome):
    """The result of `fit_wounds` (several wounds of one tissue): Outcome's verdict and these."""

    shared: dict  # name -> ParameterReport: SHARED and ETA
    r0: list  # ParameterReport of each wound's R0_um
    # per wound: name, theta (R0, sigma, lambda, T), outer radius, points, chi2, noise, ...
    wounds: list
    correlation: np.ndarray  # in y = (l, sigma, ln zeta/G, ln R0_1 ..., the nuisances)
    #: name -> ParameterReport of each nuisance fitted (fitting/tissue.py: the outline's
    #: offset, each wound's cut and PIV gain), with its standard error (no profile)
    nuisances: dict = field(default_factory=dict)
    _material: tuple = field(default=(None, None), repr=False, compare=False)

    @property
    def material(self) -> dict:
        """eta/G, zeta/G, tension/G, the viscous length and, with G given, G, eta, zeta and
        the tension, with their 95 % profile intervals: name -> {estimate, ci95,
        identifiable, unit, interval_computed}, as FitResult.material (kept while the
        estimates, intervals and G stay the same)."""
        key = (
            tuple((r.estimate, r.ci95) for r in self.shared.values()),
            self.G,
            self.threshold,
        )
        if self._material[0] != key:
            self._material = (key, self._compute_material())
        return copy.deepcopy(self._material[1])

    def _compute_material(self) -> dict:
        out = {}
        for name, (_, unit) in RATIOS.items():
            rep = self.shared[name]
            out[name] = {
                "estimate": rep.estimate,
                "ci95": list(rep.ci95),
                "identifiable": rep.identifiable,
                "unit": unit,
                "interval_computed": rep.profile is not None,
            }
        if self.G is None:
            return out
        profiles = {name: self.shared[name].profile for name in RATIOS}
        return out | absolute_values(out, profiles, self.G, self.threshold)

    def physics(self) -> tuple[list, list]:
        """(forbidden estimates, intervals reaching forbidden values): status.py."""
        mat = {k: m for k, m in self.material.items() if k != "G_pa"}
        values = [("", k, m["estimate"]) for k, m in mat.items()]
        intervals = [("", k, *m["ci95"]) for k, m in mat.items()]
        for w, rep in zip(self.wounds, self.r0):
            R0, sigma, lam, T = w["theta"]
            where = f"wound {w['name']}"
            values += [(where, "R0_um", R0), (where, "T_s", T)]
            values += [(where, k, v) for k, v in radii(R0, sigma, w["outer_radius_um"]).items()]
            intervals.append((where, "R0_um", *rep.ci95))
        return judge(values, intervals)

    def wound_view(self, k: int):
        """Wound k's fit as the single fit's tables and export read it (export.tables)."""
        from types import SimpleNamespace

        w = self.wounds[k]
        return SimpleNamespace(
            converged=self.converged,
            reasons=self.reasons,
            theta=w["theta"],
            points=w.get("points", {}),
            outer_radius_um=w["outer_radius_um"],
        )

    def tables(self, stopped: bool = False) -> dict:
        """wound name -> its tables (export.tables: radius, curve, profile, profile_curve;
        `stopped`: a failed fit's curves where it stopped)."""
        from .export import tables

        return {w["name"]: tables(self.wound_view(k), stopped) for k, w in enumerate(self.wounds)}

    def export(self, stem) -> list:
        """Each wound's tables as stem_<wound>_radius.csv, stem_<wound>_curve.csv (and the
        PIV ones), the wound's name made safe for a file name; returns the paths."""
        from pathlib import Path

        from .export import export

        stem = Path(stem)
        if stem.suffix.lower() == ".csv":
            stem = stem.with_suffix("")
        paths = []
        for k, name in enumerate(self.file_names()):
            paths += export(self.wound_view(k), stem.with_name(f"{stem.name}_{name}"))
        return paths

    def file_names(self) -> list:
        """Each wound's name for a file: its file's stem for a path, letters, digits, '-'
        and '_' kept, the rest '_'; its position where two would coincide."""
        import re
        from pathlib import PurePath

        out = []
        for k, n in enumerate(self.names):
            safe = re.sub(r"[^A-Za-z0-9_-]", "_", PurePath(n).stem or n) or str(k + 1)
            out.append(safe)
        if len(set(out)) < len(out):
            out = [f"{k + 1}_{n}" for k, n in enumerate(out)]
        return out

    @property
    def names(self) -> list:
        return [w["name"] for w in self.wounds]

    @property
    def warnings(self) -> list:
        out = list(self.plausibility) + chi2_warning(self)
        for w in self.wounds:
            out += [f"wound {w['name']}: {m}" for m in outlier_warning(w["outliers"], self.loss)]
        return out

    def advice(self, name: str) -> str:
        rep = self.shared[name]
        if rep.identifiable or rep.profile is None:
            return ""
        lo, hi = rep.ci95
        why = rep.profile.doubt or ADVICE[name]
        return f"{name}: not identified (95 % interval [{fmt(lo)}, {fmt(hi)}]); {why}"

    @staticmethod
    def _report(rep: ParameterReport) -> dict:
        """identifiable: null when the intervals were not computed (intervals=False)."""
        return {
            "estimate": rep.estimate,
            "stderr": rep.stderr if math.isfinite(rep.stderr) else None,
            "ci95": list(rep.ci95),
            "identifiable": rep.identifiable if rep.profile is not None else None,
        } | rep.constraint

    @staticmethod
    def _interval(rep: ParameterReport, width: int) -> str:
        """The interval and whether identified, or that it was not computed."""
        if rep.constraint.get("fixed"):
            return f"{'(fixed)':<{2 * width + 5}}  {'-':<3}"
        if rep.profile is None:
            return f"{'(not computed)':<{2 * width + 5}}  {'-':<3}"
        lo, hi = rep.ci95
        lo, hi = ends(lo, hi, rep.estimate)
        return f"[{lo:>{width}}, {hi:>{width}}]  {'yes' if rep.identifiable else 'no':<3}"

    def to_dict(self) -> dict:
        status = verdict_fields(self)
        wounds = []
        for w, rep in zip(self.wounds, self.r0):
            R0, sigma, lam, T = w["theta"]
            row = {
                "name": w["name"],
                "outer_radius_um": w["outer_radius_um"],
                "n_points": list(w["n_points"]),
            }
            if self.converged:
                row |= {
                    "R0_um": self._report(rep),
                    "lambda": lam,
                    "T_s": T,
                    "chi2": w["chi2"],
                    "residual_rms_um": w["residual_rms_um"],
                    "noise": {
                        "radius_um": w["noise"][0],
                        "velocity_um_s": w["noise"][1],
                        "radius_at_floor_um": w.get("radius_floor_um"),
                    },
                    "outliers": w["outliers"],
                    "piv_vectors_at_edge": w["piv_vectors_at_edge"],
                }
            else:
                row["estimate_at_stop"] = {"R0_um": R0, "sigma": sigma, "lambda": lam, "T_s": T}
            wounds.append(row)
        if not self.converged:
            return status | {"wounds": wounds, "settings": self.settings}
        shared = {}
        for name, rep in self.shared.items():
            shared[name] = self._report(rep)
            if self.advice(name):
                shared[name]["advice"] = self.advice(name)
        order = list(SHARED[:2]) + ["ln_" + SHARED[2]] + [f"ln_R0_um[{n}]" for n in self.names]
        order += list(self.nuisances)
        st = physical_status(self)
        return status | {
            "status": {"level": st.level, "text": st.text},
            "material": self.material,
            "settings": self.settings,
            "shared": shared,
            "wounds": wounds,
            "nuisances": {name: self._report(rep) for name, rep in self.nuisances.items()},
            "delta_chi2_95": self.threshold,
            "correlation": {"order": order, "matrix": np.nan_to_num(self.correlation).tolist()},
        }

    def summary(self) -> str:
        if not self.converged:
            return "FIT FAILED: " + "; ".join(self.reasons)
        head = "95 % interval (profile)  identified"
        n = len(self.wounds)
        lines = [
            f"{f'shared by {n} wound' + 's' * (n > 1):<22} {'estimate':>11} {'stderr':>10}   {head}"
        ]
        for name in SHARED + (ETA,):
            rep = self.shared[name]
            lines.append(
                f"{name:<22} {rep.estimate:>11.5g} {rep.stderr:>10.3g}   {self._interval(rep, 9)}"
            )
        lines += [f"  {self.advice(n)}" for n in self.shared if self.advice(n)]
        lines += ["material (95 % profile intervals):"]
        lines += [f"  {m}" for m in material_lines(self.material)]
        st = physical_status(self)
        if st.level != "green":
            lines.append(f"status: {st.text}")
        wide = max([5] + [len(n) for n in self.names])
        lines.append(
            f"{'wound':<{wide}} {'outer um':>9} {'points':>7} {'R0_um':>9} {'stderr':>9}   "
            f"{'95 % interval':<21} {'identified':<10} {'lambda':>8} {'T_s':>9} {'chi^2':>8}"
        )
        for w, rep in zip(self.wounds, self.r0):
            _, _, lam, T = w["theta"]
            lines.append(
                f"{w['name']:<{wide}} {w['outer_radius_um']:>9.4g} {sum(w['n_points']):>7} "
                f"{rep.estimate:>9.5g} "
                f"{rep.stderr:>9.3g}   {self._interval(rep, 8)}        {lam:>8.4g} {T:>9.4g} "
                f"{w['chi2']:>8.4g}"
            )
        if self.nuisances:
            lines.append("nuisances (estimate +- standard error):")
        for name, rep in self.nuisances.items():
            said = "fixed" if rep.constraint.get("fixed") else f"+- {rep.stderr:.3g}"
            prior = rep.constraint.get("prior")
            lines.append(
                f"  {name} = {rep.estimate:.5g} {said}"
                + (f"  (prior {prior[0]:g} +- {prior[1]:g})" if prior else "")
            )
        fit = f"chi^2 = {self.chi2:.4g} for {self.dof} dof" + (
            f", p = {self.p_value:.3g}"
            if self.p_value is not None
            else " (noise estimated from the residuals)"
        )
        lines.append(f"{fit}; optimiser: {self.optimizer.get('message', '')}")
        lines += [
            f"wound {w['name']}: "
            + floor_line(w["radius_floor_um"], w["residual_rms_um"], w.get("radius_floor_said", ""))
            for w in self.wounds
            if w.get("radius_floor_um") is not None
        ]
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)
