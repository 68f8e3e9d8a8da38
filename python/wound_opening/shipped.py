"""The files the package ships besides Python: the native library and the FMU archives.

Each is looked for, in this order, inside the installed package (where a wheel puts them:
`wound_opening/libwound_opening.so`, `wound_opening/fmu/*.fmu`), then in the checkout an
editable install points into (`target/release/`, built by `cargo build --release`;
`target/fmu/`, written by `cargo run --release -- fmu`).
"""

from __future__ import annotations

from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
#: The repository root when the package is imported from a checkout (python/wound_opening).
CHECKOUT = PACKAGE_DIR.parents[1]
FMUS = (
    "WoundOpening.fmu",
    "WoundOpening-me.fmu",
    "WoundOpening-fmi3.fmu",
    "PurseString.fmu",
    "PurseString-fmi3.fmu",
)


def candidates(in_package: str, in_target: str) -> list[Path]:
    """Where a shipped file is looked for, first match wins: the package, then the checkout."""
    return [PACKAGE_DIR / in_package, CHECKOUT / "target" / in_target]


def first_file(paths: list[Path]) -> Path | None:
    """The first of `paths` that is a file, or None."""
    return next((path for path in paths if path.is_file()), None)


def fmu_path(name: str = "WoundOpening.fmu") -> Path:
    """The path of one of the five FMU archives, for fmpy or any other FMI master:

        from fmpy import simulate_fmu
        simulate_fmu(wound_opening.fmu_path("WoundOpening.fmu"), stop_time=100, ...)

    Raises ValueError for a name that is not one of `FMUS`, FileNotFoundError (naming the
    places looked at) when the archive is in neither place.
    """
    if name not in FMUS:
        raise ValueError(f"no FMU named {name!r}; the archives are {', '.join(FMUS)}")
    paths = candidates(f"fmu/{name}", f"fmu/{name}")
    if path := first_file(paths):
        return path
    raise FileNotFoundError(
        f"{name} not found at {' or '.join(map(str, paths))}; in a checkout, "
        f"write it with `cargo run --release -- fmu`"
    )
