"""From a fit to a simulation: the WoundOpening FMU's start values, and a co-simulation
master coupling the wound to a closure model (the PurseString FMU), both shipped in the
wheel with the archives.

    fmu_start_values(...)      start values by the FMU's names (start.py; also
                               wound_opening.fmu_start_values)
    loop.couple(...)           the fmpy master: WoundOpening + PurseString, Gauss-Seidel
                               (needs fmpy); loop.observed_order, the worked example's values
    python -m wound_opening.coupling --out out
                               the worked example: opening, then purse-string closure
                               (example.py; CSV files and a chart)
"""

from .start import fmu_start_values

__all__ = ["fmu_start_values"]
