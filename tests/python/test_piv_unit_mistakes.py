"""Unit mistakes with OpenPIV files, which do not state their units, are refused naming the
option at fault (inputs/edge_speed.py unit_mistake, piv.py, fiji.py): the examples' wound of
8 um (python/make_lab_examples.py, the exact solution) with its field written by
openpiv.tools.save's layout in px and px/s, and the same field in um and um/s."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
import make_lab_examples as lab  # noqa: E402

from wound_opening.cli import main  # noqa: E402

R0 = 8.0
HEAD = "\t".join(["x", "y", "u", "v", "flags", "mask"])


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """(Fiji table in px^2, in um^2, OpenPIV folder in px and px/s, in um and um/s)."""
    out = tmp_path_factory.mktemp("units")
    lab.write_fiji(out / "Results_px.csv", R0, noise_px=0.3)
    lines = (out / "Results_px.csv").read_text().splitlines()
    head = lines[0].split(",")
    um2 = [lines[0]]
    for s in lines[1:]:
        cells = s.split(",")
        for name, power in (("Area", 2), ("Perim.", 1)):
            k = head.index(name) if name in head else None
            if k is not None and cells[k] not in ("", "NaN"):
                cells[k] = repr(float(cells[k]) * lab.PIXEL_UM**power)
        um2.append(",".join(cells))
    (out / "Results_um.csv").write_text("\n".join(um2) + "\n")
    lab.write_openpiv(out / "px", R0, noise=0.05)
    (out / "um").mkdir()
    for f in sorted((out / "px").iterdir()):
        a = np.loadtxt(f)
        a[:, :4] *= lab.PIXEL_UM
        np.savetxt(out / "um" / f.name, a, fmt="%.4e", delimiter="\t", header=HEAD)
    return out


def _run(capsys, table, folder, *options) -> str:
    argv = ["fit", str(table), "--area-col", "Area", "--frame-interval-s", str(lab.FRAME_S)]
    argv += ["--cut-after-frame", str(lab.CUT_AFTER), "--outer-radius-um", "100"]
    argv += ["--piv", str(folder), "--piv-first-frame", str(lab.PIV_FIRST)]
    argv += ["--piv-pair-step", str(lab.PIV_STEP), *options]
    code = main(argv)
    err = capsys.readouterr().err
    assert code == 2, err
    return err


def test_a_forgotten_piv_units_is_named_at_every_step(files, capsys):
    """A table in um^2 and OpenPIV files in um, --piv-units forgotten (px,px/s read): the
    first refusal asks for a pixel size or --piv-units um,um/s; the pixel size then given
    (with the table's um) is refused naming --piv-units um,um/s again."""
    table, folder = files / "Results_um.csv", files / "um"
    first = _run(capsys, table, folder)
    assert "--pixel-size-um" in first and "--piv-units um,um/s" in first, first
    second = _run(capsys, table, folder, "--pixel-size-um", str(lab.PIXEL_UM))
    assert "--piv-units um,um/s" in second, second


@pytest.mark.parametrize(
    "folder, units, fix",
    [
        ("px", "px,px/frame", "velocities in px/s read as px/frame: give --piv-units px,px/s"),
        ("um", "um,um/frame", "velocities in um/s read as um/frame: give --piv-units um,um/s"),
    ],
)
def test_a_velocity_per_frame_read_for_per_s_is_named(files, capsys, folder, units, fix):
    """Velocities in LENGTH/s read as LENGTH/frame (4 frames a second): the edge speed is
    off by the frame interval's inverse, and the refusal names the --piv-units to give."""
    px = ("--length-unit", "px", "--pixel-size-um", str(lab.PIXEL_UM))
    err = _run(capsys, files / "Results_px.csv", files / folder, *px, "--piv-units", units)
    assert fix in err and "A factor 4 from a correct field's" in err, err


def test_the_named_mistake_is_the_one_made():
    """unit_mistake names a factor only near its own: the pixel size squared for um read as
    px, 1 / frame interval for per s read per frame; nothing for a correct field's ratio or
    for files that name their units (PIVlab)."""
    from wound_opening.inputs.edge_speed import unit_mistake

    px = ("px", "px/s")
    assert "--piv-units um,um/s" in unit_mistake(0.8 * 0.04, px, 0.25, 0.2)
    assert "--piv-units px,px/frame" in unit_mistake(0.8 * 0.25, px, 0.25, 0.2)
    assert unit_mistake(0.8, px, 0.25, 0.2) is None
    assert unit_mistake(0.8 * 0.25, None, 0.25, 0.2) is None


def test_the_fields_own_interval_names_a_per_frame_mistake(files):
    """Through the Python API, a field read with its frames' clock and profiled without
    repeating the frame interval: the refusal still names the per-frame mistake, from the
    interval the field carries (rings.field_profile's Measurement)."""
    from wound_opening.inputs.columns import InputError
    from wound_opening.inputs.fiji import read_fiji
    from wound_opening.inputs.piv import Frames, read_field
    from wound_opening.inputs.rings import field_profile

    units = ("px", "px/frame")
    radius = read_fiji(
        files / "Results_px.csv",
        area_col="Area",
        frame_interval_s=lab.FRAME_S,
        cut_after_frame=lab.CUT_AFTER,
        length_unit="px",
        pixel_size_um=lab.PIXEL_UM,
    )
    frames = Frames(lab.FRAME_S, lab.CUT_AFTER, lab.PIV_FIRST, lab.PIV_STEP)
    field = read_field(files / "px", frames, pixel_size_um=lab.PIXEL_UM, units=units)
    with pytest.raises(InputError) as refused:
        field_profile(field, radius, 100.0, units=units, pixel_size_um=lab.PIXEL_UM)
    assert "give --piv-units px,px/s" in str(refused.value), refused.value
