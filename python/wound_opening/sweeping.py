"""`sweep`: many parameter sets to a table of outputs at requested times.

Work is grouped by (lambda, R_inf): the edge stress being 0, R - R1 and dR/dt are
proportional to sigma (the problem is linear and its initial state is sigma r / 6), so each
pair is solved once, at sigma = 1, in one C call for all times, and every sigma of the pair
is a product:

```text
R(t; sigma) = 1 + sigma / 6 + sigma (R(t; 1) - 7/6)        dR/dt(t; sigma) = sigma dR/dt(t; 1)
```

Pairs are cut into chunks, computed in local processes (default) or on a Dask cluster
(`scheduler="tcp://host:port"`): the same function on the same chunks, so both give the
same numbers bit for bit. Only plain tuples travel to workers; each worker process loads
the native library itself.
"""

from __future__ import annotations

import itertools
import math
import os
from concurrent.futures import ProcessPoolExecutor, as_completed

import numpy as np

from .model import edge_series

COLUMNS = ["lambda", "sigma", "R_inf", "time", "wound_radius", "edge_velocity"]
#: The columns in physical units (R0_um and T_s given): times in s, radii in um, velocities in um/s.
PHYSICAL_COLUMNS = ["lambda", "sigma", "R_inf", "time_s", "wound_radius_um", "edge_velocity_um_s"]
#: Fewest (lambda, R_inf) pairs per task; large sweeps are cut into at most MAX_TASKS tasks
#: (each pair is solved alone, so the cut does not change a single bit of the result).
CHUNK = 256
MAX_TASKS = 64


def parameter_sets(grid=None, sets=None) -> np.ndarray:
    """An (n, 3) array of (lambda, sigma, R_inf): the product of `grid` = {"lambda": [...],
    "sigma": [...], "R_inf": [...]} (lambda outermost), or the rows of `sets`."""
    if (grid is None) == (sets is None):
        raise ValueError(
            "sweep: give either grid (lists per parameter) or sets (a list of parameter sets)"
        )
    if grid is not None:
        missing = {"lambda", "sigma", "R_inf"} - set(grid)
        if missing:
            raise ValueError(f"sweep: grid lacks {sorted(missing)}")
        rows = list(
            itertools.product(
                *(np.atleast_1d(np.asarray(grid[k], float)) for k in ("lambda", "sigma", "R_inf"))
            )
        )
    else:
        rows = [
            (s["lambda"], s["sigma"], s["R_inf"]) if isinstance(s, dict) else tuple(s) for s in sets
        ]
    out = np.asarray(rows, dtype=float).reshape(-1, 3)
    if not np.all(np.isfinite(out)):
        raise ValueError("sweep: every parameter must be finite")
    return out


def solve_chunk(pairs, times):
    """R(t; sigma = 1) and dR/dt(t; 1) for each (lambda, R_inf) pair: arrays (len(pairs),
    len(times))."""
    tau = np.asarray(times, dtype=float)
    order = np.argsort(tau, kind="stable")
    radius = np.empty((len(pairs), tau.size))
    velocity = np.empty_like(radius)
    for k, (lam, r_inf) in enumerate(pairs):
        r, v = edge_series(lam, 1.0, r_inf, tau[order])
        radius[k, order], velocity[k, order] = r, v
    return radius, velocity


def _chunks(pairs):
    size = max(CHUNK, -(-len(pairs) // MAX_TASKS))
    return [pairs[i : i + size] for i in range(0, len(pairs), size)]


def _progress(total, enabled):
    from tqdm import tqdm

    return tqdm(total=total, unit="pair", disable=not enabled, desc="sweep")


def _run_local(chunks, times, processes, bar):
    results = [None] * len(chunks)
    if processes == 1 or len(chunks) == 1:
        for i, c in enumerate(chunks):
            results[i] = solve_chunk(c, times)
            bar.update(len(c))
        return results
    with ProcessPoolExecutor(max_workers=processes) as pool:
        futures = {pool.submit(solve_chunk, c, times): i for i, c in enumerate(chunks)}
        for f in as_completed(futures):
            results[futures[f]] = f.result()
            bar.update(len(chunks[futures[f]]))
    return results


def _run_dask(chunks, times, scheduler, bar):
    from distributed import Client
    from distributed import as_completed as dask_completed

    with Client(scheduler, timeout="30s") as client:
        futures = client.map(solve_chunk, chunks, times=list(times), pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results = [None] * len(chunks)
        for f in dask_completed(futures):
            results[index[f.key]] = f.result()
            bar.update(len(chunks[index[f.key]]))
    return results


def sweep(
    grid=None,
    *,
    times,
    sets=None,
    R0_um: float | None = None,
    T_s: float | None = None,
    scheduler: str | None = None,
    processes: int | None = None,
    progress: bool | None = None,
):
    """Outputs of every parameter set at every time, as a pandas DataFrame with columns
    lambda, sigma, R_inf, time, wound_radius, edge_velocity (one row per set and time).

    Dimensionless by default (lengths in R0, time in T, as the FMU's defaults); with R0_um
    and T_s (both or neither), `times` are in s and the columns are time_s, wound_radius_um
    and edge_velocity_um_s (um/s), with R0_um and T_s in `df.attrs`. The edge stress
    is 0 (free edge). Local processes by default (`processes`, default: all cores), or the
    Dask cluster at `scheduler`; identical numbers either way. `progress`: a tqdm bar
    (default: on for more than 2000 pairs)."""
    import pandas as pd

    physical = R0_um is not None or T_s is not None
    if physical and (R0_um is None or T_s is None):
        raise ValueError(
            "sweep: give both R0_um and T_s (physical units) or neither (dimensionless)"
        )
    if not physical:
        R0_um = T_s = 1.0
    if not (math.isfinite(R0_um) and R0_um > 0 and math.isfinite(T_s) and T_s > 0):
        raise ValueError(f"sweep: R0_um = {R0_um} and T_s = {T_s} must be finite and > 0")
    params = parameter_sets(grid, sets)
    t = np.atleast_1d(np.asarray(times, dtype=float))
    if t.ndim != 1 or t.size == 0 or not np.all(np.isfinite(t)) or np.any(t < 0):
        raise ValueError("sweep: times must be a non-empty list of finite times >= 0")
    keys, inverse = np.unique(params[:, [0, 2]], axis=0, return_inverse=True)
    pairs = [tuple(map(float, k)) for k in keys]
    chunks = _chunks(pairs)
    with _progress(len(pairs), len(pairs) > 2000 if progress is None else progress) as bar:
        if scheduler:
            results = _run_dask(chunks, t / T_s, scheduler, bar)
        else:
            results = _run_local(chunks, t / T_s, processes or os.cpu_count() or 1, bar)
    radius1 = np.concatenate([r for r, _ in results])[inverse.ravel()]
    velocity1 = np.concatenate([v for _, v in results])[inverse.ravel()]
    sigma = params[:, 1:2]
    radius = 1 + sigma / 6 + sigma * (radius1 - 7 / 6)
    with np.errstate(invalid="ignore"):
        velocity = np.where(sigma == 0, 0.0, sigma * velocity1)
    n, m = radius.shape
    names = PHYSICAL_COLUMNS if physical else COLUMNS
    values = [
        np.repeat(params[:, 0], m),
        np.repeat(params[:, 1], m),
        np.repeat(params[:, 2], m),
        np.tile(t, n),
        R0_um * radius.ravel(),
        R0_um / T_s * velocity.ravel(),
    ]
    df = pd.DataFrame(dict(zip(names, values)), columns=names)
    if physical:
        df.attrs.update(R0_um=float(R0_um), T_s=float(T_s))
    return df
