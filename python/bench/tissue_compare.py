"""One draw of the three wounds of bench/tissue_designs.py (exact solution, noise given):
the 95 % profile intervals of the material each wound gives fitted alone (`fit`: its
derived viscous length, zeta/G, eta/G = tau and its sigma = tension/G) against the three
fitted together (`fit_wounds`), as a markdown table.

    cd python && nice python -m bench.tissue_compare --noise 0.04 --seed 1
"""

from __future__ import annotations

import argparse

from bench.tissue_designs import TRUTH, draw
from wound_opening.fitting.single import fit
from wound_opening.fitting.wounds import fit_wounds
from wound_opening.results.result import fmt

#: The single fit's names of the shared quantities.
ALONE = {
    "viscous_length_um": "viscous_length_um",
    "tension_over_G": "tension_over_G",
    "zeta_over_G_s_per_um2": "zeta_over_G_s_per_um2",
    "eta_over_G_s": "tau_s",
}


def cell(ci, identified: bool) -> str:
    lo, hi = ci
    return f"[{fmt(lo)}, {fmt(hi)}]" + ("" if identified else " (not identified)")


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--noise", type=float, default=0.04, help="relative to each wound's opening")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    wounds = draw(args.noise, args.seed)
    rows = {name: [] for name in TRUTH}
    for w in wounds:
        alone = fit(w.radius, w.profile, outer_radius_um=w.outer_radius_um)
        for name, key in ALONE.items():
            ci = alone.derived_ci95.get(key, (None, None))
            rows[name].append(
                cell(ci, alone.derived[key] is not None) if alone.converged else "fit failed"
            )
    together = fit_wounds(wounds)
    head = [w.name.replace("R0=", "R0 = ").replace("um", " µm") + " alone" for w in wounds]
    print("| quantity | truth | " + " | ".join(head) + " | the three together |")
    print("|---" * (3 + len(wounds)) + "|")
    for name, truth in TRUTH.items():
        rep = together.shared[name]
        print(
            f"| {name} | {truth:g} | "
            + " | ".join(rows[name])
            + f" | {cell(rep.ci95, rep.identifiable)} |"
        )


if __name__ == "__main__":
    main()
