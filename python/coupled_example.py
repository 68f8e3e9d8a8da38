"""The README's coupled worked example (wound opening, then purse-string closure): a thin
caller of the package's `python -m wound_opening.coupling` (wound_opening/coupling/
example.py, which the wheel ships). With --fmu-dir the archives of that folder are used,
otherwise the package's (wound_opening.fmu_path).

    python python/coupled_example.py --fmu-dir target/fmu --out out
"""

from wound_opening.coupling.example import STEP, STOP, equilibrium_radius, main

__all__ = ["STEP", "STOP", "equilibrium_radius", "main"]

if __name__ == "__main__":
    main()
