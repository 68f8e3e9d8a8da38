"""Reading the command line's CSV files with one-line errors naming the file, the row and
the problem (row 1 is the first data row, under the header)."""

from __future__ import annotations

import csv
import math

import numpy as np

MIN_POINTS = 5


class InputError(ValueError):
    """Bad input: the message is one line, naming the file, the row and the problem."""


def read_columns(path: str, columns: tuple[str, ...], *, time_column: str = "time_s",
                 ascending: bool = True, min_rows: int = MIN_POINTS, optional: tuple[str, ...] = ()) -> dict[str, np.ndarray]:
    """The named columns of a CSV file as float arrays, checked: every cell a finite number,
    times >= 0 and (if `ascending`) non-decreasing, at least `min_rows` rows. Columns in
    `optional` are read too when the header has them."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise InputError(f"{path}: cannot read the file ({e.strerror})") from None
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a text (CSV) file") from None
    if not rows:
        raise InputError(f"{path}: empty file: expected the header {','.join(columns)}")
    header = [h.strip() for h in rows[0]]
    for name in columns:
        if name not in header:
            raise InputError(f"{path}: missing column {name!r} (header is {','.join(header)!r}; expected {','.join(columns)!r})")
    columns = tuple(columns) + tuple(name for name in optional if name in header)
    index = [header.index(name) for name in columns]
    data = {name: [] for name in columns}
    body = [(n, r) for n, r in enumerate(rows[1:], start=1) if any(cell.strip() for cell in r)]
    for n, row in body:
        if len(row) != len(header):
            raise InputError(f"{path}: row {n}: {len(row)} cells, expected {len(header)} (as in the header)")
        for name, i in zip(columns, index):
            cell = row[i].strip()
            try:
                value = float(cell)
            except ValueError:
                raise InputError(f"{path}: row {n}: {name} = {cell!r} is not a number") from None
            if not math.isfinite(value):
                raise InputError(f"{path}: row {n}: {name} = {cell} is not a finite number")
            data[name].append(value)
        t = data[time_column][-1]
        if t < 0:
            raise InputError(f"{path}: row {n}: {time_column} = {t:g} is negative (times are since the cut)")
        if ascending and len(data[time_column]) > 1 and t < data[time_column][-2]:
            raise InputError(f"{path}: row {n}: {time_column} = {t:g} is before row {n - 1}'s "
                             f"{data[time_column][-2]:g} (times must be ascending)")
    if len(body) < min_rows:
        raise InputError(f"{path}: {len(body)} data rows: too few points, need at least {min_rows}")
    return {name: np.asarray(values) for name, values in data.items()}


def float_list(text: str, what: str) -> list[float]:
    """A comma-separated list of finite numbers (for --lambda 0.1,1,10 and the like)."""
    try:
        values = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise InputError(f"{what}: {text!r} is not a comma-separated list of numbers") from None
    if not values or not all(math.isfinite(v) for v in values):
        raise InputError(f"{what}: {text!r} must list at least one finite number")
    return values
