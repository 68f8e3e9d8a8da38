"""Reading CSV files as labs export them, with one-line errors naming the file, the FILE LINE
(1-based, counting the header, comment and blank lines) and the problem.

pandas does the reading: a UTF-8 byte-order mark is dropped (`encoding="utf-8-sig"`), lines
starting with `#` are comments, blank lines are skipped. The separator is the first of tab,
`;` and `,` found in the header line (the header names the columns, so it has one separator
fewer than columns and no decimals to confuse it), or the one an Excel `sep=;` line before
the header names. Decimal commas are read where they are
unambiguous: in a file separated by `;` or tab, numeric cells with a `,` and none with a `.`;
a `,`-separated file has `.` decimals."""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass

import numpy as np

MIN_POINTS = 5
COMMENT = "#"


class InputError(ValueError):
    """Bad input: the message is one line, naming the file, the line and the problem."""


@dataclass(frozen=True)
class Table:
    """The requested columns as float arrays; `lines[k]` is the file line of data row k."""

    path: str
    columns: dict
    lines: np.ndarray

    def line(self, k: int) -> int:
        return int(self.lines[k])


def _text(path: str) -> str:
    """The file's text, read once (a UTF-8 byte-order mark dropped)."""
    try:
        with open(path, encoding="utf-8-sig", newline="") as f:
            return f.read()
    except OSError as e:
        raise InputError(f"{path}: cannot read the file ({e.strerror})") from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a UTF-8 text (CSV) file") from None


def _is_data(text: str) -> bool:
    s = text.strip()
    return bool(s) and not s.startswith(COMMENT)


def _declared_separator(text: str) -> str | None:
    """The separator an Excel `sep=X` line declares (quoted or not), else None."""
    s = text.strip().strip('"')
    return s[4] if len(s) == 5 and s.lower().startswith("sep=") else None


def _refuse_piv(path, first_lines) -> None:
    """A PIVlab or OpenPIV export is a vector field, not a table of these columns."""
    from .sniff import sniff

    program = sniff(first_lines)
    if program:
        raise InputError(
            f"{path}: a {'PIVlab' if program == 'pivlab' else 'OpenPIV'} vector field, not a "
            "profile table: give its folder with --piv (docs/fitting.md, 'Lab files')"
        )


def read_columns(
    path: str,
    columns: tuple[str, ...],
    *,
    time_column: str | None = None,
    cut_time: float = 0.0,
    ascending: bool = True,
    min_rows: int = MIN_POINTS,
    optional: tuple[str, ...] = (),
    label: str | None = None,
    check_times=None,
) -> Table:
    """The named columns of a CSV file, checked: every cell a finite number, the time column
    (default: the first of `columns`) >= `cut_time` and (if `ascending`) non-decreasing, at least
    `min_rows` rows. Columns in `optional` are read too when the header has them. `label`: a
    column of names (kept as text, none empty; a wound id): times ascend within each name.
    `check_times(t)`: a check of every row's time (in the file's unit) before any row is
    refused as before the cut (lab_files.check_cut: a cut time in another unit). The file is
    read once."""
    import pandas as pd

    time_column = time_column or columns[0]
    content = _text(path)
    text = content.splitlines()
    numbered = [(n, s) for n, s in enumerate(text, start=1) if _is_data(s)]
    if not numbered:
        raise InputError(f"{path}: no header: expected the columns {', '.join(map(repr, columns))}")
    declared = _declared_separator(numbered[0][1])
    if declared is not None:
        numbered = numbered[1:]
        if not numbered:
            raise InputError(
                f"{path}: no header after the 'sep=' line: expected the columns "
                f"{', '.join(map(repr, columns))}"
            )
    header_line, header_text = numbered[0]
    _refuse_piv(path, text[:3])
    sep = declared or next((c for c in ("\t", ";", ",") if c in header_text), ",")
    body = numbered[1:]
    try:
        frame = pd.read_csv(
            io.StringIO(content),
            sep=sep,
            comment=COMMENT,
            dtype=str,
            na_filter=False,
            skip_blank_lines=True,
            skipinitialspace=True,
            engine="python",
            skiprows=range(header_line - 1),
        )
    except pd.errors.ParserError:
        frame = None
    width = len(next(csv.reader([header_text], delimiter=sep)))
    for n, s in body:  # pandas fills short rows and refuses long ones without a usable line number
        cells = len(next(csv.reader([s], delimiter=sep)))
        if cells != width:
            hint = (
                (
                    " (with ',' as the separator a decimal comma splits a number in two: separate "
                    "the "
                    "columns with ';' or a tab)"
                )
                if sep == "," and cells > width
                else ""
            )
            raise InputError(
                f"{path}: line {n}: {cells} cell{'' if cells == 1 else 's'}, expected {width} as "
                f"in the header (line "
                f"{header_line}){hint}"
            )
    if frame is None or len(frame) != len(body):
        raise InputError(f"{path}: cannot be read as a table separated by {sep!r}")
    frame.columns = [
        "(blank: row numbers)" if str(c).startswith("Unnamed: ") else str(c).strip()
        for c in frame.columns
    ]
    header = list(frame.columns)
    for name in columns + ((label,) if label else ()):
        if name not in header:
            raise InputError(
                f"{path}: line {header_line}: no column {name!r} (the header has "
                f"{', '.join(map(repr, header))})"
            )
    columns = tuple(columns) + tuple(
        name for name in optional if name in header and name not in columns
    )
    cells = {name: frame[name].astype(str).str.strip() for name in columns}
    lines = np.array([n for n, _ in body], dtype=int)
    decimal_comma = False
    if sep != ",":
        comma = [
            (lines[i], name)
            for name in columns
            for i in np.flatnonzero(cells[name].str.contains(",", regex=False))
        ]
        dot = [
            (lines[i], name)
            for name in columns
            for i in np.flatnonzero(cells[name].str.contains(".", regex=False))
        ]
        if comma and dot:
            (lc, nc), (ld, nd) = min(comma), min(dot)
            raise InputError(
                f"{path}: both decimal commas (line {lc}, {nc}) and decimal points (line {ld}, "
                f"{nd}): "
                "ambiguous, use one of them"
            )
        decimal_comma = bool(comma)
    data = {}
    for name in columns:
        raw = cells[name]
        values = pd.to_numeric(
            raw.str.replace(",", ".", regex=False) if decimal_comma else raw, errors="coerce"
        ).to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            k = bad[0]
            cell = raw.iloc[k]
            what = (
                "is empty"
                if cell == ""
                else "is not a finite number"
                if np.isinf(values[k]) or cell.lower().lstrip("+-") == "nan"
                else "is not a number"
            )
            raise InputError(f"{path}: line {lines[k]}: {name} = {raw.iloc[k]!r} {what}")
        data[name] = values
    ids = np.zeros(len(lines), dtype=int)
    if label:
        names = frame[label].astype(str).str.strip()
        empty = np.flatnonzero(names == "")
        if empty.size:
            raise InputError(
                f"{path}: line {lines[empty[0]]}: {label} is empty (every row needs its name)"
            )
        data[label] = names.to_numpy(dtype=str)
        ids = pd.factorize(names)[0]
    t = data[time_column]
    if check_times is not None:
        check_times(t)
    if t.size and np.any(t < cut_time):
        k = int(np.flatnonzero(t < cut_time)[0])
        raise InputError(
            f"{path}: line {lines[k]}: {time_column} = {t[k]:g} is before the cut at {cut_time:g} "
            "(times are since the cut, or from the cut time given; remove the rows before the cut)"
        )
    back = [
        (rows[j + 1], rows[j])
        for rows in (np.flatnonzero(ids == g) for g in range(ids.max(initial=0) + 1))
        for j in np.flatnonzero(np.diff(t[rows]) < 0)[:1]
    ]
    if ascending and back:
        k, prev = min(back)
        raise InputError(
            f"{path}: line {lines[k]}: {time_column} = {t[k]:g} is before line {lines[prev]}'s "
            f"{t[prev]:g} (times must be ascending{' within each ' + label if label else ''})"
        )
    if t.size < min_rows:
        raise InputError(f"{path}: {t.size} data rows: too few points, need at least {min_rows}")
    return Table(path, data, lines)


def float_list(text: str, what: str) -> list[float]:
    """A comma-separated list of finite numbers (for --lambda 0.1,1,10 and the like)."""
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise InputError(f"{what}: {text!r} is not a comma-separated list of numbers") from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError(f"{what}: {text!r} must list at least one finite number")
    return values
