"""Fiji/ImageJ Results tables (Analyze > Measure, saved as .csv or .txt): one row per
measurement, the wound's area and the frame it was measured in.

ImageJ's ResultsTable writes a first column with a blank heading (" ") holding 1-based row
numbers when row numbers are shown, then "Label" when labels are recorded, then the measured
columns ("Area", "Perim.", ..., "Slice" or "Frame"), separated by "," in .csv files and by tabs
otherwise; a failed measurement is written "NaN".

    radius [um] = sqrt(Area / pi) x (1 for um^2, pixel_size_um for px^2)
    time [s] = (frame - cut_after_frame) x frame_interval_s

counted from the cut, or from frame N when `cut_after_frame` = N and the fit places the cut
after it (the nuisance cut_s, cli/lab.py). Frames up to and including `cut_after_frame` were
recorded before the cut: their rows are
skipped (whatever they hold: Area 0, empty, a pre-cut measurement). After the cut a row with
no area (empty, NaN, 0) is a frame where the tracking failed: skipped. Both are counted in
the file's record (provenance.RawFile) and its notes, which the report and the command line
show. A column that holds a radius (or a diameter) instead of an area is refused, and so is a
frame measured twice (two ROIs per slice: never averaged) and a pixel size whose radius is
no laser wound's (nm or mm typed as um); rows in another order are sorted by frame; the rows
Analyze > Summarize appends (labels Mean, SD, Min, Max) are skipped and counted."""

from __future__ import annotations

import csv
import math
from dataclasses import replace

import numpy as np

from .columns import MIN_POINTS, InputError
from .lab_files import RADIUS_UM, check_pixel_size
from .provenance import RawFile, decode, read_bytes, sha256_bytes
from .series import RadiusSeries

ROW_NUMBERS = "(row numbers)"
#: The labels of the rows Analyze > Summarize appends (ImageJ's ResultsTable summary).
SUMMARY = ("Mean", "SD", "Min", "Max")
PERIMETER = "Perim."
#: 4 pi Area / Perim.^2 (circularity) is 1 for a circle and less for any other shape; a real
#: wound outline is above this (a rough ellipse of axis ratio 10 is 0.35).
MIN_CIRCULARITY = 0.2
#: A round wound's outline is above this circularity (a thresholded disk's outline gives
#: 0.85-0.95; an exact ellipse of axis ratio 2 is 0.84): below it the threshold took in more
#: than the wound. On the rendered movies of python/bench/lab_coverage.py the outlines of 4
#: draws in 20 had a median circularity of 0.30-0.59, their edge 0.21-1.02 um (median over
#: the frames) outside the true one: the neighbouring cells' interiors taken in; the 16
#: others 0.73-0.91, within 0.28 um of it (docs/fitting.md, "Outlines that are not round").
ROUND_CIRCULARITY = 0.65
#: More than this fraction of the outlines below ROUND_CIRCULARITY (their median below it)
#: is a warning; fewer, a note (one outline in three took in a cell in a draw that held every
#: value).
NOT_ROUND_SHARE = 0.5
#: The pixel [um] an area table in um^2 is taken to have been measured on (a laser-ablation
#: movie's: 0.1-0.3 um): the outline offset's prior sd (cli/commands.py) and the noise floor.
PIXEL_UM = 0.2
#: A thresholded outline's radius error is taken as no less than this many pixels: its
#: error is no independent noise but a slow drift plus the cells an outline takes in or lets
#: go (0.018-0.18 um on rendered movies, docs/fitting.md "The outline's noise floor"), which
#: the residuals of a fit whose opening spans a few frames absorb (estimated 0.008 um there).
OUTLINE_FLOOR_PX = 0.5
#: A wound smaller than this radius (in pixels) cannot be outlined on an image.
MIN_RADIUS_PX = 5.0
#: ... and smaller than this radius in um (laser cuts are microns wide).
MIN_RADIUS_UM = RADIUS_UM[0]


def _frame_interval(value) -> float:
    if value is None or not (math.isfinite(value) and value > 0):
        raise InputError(
            f"--frame-interval-s {value}: a Fiji table numbers frames, the time between frames "
            "(s, finite, > 0) turns them into times"
        )
    return float(value)


def _cut_frame(value) -> float:
    if value is None or not (math.isfinite(value) and value >= 0):
        raise InputError(
            f"--cut-after-frame {value}: give the last frame recorded before the cut (>= 0; 0 "
            "when the first frame is after the cut; 3.2 for a cut 0.2 frame intervals after "
            "frame 3)"
        )
    return int(value) if value == int(value) else float(value)


def _um_per_length(path, length_unit: str, pixel_size_um) -> float:
    if length_unit == "um":
        if pixel_size_um is not None:
            raise InputError(
                f"{path}: a pixel size is given but the length unit is um: give --length-unit "
                "px if the areas are in px^2; if the pixel size was given for OpenPIV files, "
                "files in um need none: give --piv-units um,um/s instead"
            )
        return 1.0
    if length_unit != "px":
        raise InputError(f"{path}: length unit {length_unit!r}: expected um or px")
    if pixel_size_um is None or not (math.isfinite(pixel_size_um) and pixel_size_um > 0):
        raise InputError(
            f"{path}: length unit px needs the pixel size in um (finite, > 0), got {pixel_size_um}"
        )
    return float(pixel_size_um)


def header_names(cells) -> list[str]:
    """The header's names, the blank first heading named ROW_NUMBERS (not 'Unnamed: 0')."""
    names = [c.strip() for c in cells]
    return [ROW_NUMBERS if (k == 0 and n == "") else n for k, n in enumerate(names)]


def _number(path, n, name, text, *, missing_ok=False):
    s = text.strip()
    if s == "" or s.lower() == "nan":
        if missing_ok:
            return math.nan
        raise InputError(f"{path}: line {n}: {name} = {text!r} is not a number")
    try:
        return float(s)
    except ValueError:
        raise InputError(f"{path}: line {n}: {name} = {text!r} is not a number") from None


def read_fiji(
    path: str,
    *,
    area_col: str = "Area",
    frame_col: str | None = None,
    frame_interval_s: float | None = None,
    cut_after_frame: float | None = None,
    length_unit: str = "um",
    pixel_size_um: float | None = None,
    noise_um: float | None = None,
) -> RadiusSeries:
    """The wound radius series of a Fiji Results table (module docstring). `frame_col`: the
    frame column (default: Frame, else Slice: ImageJ writes Frame (time) and Slice (z) for a
    hyperstack, Slice alone for a plain stack); `length_unit`: of the area's length (um for
    um^2, px for px^2 with `pixel_size_um`). The series' `files` holds the file's record."""
    dt = _frame_interval(frame_interval_s)
    cut = _cut_frame(cut_after_frame)
    um = _um_per_length(path, length_unit, pixel_size_um)
    data = read_bytes(path, InputError)
    text = decode(path, data, InputError)
    numbered = [(n, s) for n, s in enumerate(text, start=1) if s.strip()]
    if not numbered:
        raise InputError(f"{path}: empty: expected a Fiji Results table with the column {area_col}")
    header_line, header = numbered[0]
    # ImageJ writes "," (.csv) or tabs; a table re-saved by a spreadsheet in a locale with a
    # decimal comma has ";" between cells and "," in numbers
    sep = "\t" if "\t" in header else ";" if ";" in header and "," not in header else ","
    names = header_names(next(csv.reader([header], delimiter=sep)))
    if frame_col is None:
        frame_col = next((c for c in ("Frame", "Slice") if c in names), "Slice")
    for name, option in ((area_col, "--area-col"), (frame_col, "--frame-col")):
        if name not in names:
            raise InputError(
                f"{path}: line {header_line}: no column {name!r} ({option}); the header has "
                f"{', '.join(map(repr, names))}"
                + (
                    ". ImageJ writes the frame (Slice, or Frame for a hyperstack) with "
                    "Analyze > Set Measurements > Stack position checked: measure again with it"
                    if option == "--frame-col" and not {"Slice", "Frame"} & set(names)
                    else ""
                )
            )
    ia, i_f = names.index(area_col), names.index(frame_col)
    ip = names.index(PERIMETER) if PERIMETER in names else None
    il = names.index("Label") if "Label" in names else None
    rows, summary = [], []  # (line, frame, area, perimeter); lines of summary rows
    for n, s in numbered[1:]:
        cells = next(csv.reader([s], delimiter=sep))
        if sep == ";":
            cells = [c.replace(",", ".") for c in cells]
        if len(cells) != len(names):
            raise InputError(
                f"{path}: line {n}: {len(cells)} cells, expected {len(names)} as in the header "
                f"(line {header_line})"
            )
        if il is not None and cells[il].strip() in SUMMARY:
            summary.append(n)
            continue
        frame = _number(path, n, frame_col, cells[i_f])
        if frame != int(frame) or frame < 0:
            raise InputError(f"{path}: line {n}: {frame_col} = {cells[i_f]!r}: not a frame number")
        area = _number(path, n, area_col, cells[ia], missing_ok=True)
        perim = math.nan if ip is None else _number(path, n, PERIMETER, cells[ip], missing_ok=True)
        rows.append((n, int(frame), area, perim))
    series = _series(path, data, rows, area_col, frame_col, dt, cut, um, length_unit, noise_um)
    if summary:
        f = series.files[0]
        note = (
            f"{path}: {len(summary)} summary rows (Analyze > Summarize: labels "
            f"{', '.join(SUMMARY)}; lines {summary[0]}-{summary[-1]}) skipped"
        )
        f = replace(f, counts={"summary rows": len(summary), **f.counts}, notes=(note, *f.notes))
        series = replace(series, files=(f,))
    return series


def _series(path, data, rows, area_col, frame_col, dt, cut, um, length_unit, noise_um):
    first = {}
    for n, f, _, _ in rows:
        if f in first:
            raise InputError(
                f"{path}: line {n}: {frame_col} {f} measured again (first on line {first[f]}): "
                "one measurement per frame; several ROIs or wounds measured in one frame, or a "
                "table appended twice, cannot be told apart: save one Results table per wound "
                "(Clear Results between wounds)"
            )
        first[f] = n
    unsorted = any(rows[k][1] < rows[k - 1][1] for k in range(1, len(rows)))
    rows = sorted(rows, key=lambda r: r[1])  # measured in any order: the frame gives the time
    before = [r for r in rows if r[1] <= cut]
    after = [r for r in rows if r[1] > cut]
    failed = [r for r in after if not (math.isfinite(r[2]) and r[2] > 0)]
    used = [r for r in after if math.isfinite(r[2]) and r[2] > 0]
    bad = [r for r in used if r[2] < 0]
    if bad:
        raise InputError(f"{path}: line {bad[0][0]}: {area_col} = {bad[0][2]:g} < 0")
    if len(used) < MIN_POINTS:
        raise InputError(
            f"{path}: {len(used)} frames after the cut (frame {cut:g}) with an area: too few, need "
            f"at least {MIN_POINTS} ({len(before)} rows before the cut, {len(failed)} without an "
            "area)"
            + (
                f"; the last frame is {rows[-1][1]}: --cut-after-frame is the number of the last "
                "frame before the cut, not a time"
                if rows and cut >= rows[-1][1]
                else ""
            )
        )
    lines = np.array([r[0] for r in used], dtype=int)
    area = np.array([r[2] for r in used])
    perim = np.array([r[3] for r in used])
    _check_area(path, area_col, area, perim, lines, um, length_unit)
    radius = np.sqrt(area / math.pi) * um
    frames = np.array([r[1] for r in used], dtype=float)
    times = (frames - cut) * dt
    doubts, round_notes = outline_warnings(path, frame_col, frames, area, perim)
    notes = [f"{path}: rows not in {frame_col} order: sorted by {frame_col}"] if unsorted else []
    notes += round_notes
    if before:
        notes.append(
            f"{path}: {len(before)} rows at or before frame {cut:g} (before the cut) skipped"
        )
    if failed:
        listed = ", ".join(str(r[1]) for r in failed[:10]) + (", ..." if len(failed) > 10 else "")
        notes.append(
            f"{path}: {len(failed)} frames after the cut without an area (NaN, empty or 0: "
            f"the tracking failed) skipped: {frame_col} {listed}"
        )
    record = RawFile(
        path,
        sha256_bytes(data),
        "Fiji Results table",
        {
            "rows": len(rows),
            "before the cut": len(before),
            "tracking failed": len(failed),
            "used": len(used),
        },
        tuple(notes),
    )
    return RadiusSeries(
        times,
        radius,
        noise_um,
        source=path,
        lines=lines,
        files=(record,),
        serial=True,
        warnings=tuple(doubts),
        noise_floor_um=None if noise_um is not None else noise_floor(um, length_unit),
        noise_floor_said="half a pixel",
    )


def noise_floor(um_per_length: float, length_unit: str) -> float:
    """The radius noise's floor [um]: OUTLINE_FLOOR_PX of the table's pixel (PIXEL_UM for
    a table in um^2)."""
    return OUTLINE_FLOOR_PX * (um_per_length if length_unit == "px" else PIXEL_UM)


def circularity(area, perim) -> tuple[np.ndarray, np.ndarray]:
    """(the rows with a perimeter, 4 pi Area / Perim.^2 of those rows)."""
    has_p = np.isfinite(perim) & (perim > 0)
    return has_p, 4 * math.pi * area[has_p] / perim[has_p] ** 2


def outline_warnings(path, frame_col, frames, area, perim) -> tuple[list, list]:
    """(warnings, notes) on outlines that are not round (ROUND_CIRCULARITY): the radius
    sqrt(Area / pi) of such an outline is not the wound edge's, and its error, which
    follows the cells the threshold took in, is neither small nor a constant offset."""
    has_p, circ = circularity(area, perim)
    low = np.flatnonzero(circ < ROUND_CIRCULARITY)
    if low.size == 0:
        return [], []
    which = frames[has_p][low]
    listed = ", ".join(f"{f:g}" for f in which[:8]) + (", ..." if which.size > 8 else "")
    said = (
        f"{low.size} of {circ.size} outlines are not round in {path} (4 pi Area / Perim.^2 below "
        f"{ROUND_CIRCULARITY}, median {np.median(circ):.2f}; a round wound's outline is "
        f"0.85-0.95): {frame_col} {listed}"
    )
    if low.size <= NOT_ROUND_SHARE * circ.size:
        return [], [said]
    return [
        said + ": the threshold took in more than the wound (the neighbouring cells' "
        "interiors, debris), so the radius from the area is not the edge's and its error "
        "follows the cells taken in: R0, sigma and the material values are biased with "
        "intervals that do not show it. Look at the outlines (Analyze Particles, Show: "
        "Outlines) and segment again (a smaller region around the wound, another threshold "
        "method, a closing of the mask)"
    ], []


def _check_area(path, area_col, area, perim, lines, um, length_unit) -> None:
    """Refuse a column that holds a radius or a diameter instead of an area."""
    has_p, circ = circularity(area, perim)
    if np.count_nonzero(has_p) >= max(3, area.size // 2):
        median = float(np.median(circ))
        if median < MIN_CIRCULARITY:
            r_if = float(np.median(area[has_p]))
            raise InputError(
                f"{path}: {area_col} does not hold an area: 4 pi {area_col} / {PERIMETER}^2 = "
                f"{median:.3g} (median), but an outline has at most 1 (a circle) and a wound more "
                f"than {MIN_CIRCULARITY}; with {PERIMETER} = 2 pi r the column holds about r "
                f"(median {r_if:.4g}): a radius or a diameter. Measure Area in Fiji, or give a "
                "radius column to the plain reader (--radius-col)"
            )
        if median > 1.05:
            k = int(np.flatnonzero(has_p)[int(np.argmax(circ))])
            raise InputError(
                f"{path}: line {lines[k]}: {area_col} = {area[k]:g} with {PERIMETER} = "
                f"{perim[k]:g}: 4 pi {area_col} / {PERIMETER}^2 = {circ.max():.3g} > 1, no outline "
                f"has that: the two columns are not the area and perimeter of one outline"
            )
    radius_len = float(np.median(np.sqrt(area / math.pi)))
    if length_unit == "px" and radius_len < MIN_RADIUS_PX:
        raise InputError(
            f"{path}: {area_col} median {np.median(area):.4g} px^2 is a radius of "
            f"{radius_len:.3g} px: no wound that small can be outlined; does {area_col} hold a "
            f"radius? (a radius needs the plain reader, --radius-col)"
        )
    if length_unit == "px":
        check_pixel_size(path, f"{area_col} median {np.median(area):.4g} px^2", radius_len, um)
    if length_unit == "um" and radius_len * um < MIN_RADIUS_UM:
        raise InputError(
            f"{path}: {area_col} median {np.median(area):.4g} um^2 is a radius of "
            f"{radius_len:.3g} um: smaller than a laser cut; is the area in px^2 (--length-unit "
            f"px --pixel-size-um) or does {area_col} hold a radius?"
        )
