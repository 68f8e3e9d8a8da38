"""Writes examples/data/tissue_*.csv (R5um, R10um, R20um, and tissue_long.csv): three wounds
of one tissue (R0 = 5, 10, 20 um; outer radii 80, 100, 120 um) from the EXACT solution
(wound_exact.py) of the material of bench/tissue_designs.py (viscous length 20 um,
tension/G 0.5, zeta/G 0.1 s/um^2, so eta/G = 10 s), 40 radii each over 0.5 .. 60 s with
Gaussian noise of 2 % of each wound's opening (seed 2026), for the README's quick start.
The long table has the same rows with a column `wound` naming each wound.

    python python/example_wounds.py [--out examples/data]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pandas as pd
from bench.tissue_designs import OUTERS, R0S, draw

NOISE, SEED = 0.02, 2026


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--out", default=str(Path(__file__).resolve().parents[1] / "examples" / "data"))
    out = Path(ap.parse_args().out)
    out.mkdir(parents=True, exist_ok=True)
    tables = []
    for R0, outer, wound in zip(R0S, OUTERS, draw(NOISE, SEED)):
        frame = pd.DataFrame({"time_s": wound.radius.times_s, "radius_um": wound.radius.radius_um})
        frame.to_csv(out / f"tissue_R{R0:g}um.csv", index=False, float_format="%.4f")
        tables.append(frame.assign(wound=f"R{R0:g}")[["wound", "time_s", "radius_um"]])
    pd.concat(tables).to_csv(out / "tissue_long.csv", index=False, float_format="%.4f")
    print(f"{len(tables)} wounds (outer radii {', '.join(f'{o:g}' for o in OUTERS)} um) -> {out}")


if __name__ == "__main__":
    main()
