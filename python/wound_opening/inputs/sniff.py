"""Which PIV program wrote a text file, from its first lines (no imports of the readers:
columns.py asks it to refuse a vector field given as a table)."""

from __future__ import annotations

import re


def sniff(first_lines: list[str]) -> str | None:
    """'pivlab', 'openpiv' or None from a file's first lines."""
    head = [s.strip() for s in first_lines if s.strip()][:3]
    if not head:
        return None
    if head[0].startswith("PIVlab") or any(s.startswith("FRAME:") for s in head):
        return "pivlab"
    if any(re.match(r"x \[(m|px)\]", s) for s in head):
        return "pivlab"
    # openpiv.tools.save: "x y u v flags mask" (0.24.4 on), "x y u v mask" (0.23), "x y u v
    # s2n mask" (late 2020)
    if re.fullmatch(r"#\s*x\s+y\s+u\s+v\s+((flags|s2n)\s+)?mask", head[0]):
        return "openpiv"
    return None
