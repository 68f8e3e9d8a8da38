"""The recording's settings, as a report prints them: taken from the inputs (the command
line's options, cli/commands.py, and the series read), not from the command line's text.

`FitResult.settings` and `TissueFitResult.settings` hold a dict with these keys (each may be
missing or None: not given):

    cut_time          float   the time of the cut in the files' time unit (subtracted)
    cut               str     how the cut was placed on a movie's clock (frames): fitted
                      between two frames, given, or at a frame (cli/lab.py, Cut)
    time_unit         str     "s", "ms" or "min": the files' time unit
    length_unit       str     "um" or "px": the files' length unit
    pixel_size_um     float   um per pixel (with length_unit "px")
    frame_interval_s  float   s between frames (a frame column read as times)
    centre_um         [x, y]  the wound centre given in um (PIV fields)
    centre_px         [x, y]  the wound centre given in px
    outer_radius_um   list    the outer radius of each wound's tissue
    files             list of {"wound": name or None, "data": "radius" or "velocity
                      profile", "path": str, "columns": {role: column name}}
    reader            dict    a lab-file reader's own settings (Fiji, PIVlab, OpenPIV:
                      any keys; printed as given, one row per key)
    raw_files         list of {"path", "sha256", "kind", "counts", "notes"}: the raw lab
                      files read (a Fiji table, each PIV file) and the steps made of them
                      (rings, the wound centre), as the report's "Raw files read" lists
                      them: what was skipped and why, the centre with its uncertainty

Other keys are printed as given, after these.
"""

from __future__ import annotations

#: The keys in the order a report prints them, with their labels.
LABELS = {
    "cut_time": "cut time (files' time unit)",
    "cut": "cut",
    "time_unit": "time unit",
    "length_unit": "length unit",
    "pixel_size_um": "pixel size (µm)",
    "frame_interval_s": "frame interval (s)",
    "centre_um": "wound centre (µm)",
    "centre_px": "wound centre (px)",
    "outer_radius_um": "outer radius (µm)",
}


def raw_files(series) -> list:
    """The raw files behind `series` (inputs.provenance.RawFile; None skipped) as dicts."""
    return [
        {
            "path": f.path,
            "sha256": f.sha256,
            "kind": f.kind,
            "counts": dict(f.counts),
            "notes": list(f.notes),
        }
        for s in series
        if s is not None
        for f in getattr(s, "files", ())
    ]


def rows(settings: dict) -> list:
    """(label, value as text) of the settings other than the files, in LABELS' order then
    the rest; the reader's settings one row per key."""
    out = []

    def text(v) -> str:
        if isinstance(v, (list, tuple)):
            return ", ".join(text(x) for x in v)
        return f"{v:g}" if isinstance(v, float) else str(v)

    for key, label in LABELS.items():
        if settings.get(key) is not None:
            out.append((label, text(settings[key])))
    for key, value in settings.items():
        if key in LABELS or key in ("files", "raw_files") or value is None:
            continue
        if isinstance(value, dict):
            out += [(f"{key}: {k}", text(v)) for k, v in value.items() if v is not None]
        else:
            out.append((key, text(value)))
    return out


def file_rows(settings: dict) -> list:
    """(wound, data, path, columns as text) of each file the settings name."""
    return [
        (
            str(f.get("wound") or "—"),
            str(f.get("data", "")),
            str(f.get("path", "")),
            ", ".join(f"{k}: {v}" for k, v in (f.get("columns") or {}).items()),
        )
        for f in settings.get("files", [])
    ]
