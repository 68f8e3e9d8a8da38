"""PIV vector fields as PIVlab and OpenPIV write them: one text file per frame pair, read
into one field (positions in um, velocities in um/s, times in s since the cut).

PIVlab (its ASCII export, +export/file_save.m): optional info lines ("PIVlab, ASCII chart
output - DATE", "FRAME: k, filenames: A & B, conversion factor xy (px -> m): ..."), optional
column headings, then the numbers (10 significant digits, "NaN"), separated by ",", a tab
or a space, CRLF line ends; one file per frame pair, PIVlab_0001.txt, ... The headings name
the units: "x [m],y [m],u [m/s],v [m/s],Vector type [-]" when calibrated (or "u [m/frame]"
for displacements only), "x [px],y [px],u [px/frame],v [px/frame],Vector type [-]"
uncalibrated, maybe followed by derived columns. Vector type: 0 masked (u, v written NaN),
1 valid, 2 interpolated (a vector that failed validation, replaced from its neighbours).

OpenPIV (openpiv.tools.save, numpy.savetxt): a heading "# x<TAB>y<TAB>u<TAB>v<TAB>flags
<TAB>mask", numbers as "%.4e" separated by tabs; x, y in pixels and u, v in pixels per
second unless scaled (openpiv.scaling.uniform): the file does not say, `units` does;
flags: 0 valid, 1 invalid, 2 interpolated; mask: 1 inside a masked region (u, v written 0).

Frame pair k (1-based: PIVlab's "FRAME: k", else the k-th file in natural order) is taken
between frames a = first_frame + (k - 1) pair_step and a + 1 of the movie: its vectors are
the displacement over that frame interval, the velocity at the pair's middle,

    t [s since the cut] = (a + 1/2 - cut_after_frame) frame_interval_s,

the same frame count as a Fiji table (frames up to cut_after_frame are before the cut). A
pair with a <= cut_after_frame spans the cut: skipped. Masked and invalid vectors are
dropped, interpolated ones too unless `keep_interpolated` (they are not measurements of
their own); every file's counts go to its provenance.RawFile.

Both programs give y in image coordinates (pointing down) unless told otherwise, with v in
the same axes: the radial projection (centre.py) needs only that the centre is given in the
file's axes, which holds for the estimated centre and for --centre-px of a pixel file."""

from __future__ import annotations

import glob
import math
import os
import re
from dataclasses import dataclass

import numpy as np

from .columns import InputError
from .pivlab_info import check_pairs, image_numbers, time_step
from .provenance import RawFile, decode, read_bytes, sha256_bytes
from .sniff import sniff

#: um per unit of length.
LENGTHS = {"m": 1e6, "mm": 1e3, "um": 1.0, "px": None}
_HEADING = re.compile(r"\s*([^\[\],\t]+?)\s*\[([^\]]*)\]")


@dataclass(frozen=True)
class Frames:
    """The movie's clock: frame n is at (n - cut_after_frame) frame_interval_s since frame
    cut_after_frame (the cut, or frame N when the fit places the cut after it: the radius
    table's clock); PIV pair k starts at frame first_frame + (k - 1) pair_step."""

    frame_interval_s: float
    cut_after_frame: float
    first_frame: int = 1
    pair_step: int = 1

    def __post_init__(self):
        if not (math.isfinite(self.frame_interval_s) and self.frame_interval_s > 0):
            raise InputError(
                f"--frame-interval-s {self.frame_interval_s}: the time between frames (s, > 0)"
            )
        if not (math.isfinite(self.cut_after_frame) and self.cut_after_frame >= 0):
            raise InputError(f"--cut-after-frame {self.cut_after_frame}: must be >= 0")
        for name, v, low in (
            ("--piv-first-frame", self.first_frame, 1),
            ("--piv-pair-step", self.pair_step, 1),
        ):
            if int(v) != v or v < low:
                raise InputError(f"{name} {v}: must be an integer >= {low}")

    def pair_start(self, k: int) -> int:
        return self.first_frame + (k - 1) * self.pair_step

    def pair_time(self, k: int) -> float:
        return (self.pair_start(k) + 0.5 - self.cut_after_frame) * self.frame_interval_s


@dataclass(frozen=True)
class Field:
    """Vectors of every frame pair read: time [s since the cut], position [um] in the files'
    axes, velocity [um/s]; `pair` the frame pair of each vector; `files` the records."""

    time_s: np.ndarray
    x_um: np.ndarray
    y_um: np.ndarray
    u_um_s: np.ndarray
    v_um_s: np.ndarray
    pair: np.ndarray
    files: tuple
    notes: tuple
    spacing_um: float
    #: The frame interval [s]: each pair spans one (Frames.frame_interval_s).
    interval_s: float | None = None

    @property
    def source(self) -> str:
        return os.path.commonpath([f.path for f in self.files]) if self.files else ""


def natural_key(path: str):
    return [int(p) if p.isdigit() else p.lower() for p in re.split(r"(\d+)", path)]


def list_files(where: str) -> list[str]:
    """The files of a folder (*.txt, *.csv, *.dat) or of a glob pattern, in natural order."""
    if os.path.isdir(where):
        found = [
            os.path.join(where, n)
            for n in os.listdir(where)
            if n.lower().endswith((".txt", ".csv", ".dat"))
        ]
    else:
        found = [p for p in glob.glob(where) if os.path.isfile(p)]
    if not found:
        raise InputError(
            f"{where}: no PIV files (a folder of .txt/.csv/.dat files, or a glob pattern in "
            "quotes such as 'piv/PIVlab_*.txt')"
        )
    return sorted(found, key=natural_key)


def _velocity_factor(path, unit: str, um_per_length, dt: float) -> float:
    """um/s per unit of velocity "L/s" or "L/frame"."""
    if "/" not in unit:
        raise InputError(f"{path}: velocity unit {unit!r}: expected LENGTH/s or LENGTH/frame")
    length, per = unit.split("/", 1)
    um = _length_factor(path, length, um_per_length)
    if per == "s":
        return um
    if per == "frame":
        return um / dt
    raise InputError(f"{path}: velocity unit {unit!r}: expected LENGTH/s or LENGTH/frame")


def _length_factor(path, unit: str, pixel_size_um) -> float:
    if unit not in LENGTHS:
        raise InputError(f"{path}: length unit {unit!r}: expected one of {', '.join(LENGTHS)}")
    if unit == "px":
        if pixel_size_um is None or not (math.isfinite(pixel_size_um) and pixel_size_um > 0):
            raise InputError(
                f"{path}: positions in px need the pixel size (--pixel-size-um, finite, > 0); "
                "OpenPIV files do not state their units (--piv-units, default px,px/s): files "
                "in um (a scaled run) need --piv-units um,um/s and no pixel size"
            )
        return float(pixel_size_um)
    return LENGTHS[unit]


def _numbers(path, lines, start, width, sep):
    rows, numbers = [], []
    for n, s in lines[start:]:
        cells = s.split(sep) if sep else s.split()
        if len(cells) < width:
            raise InputError(f"{path}: line {n}: {len(cells)} cells, expected {width}")
        try:
            numbers.append([float(c) for c in cells[:width]])
        except ValueError:
            raise InputError(f"{path}: line {n}: {s.strip()[:60]!r}: not numbers") from None
        rows.append(n)
    if not numbers:
        raise InputError(f"{path}: no vectors")
    return np.array(rows), np.array(numbers)


def _read_pivlab(path, lines, pixel_size_um, dt):
    """(frame pair or None, x, y, u, v [um, um/s], type) of a PIVlab file."""
    pair = None
    for _, s in lines[:2]:
        m = re.match(r"\s*FRAME:\s*(\d+)", s)
        if m:
            pair = int(m.group(1))
    k = next((i for i, (_, s) in enumerate(lines) if re.match(r"\s*x \[", s)), None)
    if k is None:
        raise InputError(
            f"{path}: a PIVlab file without column headings: export it with 'add column "
            "headers' so that its units (m or px) can be read"
        )
    names = [(m.group(1).strip(), m.group(2)) for m in _HEADING.finditer(lines[k][1])]
    keys = [n for n, _ in names]
    for want in ("x", "y", "u", "v"):
        if want not in keys:
            raise InputError(f"{path}: line {lines[k][0]}: no column {want!r} in the headings")
    units = dict(names)
    data_line = lines[k + 1][1] if k + 1 < len(lines) else ""
    sep = "," if "," in data_line else "\t" if "\t" in data_line else None
    _, a = _numbers(path, lines, k + 1, len(keys), sep)
    um = _length_factor(path, units["x"], pixel_size_um)
    if units["y"] != units["x"]:
        raise InputError(f"{path}: x in {units['x']} but y in {units['y']}")
    vel = _velocity_factor(path, units["u"], pixel_size_um, dt)
    notes = ()
    if units["u"] == "m/s":
        vel, notes = time_step(path, lines, vel, dt)
    c = {n: a[:, i] for i, n in enumerate(keys)}
    if "Vector type" not in c:  # PIVlab before March 2021: masked vectors NaN, no types
        c["Vector type"] = np.ones(len(a))
        notes = (
            *notes,
            f"{path}: no 'Vector type' column (PIVlab before March 2021): NaN vectors dropped as "
            "masked; vectors PIVlab interpolated cannot be told from measured ones: kept",
        )
    return pair, c["x"] * um, c["y"] * um, c["u"] * vel, c["v"] * vel, c["Vector type"], notes


#: The columns of an OpenPIV file without a heading (openpiv.tools.save before 0.23: x y u v
#: and the validation's mask, nonzero for an invalid vector; later: x y u v flags mask).
_OPENPIV_COLUMNS = {4: "x y u v", 5: "x y u v mask", 6: "x y u v flags mask"}


def _read_openpiv(path, lines, units, pixel_size_um, dt):
    if lines[0][1].lstrip().startswith("#"):
        names, start = lines[0][1].lstrip().lstrip("#").split(), 1
    else:
        width = len(lines[0][1].split())
        if width not in _OPENPIV_COLUMNS:
            raise InputError(
                f"{path}: line {lines[0][0]}: {width} columns and no '# x y u v ...' heading: "
                "an OpenPIV file without a heading has 4 to 6 (x y u v [flags] mask)"
            )
        names, start = _OPENPIV_COLUMNS[width].split(), 0
    missing = [n for n in ("x", "y", "u", "v") if n not in names]
    if missing:
        raise InputError(
            f"{path}: line {lines[0][0]}: no column {', '.join(missing)} in the heading "
            f"{lines[0][1].strip()!r}: expected '# x y u v flags mask' (openpiv.tools.save)"
        )
    _, a = _numbers(path, lines, start, len(names), None)
    c = {n: a[:, i] for i, n in enumerate(names)}
    length, velocity = units
    um = _length_factor(path, length, pixel_size_um)
    vel = _velocity_factor(path, velocity, pixel_size_um, dt)
    flags = c.get("flags", np.zeros(len(a)))
    mask = c.get("mask", np.zeros(len(a)))
    # as PIVlab's vector type: 0 masked, 1 valid, 2 interpolated; -1 invalid
    kind = np.where(mask != 0, 0, np.where(flags == 1, -1, np.where(flags == 2, 2, 1)))
    return None, c["x"] * um, c["y"] * um, c["u"] * vel, c["v"] * vel, kind, ()


def read_field(
    where: str,
    frames: Frames,
    *,
    pixel_size_um: float | None = None,
    program: str = "auto",
    units: tuple[str, str] = ("px", "px/s"),
    keep_interpolated: bool = False,
) -> Field:
    """Every frame pair's vectors of a folder or glob of PIVlab or OpenPIV files (module
    docstring). `units`: (length, velocity) of OpenPIV files (PIVlab files name theirs)."""
    rows, records, notes, spacing, named, seen = [], [], [], [], [], {}
    for order, path in enumerate(list_files(where), start=1):
        data = read_bytes(path, InputError)
        lines = [(n, s) for n, s in enumerate(decode(path, data, InputError), 1) if s.strip()]
        kind = sniff([s for _, s in lines[:3]]) if program == "auto" else program
        if kind == "pivlab":
            got = _read_pivlab(path, lines, pixel_size_um, frames.frame_interval_s)
        elif kind == "openpiv":
            got = _read_openpiv(path, lines, units, pixel_size_um, frames.frame_interval_s)
        else:
            raise InputError(
                f"{path}: neither a PIVlab export (info lines or 'x [m],y [m],...' headings) nor "
                "an OpenPIV file ('# x y u v flags mask'): give --piv-format (openpiv for "
                "OpenPIV files without a heading: x y u v [flags] mask), or give a glob of "
                "the export's files alone (e.g. 'folder/PIVlab_*.txt')"
            )
        pair, x, y, u, v, vtype, file_notes = got
        pair = pair or order
        if pair in seen:
            raise InputError(
                f"{path}: frame pair {pair} again (first in {seen[pair]}): one file per frame "
                "pair; a folder holding two exports (or copies) of the same pairs: give a glob "
                "of one export's files, e.g. 'folder/PIVlab_*.txt'"
            )
        seen[pair] = path
        if kind == "pivlab":
            named.append((path, pair, image_numbers(lines)))
        finite = np.isfinite(u) & np.isfinite(v) & np.isfinite(x) & np.isfinite(y)
        masked = (vtype == 0) | ~finite
        invalid = (vtype == -1) & ~masked
        interp = (vtype == 2) & ~masked
        use = ~masked & ~invalid & (~interp | keep_interpolated)
        t = frames.pair_time(pair)
        counts = {"vectors": int(x.size), "masked": int(masked.sum())}
        if kind == "openpiv":
            counts["invalid"] = int(invalid.sum())
        counts["interpolated"] = int(interp.sum())
        name = "PIVlab export" if kind == "pivlab" else "OpenPIV file"
        label = f"{name}, frame pair {pair} (frames {frames.pair_start(pair)}-" + (
            f"{frames.pair_start(pair) + 1}, t = {t:g} s)"
        )
        if frames.pair_start(pair) <= frames.cut_after_frame:
            counts["used"] = 0
            notes.append(f"{path}: frame pair {pair} starts at or before the cut: skipped")
        else:
            counts["used"] = int(use.sum())
            rows.append((np.full(use.sum(), t), x[use], y[use], u[use], v[use], pair))
            spacing.append(_spacing(x, y))
        records.append(RawFile(path, sha256_bytes(data), label, counts, file_notes))
    notes += check_pairs(named, frames)
    if not rows:
        raise InputError(f"{where}: no frame pair after the cut (frame {frames.cut_after_frame})")
    cols = [np.concatenate([r[i] for r in rows]) for i in range(5)]
    pair = np.concatenate([np.full(r[0].size, r[5]) for r in rows])
    dropped = sum(r.counts["vectors"] - r.counts["used"] for r in records)
    if dropped:
        notes.append(
            f"{where}: {dropped} of {sum(r.counts['vectors'] for r in records)} vectors "
            "dropped (masked, invalid"
            + (")" if keep_interpolated else ", interpolated)")
            + " or in frame pairs before the cut"
        )
    return Field(
        *cols,
        pair,
        tuple(records),
        tuple(notes),
        float(np.median(spacing)),
        frames.frame_interval_s,
    )


def _spacing(x, y) -> float:
    """The grid spacing [um]: the smallest step between distinct x (or y) positions."""
    steps = [np.diff(np.unique(np.round(a, 9))) for a in (x, y)]
    steps = [s[s > 0] for s in steps]
    return float(min(np.min(s) for s in steps if s.size)) if any(s.size for s in steps) else 1.0
