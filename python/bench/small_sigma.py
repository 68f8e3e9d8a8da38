"""Error of the wound radius relative to the opening at small sigma, through `wo_series`.

The problem is linear in sigma, so the exact opening is R(t) - 1 = sigma (R_ref(t) - 1), with
R_ref the exact radius at sigma = 1 (`wound_exact.edge`); the error is
max |(R - 1) - sigma (R_ref - 1)| / |R_final - R1| over 41 times from 0.01 to 1000 T
(lambda = 1, R_inf = 10). A sigma the component refuses (below 6 eps / tolerance,
docs/model.md) prints as "refused". Run from the repository root:

    python python/bench/small_sigma.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import wound_exact as we  # noqa: E402

from wound_opening import _native  # noqa: E402

LAM, R_INF = 1.0, 10.0
SIGMAS = 10.0 ** -np.arange(3, 13)
TOLERANCES = (1e-6, 1e-8, 1e-10, 1e-11)


def main() -> None:
    t = np.geomspace(0.01, 1000, 41)
    ref = we.edge(LAM, 1.0, R_INF, t)[0] - 1.0
    amplitude = we.final_radius(1.0, R_INF) - we.initial_radius(1.0)
    print("tolerance \\ sigma " + " ".join(f"{s:8.0e}" for s in SIGMAS))
    for tol in TOLERANCES:
        row = []
        for s in SIGMAS:
            try:
                r, _ = _native.series(LAM, s, R_INF, t, velocity=False, tolerance=tol)
            except _native.SolverError:
                row.append(" refused")
                continue
            row.append(f"{np.max(np.abs((r - 1.0) - s * ref)) / (s * amplitude):8.1e}")
        print(f"{tol:17.0e} " + " ".join(row))
    print(
        f"{'bound 2 eps/sigma':>17} "
        + " ".join(f"{2 * np.finfo(float).eps / s:8.1e}" for s in SIGMAS)
    )


if __name__ == "__main__":
    main()
