"""`sweep`: the sigma shortcut against direct simulations, local processes against one
process, a real Dask cluster (a scheduler and two workers started here) against a local run
bit for bit, and CSV / Parquet written without loss."""

from __future__ import annotations

import sys

import numpy as np
import pandas as pd
import pytest
from dask_cluster import cluster

import wound_opening as wo
from wound_opening.sweeping import sweep

sweep_module = sys.modules["wound_opening.sweeping"]

GRID = {
    "lambda": [0.0, 0.1, 1.0, 10.0],
    "sigma": [-0.5, 0.0, 0.3, 1.0, 2.0],
    "R_inf": [2.0, 10.0, 100.0],
}
TIMES = [0.0, 0.01, 0.5, 3.0, 40.0]


def test_the_sigma_shortcut_matches_direct_simulations():
    df = sweep(GRID, times=TIMES, processes=1)
    assert list(df.columns) == ["lambda", "sigma", "R_inf", "time", "wound_radius", "edge_velocity"]
    assert len(df) == 4 * 5 * 3 * 5
    for (lam, sigma, r_inf), rows in df.groupby(["lambda", "sigma", "R_inf"], sort=False):
        sim = wo.simulate(TIMES, lam=lam, sigma=sigma, R0_um=1.0, T_s=1.0, outer_radius_um=r_inf)
        # R - R1 and dR/dt scale with sigma up to rounding: a few ulps of the solution.
        np.testing.assert_allclose(rows.wound_radius, sim.radius_um, rtol=1e-13, atol=1e-14)
        finite = np.isfinite(sim.edge_velocity_um_s)
        np.testing.assert_allclose(
            rows.edge_velocity[finite], sim.edge_velocity_um_s[finite], rtol=1e-12, atol=1e-14
        )
        # At lambda = 0 the velocity at the cut is infinite (0 when there is no tension).
        assert np.all(rows.edge_velocity[~finite] == sim.edge_velocity_um_s[~finite]) or sigma == 0


def test_physical_units_scale_the_columns():
    a = sweep(GRID, times=TIMES, processes=1)
    b = sweep(GRID, times=np.array(TIMES) * 10.0, R0_um=5.0, T_s=10.0, processes=1)
    assert list(b.columns) == [
        "lambda",
        "sigma",
        "R_inf",
        "time_s",
        "wound_radius_um",
        "edge_velocity_um_s",
    ]
    assert b.attrs == {"R0_um": 5.0, "T_s": 10.0}
    np.testing.assert_array_equal(b.wound_radius_um, 5.0 * a.wound_radius)
    np.testing.assert_allclose(b.edge_velocity_um_s, 0.5 * a.edge_velocity, rtol=1e-15)
    np.testing.assert_array_equal(b.time_s, 10.0 * a.time)


def test_local_processes_and_a_dask_cluster_give_the_same_table_bit_for_bit(monkeypatch, tmp_path):
    monkeypatch.setattr(sweep_module, "CHUNK", 3)  # several tasks, so both workers get some
    grid = {"lambda": np.linspace(0.0, 5.0, 9), "sigma": [0.5, 1.0], "R_inf": [3.0, 10.0]}
    one = sweep(grid, times=TIMES, processes=1)
    two = sweep(grid, times=TIMES, processes=2)
    pd.testing.assert_frame_equal(one, two, check_exact=True)
    with cluster(workers=2) as address:
        from distributed import Client

        with Client(address) as client:
            assert len(client.scheduler_info()["workers"]) == 2
        on_dask = sweep(grid, times=TIMES, scheduler=address, progress=True)
    pd.testing.assert_frame_equal(one, on_dask, check_exact=True)
    one.to_csv(tmp_path / "s.csv", index=False)  # shortest round-trip digits: read back exactly
    one.to_parquet(tmp_path / "s.parquet")
    pd.testing.assert_frame_equal(
        pd.read_csv(tmp_path / "s.csv", dtype=float), one, check_exact=True
    )
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "s.parquet"), one, check_exact=True)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(grid={"lambda": [1.0], "sigma": [1.0]}), r"grid lacks \['R_inf'\]"),
        (dict(grid=None), "give either grid"),
        (dict(times=[-1.0]), "times must be"),
        (dict(grid={"lambda": [-1.0], "sigma": [1.0], "R_inf": [10.0]}), "lambda"),
        (dict(R0_um=5.0), "give both R0_um and T_s"),
    ],
)
def test_bad_sweeps_are_refused(kwargs, message):
    args = dict(grid=GRID, times=[1.0], processes=1) | kwargs
    with pytest.raises(ValueError, match=message):
        sweep(args.pop("grid"), **args)
