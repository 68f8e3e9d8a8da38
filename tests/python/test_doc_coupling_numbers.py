"""The radii docs/fmi.md quotes for the worked example are those the package's example
(`python -m wound_opening.coupling`, wound_opening/coupling/example.py) produces (the loop
with input derivatives, step 0.5 s), read from the sentence itself."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
from wound_opening.coupling.example import STEP, STOP  # noqa: E402
from wound_opening.coupling.loop import couple  # noqa: E402

SENTENCE = re.compile(
    r"opens from ([\d.]+) um to ([\d.]+) um at t = ([\d.]+) s,"
    r".*?closes to ([\d.]+) um at 300 s \(free opening: ([\d.]+) um[;)]",
    re.S,
)


def _quoted(number: str, value: float) -> bool:
    """`number` is `value` rounded to the digits quoted."""
    decimals = len(number.split(".")[1]) if "." in number else 0
    return f"{value:.{decimals}f}" == number


def test_docs_quote_the_radii_the_example_produces(fmu_path, purse_path):
    text = (ROOT / "docs" / "fmi.md").read_text()
    match = SENTENCE.search(text)
    assert match, "docs/fmi.md: the worked example's sentence is gone"
    r0, r_max, t_max, r_end, r_free = match.groups()
    step, stop = STEP, STOP
    run = couple(fmu_path, purse_path, step=step, stop=stop, interpolate=True)
    free = couple(fmu_path, None, step=step, stop=stop, edge_stress=0.0)
    i = int(np.argmax(run.wound_radius))
    assert _quoted(r0, run.wound_radius[0]), (r0, run.wound_radius[0])
    assert _quoted(r_max, run.wound_radius[i]), (r_max, run.wound_radius[i])
    assert float(t_max) == pytest.approx(run.time[i])
    assert _quoted(r_end, run.wound_radius[-1]), (r_end, run.wound_radius[-1])
    assert _quoted(r_free, free.wound_radius[-1]), (r_free, free.wound_radius[-1])
