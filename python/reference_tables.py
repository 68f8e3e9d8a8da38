"""Write exact reference tables for examples/tune_mesh.rs: DIR/ref_{lambda}_{R_inf}.csv.

Rows (t, R(t), dR/dt) from wound_exact.edge (sigma = 1, p = 0) at t = 0.01 .. 1 every 0.01
and 20 points per decade from 0.01 to 1e8, for the lambda and R_inf of the scan.
"""

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import wound_exact  # noqa: E402

LAMBDAS = [0, 1e-3, 1e-2, 0.03, 0.1, 0.3, 1, 3, 10, 100, 1000]
RADII = [1.5, 2, 10, 100, 1000]

if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("dir", type=Path, help="folder for the ref_{lambda}_{R_inf}.csv tables")
    out = parser.parse_args().dir
    out.mkdir(parents=True, exist_ok=True)
    t = np.unique(np.concatenate([np.arange(1, 101) * 0.01, 0.01 * 10 ** (np.arange(0, 201) / 20)]))
    for lam in LAMBDAS:
        for r_inf in RADII:
            radius, velocity = wound_exact.edge(lam, 1.0, r_inf, t)
            np.savetxt(
                out / f"ref_{lam:g}_{r_inf:g}.csv", np.c_[t, radius, velocity], delimiter=","
            )
