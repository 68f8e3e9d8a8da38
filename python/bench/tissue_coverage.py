"""Coverage of `fit_wounds`' 95 % profile-likelihood intervals on three wounds of one tissue
(bench/tissue_designs.py: R0 = 5, 10, 20 um, exact solution, noise given), per noise level:
how often each shared quantity and each R0 is reported identifiable, and how often its
interval then contains the truth; beside it the same for the wound of R0 = 10 um fitted
alone (`fit`: its derived viscous length, zeta/G, eta/G and its sigma). Writes a CSV (one
row per draw) and a markdown table.

    cd python && nice python -m bench.tissue_coverage --draws 30 --out ../out/tissue_coverage
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from bench.fit_designs import covers
from bench.tissue_designs import OUTERS, R0S, TRUTH, clean, draw
from wound_opening.fitting.single import fit
from wound_opening.fitting.wounds import fit_wounds

NOISES = (1e-3, 1e-2, 4e-2)
#: The single wound's names of the shared quantities.
ALONE = {
    "viscous_length_um": "viscous_length_um",
    "tension_over_G": "tension_over_G",
    "zeta_over_G_s_per_um2": "zeta_over_G_s_per_um2",
    "eta_over_G_s": "tau_s",
}
ALONE_K = R0S.index(10.0)


def one_draw(noise: float, seed: int, curves) -> dict:
    """(identified, covered) per quantity for the three wounds and for the 10 um wound alone."""
    wounds = draw(noise, seed, curves=curves)
    row = {}
    start = time.process_time()
    result = fit_wounds(wounds)
    row["seconds"] = round(time.process_time() - start, 1)
    row["failed"] = int(not result.converged)
    if result.converged:
        for name, truth in TRUTH.items():
            rep = result.shared[name]
            row[name] = (int(rep.identifiable), int(rep.identifiable and covers(rep.ci95, truth)))
        for k, (R0, rep) in enumerate(zip(R0S, result.r0)):
            row[f"R0_{k}"] = (int(rep.identifiable), int(rep.identifiable and covers(rep.ci95, R0)))
    w = wounds[ALONE_K]
    alone = fit(w.radius, w.profile, outer_radius_um=w.outer_radius_um)
    row["alone_failed"] = int(not alone.converged)
    if alone.converged:
        values, cis = alone.derived, alone.derived_ci95
        for name, key in ALONE.items():
            ok = values.get(key) is not None and key in cis
            row[f"alone_{name}"] = (int(ok), int(ok and covers(cis[key], TRUTH[name])))
    return row


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--draws", type=int, default=30)
    ap.add_argument("--noises", default=",".join(map(str, NOISES)))
    ap.add_argument("--out", default="out/tissue_coverage")
    ap.add_argument(
        "--table-only", action="store_true", help="write the table from OUT.csv (a run so far)"
    )
    args = ap.parse_args()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    keys = list(TRUTH) + [f"R0_{k}" for k in range(len(R0S))] + [f"alone_{n}" for n in TRUTH]
    if args.table_only:
        return table(read(out, keys), keys, args.draws, out)
    curves = [clean(r, o) for r, o in zip(R0S, OUTERS)]
    rows = []
    with open(f"{out}.csv", "w") as f:
        f.write(
            "noise,seed,failed,alone_failed,seconds,"
            + ",".join(f"{k}_identified,{k}_covered" for k in keys)
            + "\n"
        )
        for level, noise in enumerate(map(float, args.noises.split(","))):
            for draw_no in range(args.draws):
                seed = (
                    5000 + 1000 * level + draw_no
                )  # other noise vectors at each level: independent samples
                row = one_draw(noise, seed, curves)
                rows.append((noise, row))
                cells = [row.get(k, ("", "")) for k in keys]
                f.write(
                    f"{noise},{seed},{row['failed']},{row['alone_failed']},{row['seconds']},"
                    + ",".join(f"{i},{c}" for i, c in cells)
                    + "\n"
                )
                f.flush()
    table(rows, keys, args.draws, out)


def read(out: Path, keys) -> list:
    """The rows of OUT.csv as `main` holds them: (noise, {key: (identified, covered), ...})."""
    import csv

    rows = []
    with open(f"{out}.csv") as f:
        for r in csv.DictReader(f):
            row = {"failed": int(r["failed"]), "alone_failed": int(r["alone_failed"])}
            row |= {
                k: (int(r[f"{k}_identified"]), int(r[f"{k}_covered"]))
                for k in keys
                if r[f"{k}_identified"] != ""
            }
            rows.append((float(r["noise"]), row))
    return rows


def table(rows, keys, draws, out: Path) -> None:
    """Per noise: covered / identified (identified / draws) per quantity, three wounds and alone."""
    names = list(TRUTH)
    head = (
        "| noise | fits | "
        + " | ".join(f"{n}: 3 wounds" for n in names)
        + " | R0 (3 wounds, pooled) | "
        + " | ".join(f"{n}: 10 µm alone" for n in names)
        + " |"
    )
    lines = [head, "|---" * (3 + 2 * len(names)) + "|"]
    for noise in sorted({n for n, _ in rows}):
        sel = [r for n, r in rows if n == noise]
        failed = sum(r["failed"] for r in sel)

        def cell(ks):
            ident = sum(r[k][0] for r in sel for k in ks if k in r)
            cov = sum(r[k][1] for r in sel for k in ks if k in r)
            total = len(sel) * len(ks)
            return f"{cov / ident:.2f} ({ident}/{total})" if ident else f"– (0/{total})"

        cells = [cell([n]) for n in names] + [cell([f"R0_{k}" for k in range(len(R0S))])]
        cells += [cell([f"alone_{n}"]) for n in names]
        lines.append(
            f"| {noise:g} | {len(sel) - failed}/{len(sel)} converged | " + " | ".join(cells) + " |"
        )
    Path(f"{out}.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
