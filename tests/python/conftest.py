"""Shared pytest setup for the FMU tests.

* puts `python/` (the exact reference, wound_exact.py) and this folder (fmu_harness.py)
  on sys.path;
* locates the FMU relative to the repository root (two levels above this file); if it is
  missing, every test that needs it fails (it is never skipped) with a message saying how
  to build it;
* prints the measured accuracy figures collected by the tests at the end of the run.
"""

from __future__ import annotations

import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
for _p in (ROOT / "python", HERE):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

import fmu_harness  # noqa: E402  (needs the sys.path entries above)

FMU_DIR = ROOT / "target" / "fmu"


def _built(name: str) -> str:
    path = FMU_DIR / f"{name}.fmu"
    if not path.is_file():
        pytest.fail(
            f"FMU not found: {path}\nBuild it first, from {ROOT}: cargo run --release -- fmu",
            pytrace=False,
        )
    return str(path)


@pytest.fixture(scope="session")
def fmu_path() -> str:
    return _built("WoundOpening")


@pytest.fixture(scope="session")
def fmu_me_path() -> str:
    """WoundOpening's FMI 2.0 Model Exchange archive."""
    return _built("WoundOpening-me")


@pytest.fixture(scope="session")
def purse_path() -> str:
    return _built("PurseString")


@pytest.fixture(scope="session")
def fmu3_path() -> str:
    return _built("WoundOpening-fmi3")


@pytest.fixture(scope="session")
def purse3_path() -> str:
    return _built("PurseString-fmi3")


@pytest.fixture(scope="session")
def model_description(fmu_path):
    from fmpy import read_model_description

    return read_model_description(fmu_path)


def _extracted(path):
    """The FMU extracted once per session; every FMU2Slave of the session loads it."""
    from fmpy import extract

    directory = extract(path)
    yield str(directory)
    shutil.rmtree(directory, ignore_errors=True)


def _slaves(unzipdir, model_description, **defaults):
    """Factory for harness Slaves; every Slave made by a test is freed after it."""
    made = []

    def make(**kwargs):
        slave = fmu_harness.Slave(unzipdir, model_description, **{**defaults, **kwargs})
        made.append(slave)
        return slave

    yield make
    for slave in reversed(made):
        slave.close()


@pytest.fixture(scope="session")
def unzipdir(fmu_path):
    yield from _extracted(fmu_path)


@pytest.fixture
def make_slave(unzipdir, model_description):
    yield from _slaves(unzipdir, model_description)


@pytest.fixture(scope="session")
def purse_unzipdir(purse_path):
    yield from _extracted(purse_path)


@pytest.fixture
def make_purse(purse_unzipdir, purse_path):
    """Harness Slaves of the PurseString FMU."""
    from fmpy import read_model_description

    yield from _slaves(purse_unzipdir, read_model_description(purse_path), instance_name="purse")


# With pytest-xdist each worker process measures its own tests: a worker leaves its figures
# in a folder the controlling process made (inherited through the environment), and the
# controller reports them all.
_MEASURED_DIR = "WOUND_OPENING_MEASURED_DIR"


def pytest_configure(config):
    if not hasattr(config, "workerinput") and _MEASURED_DIR not in os.environ:
        os.environ[_MEASURED_DIR] = tempfile.mkdtemp(prefix="wound-opening-measured-")


def pytest_runtest_teardown(item):
    """A worker's figures so far, after each of its tests (the controller may report before
    a worker's own session end)."""
    folder = os.environ.get(_MEASURED_DIR)
    worker = getattr(item.config, "workerinput", {}).get("workerid")
    if folder and worker and fmu_harness.MEASURED and Path(folder).is_dir():
        (Path(folder) / f"{worker}.json").write_text(json.dumps(fmu_harness.MEASURED))


def pytest_terminal_summary(terminalreporter, config):
    if hasattr(config, "workerinput"):
        return
    folder = os.environ.get(_MEASURED_DIR)
    if folder and Path(folder).is_dir():
        for part in sorted(Path(folder).glob("*.json")):
            for key, value in json.loads(part.read_text()).items():
                fmu_harness.MEASURED[key] = max(value, fmu_harness.MEASURED.get(key, 0.0))
        shutil.rmtree(folder, ignore_errors=True)
    if not fmu_harness.MEASURED:
        return
    terminalreporter.section("measured errors (maxima; tolerances are in the tests)")
    for key in sorted(fmu_harness.MEASURED):
        terminalreporter.write_line(f"{key}: {fmu_harness.MEASURED[key]:.3e}")


#: Tests that take tens of seconds of one worker (measured 2026-12-03 with --durations: the
#: wheel's fresh venv 56 s, the Dask cluster 12 s, the mpmath references 11 s each). They run
#: first: handed out last (test_wheel.py sorts last), the longest kept one xdist worker busy
#: alone for most of a minute at the end of the run while the other sat idle.
LONG_FIRST = (
    "test_wheel.py::test_wheel_installs_and_runs_without_rust_or_checkout",
    "test_sweep.py::test_local_processes_and_a_dask_cluster_give_the_same_table_bit_for_bit",
    "test_reference.py::test_edge_agrees_with_mpmath",
    # a rendered movie measured and fitted (13 s), the early-times coverage sample (12 s),
    # the centre of a rendered movie (8 s): measured 2026-12-07
    "test_lab_viscous_limit.py::test_radius_fit_at_the_viscous_limit_gives_honest_numbers",
    # a rendered movie measured and fitted at the outline's floor (10 s): 2026-12-07
    "test_outline_floor.py::test_a_rendered_movie_radius_fit_publishes_no_wrong_identified_value",
    "test_fit.py::test_early_times_at_one_percent_noise_report_no_interval_that_misses_the_truth",
    "test_lab_centre.py::test_centre_of_a_large_wound_from_openpiv_files_holds_the_truth",
)


def pytest_collection_modifyitems(config, items):
    """The LONG_FIRST tests first (in that order), the others as collected."""

    def rank(item):
        return next(
            (k for k, name in enumerate(LONG_FIRST) if name in item.nodeid), len(LONG_FIRST)
        )

    items.sort(key=rank)  # stable: the order within each rank is kept
