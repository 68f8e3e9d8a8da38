"""SciPy peer: method of lines with second-order finite differences, integrated by solve_ivp.

Written the way a researcher would: a uniform grid of N points, r_i = 1 + i dr
(i = 0 .. N-1, dr = (R_inf - 1)/(N - 1)), and

```text
interior (centred, O(dr^2)):
    (D2 f)_i = (f_{i+1} - 2 f_i + f_{i-1}) / dr^2 + (f_{i+1} - f_{i-1}) / (2 r_i dr) - f_i / r_i^2
edges (one-sided, O(dr^2)), D f = 2 (2 f' + f / r):
    (D f)_0     = 2 (2 (-3 f_0 + 4 f_1 - f_2) / (2 dr) + f_0 / r_0)
    (D f)_{N-1} = 2 (2 (3 f_{N-1} - 4 f_{N-2} + f_{N-3}) / (2 dr) + f_{N-1} / r_{N-1})
PDE rows:   (I - lambda^2 D2) u_t = D2 u
edge rows:  lambda^2 D u_t = -D u + s,   s = p (wound edge, 0 here), sigma (outer edge)
```

that is M u' = K u + f with M = E - lambda^2 K (E = the identity with its two edge
rows zeroed). For lambda > 0, M is invertible: the right-hand side is a solve with M
factorised once (sparse LU) and the Jacobian M^-1 K, dense because M^-1 is, is handed
to the implicit solvers as a constant matrix (the problem is linear). Its eigenvalues
lie in [-1/lambda^2, 0), so explicit Runge-Kutta methods are stable with steps of order
lambda^2 and are tried too. At lambda = 0 the edge rows are algebraic (D u = s): the
edge values are eliminated, leaving u_t = D2 u on the interior points with a sparse
tridiagonal Jacobian.

The wound radius is R = 1 + u_0 at the communication points, through `t_eval`.

    python -m bench.scipy_peer --out target/bench      (with python/ on PYTHONPATH)
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import scipy.sparse as sps
import scipy.sparse.linalg as spla
from scipy.integrate import solve_ivp

from bench import common

#: solve_ivp method -> (grid sizes, rtol values, slow run); atol = rtol (u is of order 1).
#: A run slower than `slow run` CPU seconds stops the sweep to finer grids at that rtol.
#: BDF and LSODA factorise the dense Jacobian (LU cost ~ N^3, memory ~ N^2): they stop at
#: N = 1601. DOP853's cost grows as N (its step is bounded by lambda^2, not by the grid).
SWEEP = {
    "BDF": ((101, 201, 401, 801, 1601), (1e-6, 1e-8, 1e-10), 2.5),
    "LSODA": ((101, 201, 401, 801, 1601), (1e-6, 1e-8, 1e-10), 2.5),
    "DOP853": ((201, 801, 3201, 12801, 25601), (1e-7, 1e-10), 10.0),
}


def grid(n: int) -> tuple[np.ndarray, float]:
    dr = (common.R_INF - 1.0) / (n - 1)
    return 1.0 + dr * np.arange(n), dr


def operators(n: int) -> tuple[sps.csr_matrix, np.ndarray, np.ndarray]:
    """K with rows D2 (interior) and -D (edges) as CSR, and the two edge rows of D."""
    r, dr = grid(n)
    ri = r[1:-1]
    lower = 1 / dr**2 - 1 / (2 * ri * dr)
    diag = -2 / dr**2 - 1 / ri**2
    upper = 1 / dr**2 + 1 / (2 * ri * dr)
    rows = np.repeat(np.arange(1, n - 1), 3)
    cols = (np.arange(1, n - 1)[:, None] + np.array([-1, 0, 1])).ravel()
    vals = np.column_stack([lower, diag, upper]).ravel()
    d_edge = np.array([-6 / dr + 2 / r[0], 8 / dr, -2 / dr])  # on u_0, u_1, u_2
    d_outer = np.array([2 / dr, -8 / dr, 6 / dr + 2 / r[-1]])  # on u_{N-3}, u_{N-2}, u_{N-1}
    rows = np.concatenate([[0, 0, 0], rows, [n - 1] * 3])
    cols = np.concatenate([[0, 1, 2], cols, [n - 3, n - 2, n - 1]])
    vals = np.concatenate([-d_edge, vals, -d_outer])
    return sps.csr_matrix((vals, (rows, cols)), shape=(n, n)), d_edge, d_outer


def system(n: int, lam: float, p: float = 0.0):
    """(fun, jacobian, y0, to_radius) of the ODE solve_ivp integrates; jacobian() builds J."""
    r, _ = grid(n)
    k, d_edge, d_outer = operators(n)
    u0 = common.SIGMA * r / 6
    if lam > 0:
        f = np.zeros(n)
        f[0], f[-1] = p, common.SIGMA
        e = sps.identity(n, format="lil")
        e[0, 0] = e[n - 1, n - 1] = 0.0
        m = (e.tocsr() - lam**2 * k).tocsc()
        lu = spla.splu(m)
        return (
            (lambda t, u: lu.solve(k @ u + f)),
            (lambda: lu.solve(k.toarray())),
            u0,
            (lambda y: 1.0 + y[0]),
        )
    # lambda = 0: u_0 = (p - d1 u_1 - d2 u_2) / d0 and likewise u_{N-1}; unknowns u_1..u_{N-2}.
    inner = k[1:-1]
    elim = sps.lil_matrix((n, n - 2))
    elim[1:-1, :] = sps.identity(n - 2)
    elim[0, 0], elim[0, 1] = -d_edge[1] / d_edge[0], -d_edge[2] / d_edge[0]
    elim[n - 1, n - 4], elim[n - 1, n - 3] = -d_outer[0] / d_outer[2], -d_outer[1] / d_outer[2]
    shift = np.zeros(n)
    shift[0], shift[-1] = p / d_edge[0], common.SIGMA / d_outer[2]
    a = (inner @ elim.tocsr()).tocsc()
    g = inner @ shift
    edge_u = lambda y: (p - d_edge[1] * y[0] - d_edge[2] * y[1]) / d_edge[0]  # noqa: E731
    return (lambda t, u: a @ u + g), (lambda: a), u0[1:-1], (lambda y: 1.0 + edge_u(y))


def solve(
    lam: float, n: int, rtol: float, method: str = "BDF", t: np.ndarray | None = None
) -> np.ndarray:
    """R at the communication points (whole scenario: operators, factorisation, integration)."""
    t = common.times() if t is None else t
    fun, jacobian, y0, to_radius = system(n, lam)
    options = {}
    if method in ("BDF", "Radau"):
        options["jac"] = jacobian()
    elif method == "LSODA":  # J is built on LSODA's first call, i.e. once it switches to BDF
        cache = {}

        def jac(t, y):
            if "J" not in cache:
                j = jacobian()
                cache["J"] = j.toarray() if sps.issparse(j) else j
            return cache["J"]

        options["jac"] = jac
    sol = solve_ivp(fun, (0.0, t[-1]), y0, method=method, t_eval=t, rtol=rtol, atol=rtol, **options)
    if sol.status != 0:
        return np.full(t.shape, np.nan)
    return to_radius(sol.y)


def sweep(lambdas=common.LAMBDAS, methods=tuple(SWEEP), repeats: int = 3, log=print):
    """Rows (scheme, lambda, resolution, unknowns, error, cpu_seconds)."""
    rows = []
    for method in methods:
        sizes, tolerances, slow_run = SWEEP[method]
        for lam in lambdas:
            for rtol in tolerances:
                rows += common.sweep_sizes(
                    f"scipy_{method}",
                    lam,
                    sizes,
                    f"rtol={rtol:g}",
                    lambda n: solve(lam, n, rtol, method),
                    repeats,
                    slow_run,
                    log,
                )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("target/bench"))
    parser.add_argument("--methods", nargs="+", default=list(SWEEP), choices=list(SWEEP))
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    rows = sweep(methods=args.methods, repeats=args.repeats)
    common.write_rows(args.out / "scipy_peer.csv", common.WORK_COLUMNS, rows)
    check_convergence(rows)


def check_convergence(rows: list[tuple], low: float = 1.5) -> None:
    """A fair peer converges to the exact solution at its order (2): at each method's
    tightest rtol, every grid doubling must show an observed order >= `low`."""
    tight = {f"scipy_{m}": f"rtol={min(tols):g}" for m, (_, tols, _) in SWEEP.items()}
    bad = []
    for scheme, lam, setting, n1, n2, order in common.observed_orders(rows):
        if tight.get(scheme) == setting:
            print(
                f"{scheme} lambda={lam} {setting}: observed order {order:.2f} from N={n1} to N={n2}"
            )
            bad += [] if order >= low else [(scheme, lam, n1, n2, order)]
    if bad:
        raise SystemExit(f"scipy peer does not converge at second order: {bad}")


if __name__ == "__main__":
    main()
