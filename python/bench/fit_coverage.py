"""Coverage of `fit`'s 95 % profile-likelihood intervals over noise x lambda x design
(bench/fit_designs.py): for each cell, the fraction of draws whose interval contains the
truth, among draws that report the parameter identifiable, and how often it is reported
identifiable. Writes a CSV, a markdown table and a figure.

    nice python python/bench/fit_coverage.py --draws 200 --out out/fit_coverage
"""

from __future__ import annotations

import argparse
import itertools
import time
from pathlib import Path

from bench.fit_designs import NAMES, clean, covers, draw, truth
from wound_opening.fitting.single import fit

NOISES = (1e-6, 1e-4, 1e-3, 1e-2, 4e-2)
LAMBDAS = (0.0, 0.05, 0.5, 5.0, 50.0)
DESIGNS = ("radius", "piv", "plateau", "early")
CELLS = list(itertools.product(LAMBDAS, NOISES, DESIGNS))


def cell(design, lam, noise, draws):
    data = clean(design, lam)
    true = truth(lam)
    ident = {n: 0 for n in NAMES}
    cover = {n: 0 for n in NAMES}
    failed = 0
    for k in range(draws):
        radius, profile = draw(design, lam, noise, 1000 + k, data)
        result = fit(radius, profile, outer_radius_um=100.0, derived=False)
        if not result.converged:
            failed += 1
            print(
                f"{design} lambda {lam:g} noise {noise:g} draw {k}: "
                f"not converged: {result.reasons}",
                flush=True,
            )
            continue
        for n in NAMES:
            rep = result.reports[n]
            if rep.identifiable:
                ident[n] += 1
                cover[n] += covers(rep.ci95, true[n])
    return failed, ident, cover


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--draws", type=int, default=200)
    ap.add_argument("--out", default="out/fit_coverage")
    ap.add_argument(
        "--skip", type=int, default=0, help="leave out the first SKIP cells (to resume a run)"
    )
    ap.add_argument(
        "--count",
        type=int,
        default=None,
        help="run COUNT cells after the skipped ones (default: all)",
    )
    ap.add_argument(
        "--designs", default=",".join(DESIGNS), help="only these designs (comma-separated)"
    )
    args = ap.parse_args()
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    rows = []
    with open(f"{out}.csv", "w") as f:
        f.write(
            "design,lambda,noise,draws,failed,"
            + ",".join(f"{n}_identified,{n}_covered" for n in NAMES)
            + ",seconds\n"
        )
        for lam, noise, design in [
            c for c in CELLS[args.skip :][: args.count] if c[2] in args.designs.split(",")
        ]:
            start = time.process_time()
            failed, ident, cover = cell(design, lam, noise, args.draws)
            row = [design, lam, noise, args.draws, failed]
            for n in NAMES:
                row += [ident[n], cover[n]]
            row.append(round(time.process_time() - start, 1))
            rows.append(row)
            f.write(",".join(map(str, row)) + "\n")
            f.flush()
    table(rows, out)


def table(rows, out: Path) -> None:
    """Markdown: per cell, coverage among identified draws (identified / draws) per parameter."""
    lines = [
        "| design | lambda | noise | failed | " + " | ".join(NAMES) + " |",
        "|---" * (4 + len(NAMES)) + "|",
    ]
    for design, lam, noise, draws, failed, *rest in rows:
        cells = []
        for k in range(len(NAMES)):
            ident, cov = rest[2 * k], rest[2 * k + 1]
            cells.append(f"{cov / ident:.2f} ({ident}/{draws})" if ident else f"– (0/{draws})")
        lines.append(f"| {design} | {lam:g} | {noise:g} | {failed} | " + " | ".join(cells) + " |")
    Path(f"{out}.md").write_text("\n".join(lines) + "\n")
    figure(rows, out)


def figure(rows, out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colours = ("#E69F00", "#56B4E9", "#009E73", "#0072B2", "#D55E00")
    fig, axes = plt.subplots(1, 4, figsize=(14, 3.6), sharey=True)
    for ax, design in zip(axes, ("radius", "piv", "plateau", "early")):
        for c, lam in zip(colours, LAMBDAS):
            sel = [r for r in rows if r[0] == design and r[1] == lam]
            for k, marker in zip(range(len(NAMES)), "osD^"):
                pts = [(r[2], r[6 + 2 * k] / r[5 + 2 * k]) for r in sel if r[5 + 2 * k]]
                if pts:
                    x, y = zip(*pts)
                    ax.semilogx(
                        x,
                        y,
                        marker=marker,
                        color=c,
                        ls="-",
                        lw=0.8,
                        ms=4,
                        label=f"λ = {lam:g}" if k == 0 else None,
                    )
        ax.axhspan(0.90, 0.99, color="0.9")
        ax.set_title(design)
        ax.set_xlabel("noise / opening")
    axes[0].set_ylabel("coverage of identified parameters")
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out}.png", dpi=110)


if __name__ == "__main__":
    main()
