"""Peer: the paper's appendix scheme, written in NumPy/SciPy the way a researcher would.

Source: the numerical appendix of Carvalho, Araujo and Patricio, "Wound opening in a thin
incompressible viscoelastic tissue" (docs/model.md, "The paper's own scheme"). Uniform
grid r_i = 1 + (i - 1) dr, i = 1 .. N, dr = (R_inf - 1)/(N - 1); t_n = n dt.

```text
interior, i = 2 .. N-1:
    (-I + (lambda^2 + 2 dt) D2) u^{n+1} = (-I + lambda^2 D2) u^{n-1}
    D2_{i,i-1} = 1/dr^2 - 1/(2 r_i dr),  D2_{i,i} = -2/dr^2 - 1/r_i^2,  D2_{i,i+1} = 1/dr^2 + 1/(2
        r_i dr)
wound edge, i = 1 (sigma_rr = p = 0), first-order one-sided:
    (lambda^2 + 2 dt) D_1 u^{n+1} = lambda^2 D_1 u^{n-1} + 2 dt p
    D_11 = -4/dr + 2/r_1,  D_12 = 4/dr
outer edge, i = N (sigma_rr = sigma):
    (lambda^2 + 2 dt) D_N u^{n+1} = lambda^2 D_N u^{n-1} + 2 dt sigma
    D_{N,N-1} = -4/dr,  D_{N,N} = 4/dr + 2/r_N
```

i.e. A u^{n+1} = B u^{n-1} + C. The paper gives no start value u^1: it is one
backward-Euler step of dt from u^0 = sigma r / 6 (the same rows with 2 dt -> dt). A is
factorised once (sparse LU). R = 1 + u_1 at the communication points (every 0.1/dt steps).

    python -m bench.paper_peer --out target/bench      (with python/ on PYTHONPATH)
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import scipy.sparse as sps
import scipy.sparse.linalg as spla

from bench import common

SIZES = (101, 201, 401, 1001, 2001, 4001, 10001)
STEPS = (0.1, 0.01, 0.001)
#: A run slower than this (CPU seconds) stops the sweep to finer grids at that dt.
SLOW_RUN = 2.5


def matrices(n: int, lam: float, k: float, p: float = 0.0):
    """(A, B, C) for a step of k = 2 dt (the three-level step) or k = dt (the start step)."""
    dr = (common.R_INF - 1.0) / (n - 1)
    r = 1.0 + dr * np.arange(n)
    ri = r[1:-1]
    d2 = sps.diags(
        [
            np.r_[1 / dr**2 - 1 / (2 * ri * dr), 0.0],
            np.r_[0.0, -2 / dr**2 - 1 / ri**2, 0.0],
            np.r_[0.0, 1 / dr**2 + 1 / (2 * ri * dr)],
        ],
        [-1, 0, 1],
        format="lil",
    )
    d = sps.lil_matrix((n, n))
    d[0, 0], d[0, 1] = -4 / dr + 2 / r[0], 4 / dr
    d[n - 1, n - 2], d[n - 1, n - 1] = -4 / dr, 4 / dr + 2 / r[-1]
    inner = sps.diags(np.r_[0.0, np.ones(n - 2), 0.0])
    a = (-inner + (lam**2 + k) * (d2.tocsr() + d.tocsr())).tocsc()
    b = (-inner + lam**2 * (d2.tocsr() + d.tocsr())).tocsr()
    c = np.zeros(n)
    c[0], c[-1] = k * p, k * common.SIGMA
    return a, b, c, r


def solve(lam: float, n: int, dt: float, t: np.ndarray | None = None) -> np.ndarray:
    """R at the communication points (multiples of 0.1), the whole scenario."""
    t = common.times() if t is None else t
    every = int(round(common.STEP / dt))
    a1, b1, c1, r = matrices(n, lam, dt)
    a2, b2, c2, _ = matrices(n, lam, 2 * dt)
    lu = spla.splu(a2)
    prev = common.SIGMA * r / 6
    now = spla.splu(a1).solve(b1 @ prev + c1)
    radius = np.empty(t.size)
    if every == 1:
        radius[0] = 1.0 + now[0]
    for step in range(2, int(round(t[-1] / dt)) + 1):
        prev, now = now, lu.solve(b2 @ prev + c2)
        if step % every == 0:
            radius[step // every - 1] = 1.0 + now[0]
    return radius


def sweep(lambdas=common.LAMBDAS, repeats: int = 3, log=print):
    """Rows (scheme, lambda, resolution, unknowns, error, cpu_seconds)."""
    rows = []
    for lam in lambdas:
        for dt in STEPS:
            rows += common.sweep_sizes(
                "paper_peer",
                lam,
                SIZES,
                f"dt={dt:g}",
                lambda n: solve(lam, n, dt),
                repeats,
                SLOW_RUN,
                log,
            )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("target/bench"))
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    common.write_rows(args.out / "paper_peer.csv", common.WORK_COLUMNS, sweep(repeats=args.repeats))


if __name__ == "__main__":
    main()
