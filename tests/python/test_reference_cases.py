"""The paper's three cases shipped as reference results (FMI-LS-REF) in every WoundOpening
archive: each CSV agrees with the exact solution (python/wound_exact.py), and its options
file, re-run through fmpy, gives the CSV again."""

from __future__ import annotations

import csv
import io
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
import wound_exact
from fmpy import simulate_fmu

FOLDER = "extra/org.fmi-standard.fmi-ls-ref"
LAMBDAS = ("0.1", "1", "10")
# The stated accuracy (the archive's page, docs/fmi.md): the default tolerance, of the opening
# R_final - R1
# (measured 7.8e-12 at lambda = 0.1, 1.4e-12 at 1 and 10 over all rows).
ACCURACY = 1e-10


def _read(path, name):
    with zipfile.ZipFile(path) as z:
        return z.read(f"{FOLDER}/{name}").decode()


def _csv(text):
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array(rows[1:], dtype=float)


def _options(text):
    """fmusim's options file: {option: value}, start values as a dict."""
    opts, starts = {}, {}
    for line in text.splitlines():
        parts = line.split()
        if parts[0] == "--start-value":
            starts[parts[1]] = float(parts[2])
        else:
            opts[parts[0]] = parts[1] if len(parts) > 1 else None
    return opts, starts


@pytest.fixture(scope="module", params=["fmu_path", "fmu_me_path", "fmu3_path"])
def archive(request):
    return request.getfixturevalue(request.param)


def test_manifest_names_each_case_with_its_options(archive):
    with zipfile.ZipFile(archive) as z:
        root = ET.fromstring(z.read(f"{FOLDER}/fmi-ls-manifest.xml"))
        names = set(z.namelist())
    related = {(r.get("role"), r.get("source")) for r in root}
    for lam in LAMBDAS:
        assert ("result", f"WoundOpening_lambda_{lam}_ref.csv") in related
        assert ("experiment", f"WoundOpening_lambda_{lam}.opt") in related
    for _, source in related:
        assert f"{FOLDER}/{source}" in names


@pytest.mark.parametrize("lam", LAMBDAS)
def test_reference_case_agrees_with_the_exact_solution(archive, lam):
    head, rows = _csv(_read(archive, f"WoundOpening_lambda_{lam}_ref.csv"))
    assert head == ["time", "wound_radius", "edge_velocity"]
    _, starts = _options(_read(archive, f"WoundOpening_lambda_{lam}.opt"))
    assert starts == {"lambda": float(lam), "sigma": 1.0, "R_inf": 10.0}
    sigma, r_inf = starts["sigma"], starts["R_inf"]
    opening = wound_exact.final_radius(sigma, r_inf) - wound_exact.initial_radius(sigma)
    assert rows[0, 1] == pytest.approx(wound_exact.initial_radius(sigma), abs=1e-12)
    # Every 25th row (40 rows from 0.5 to 500 T) and the last: the exact inversion is the cost.
    sample = rows[1::25]
    exact_r, _ = wound_exact.edge(float(lam), sigma, r_inf, sample[:, 0])
    error = np.max(np.abs(sample[:, 1] - exact_r)) / opening
    assert error <= ACCURACY, f"lambda = {lam}: {error:.2e} of the opening"


@pytest.mark.parametrize("lam", LAMBDAS)
def test_options_file_rerun_through_fmpy_gives_the_reference(fmu_path, lam):
    """The options reproduce the CSV: fmpy's simulate_fmu with them (co-simulation)."""
    _, rows = _csv(_read(fmu_path, f"WoundOpening_lambda_{lam}_ref.csv"))
    opts, starts = _options(_read(fmu_path, f"WoundOpening_lambda_{lam}.opt"))
    assert opts["--interface-type"] == "cs"
    result = simulate_fmu(
        fmu_path,
        start_time=float(opts["--start-time"]),
        stop_time=float(opts["--stop-time"]),
        output_interval=float(opts["--output-interval"]),
        relative_tolerance=float(opts["--tolerance"]),
        start_values=starts,
        output=["wound_radius", "edge_velocity"],
    )
    assert len(result) == len(rows)
    np.testing.assert_allclose(result["time"], rows[:, 0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(result["wound_radius"], rows[:, 1], rtol=1e-13)
    np.testing.assert_allclose(result["edge_velocity"], rows[:, 2], rtol=1e-9, atol=1e-15)


def test_the_page_plots_the_three_cases(fmu_path):
    with zipfile.ZipFile(fmu_path) as z:
        page = z.read("documentation/index.html").decode()
    assert "The paper's three cases" in page
    section = page[page.index("The paper's three cases") :]
    assert "<svg" in section and all(f"lambda = {lam}" in section for lam in LAMBDAS)
