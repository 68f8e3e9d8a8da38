"""From a fit to a simulation: the WoundOpening FMU's start values, and a co-simulation
master coupling the wound to a closure model (the PurseString FMU), both shipped in the
wheel with the archives.

    fmu_start_values(...)      start values by the FMU's names (start.py; also
                               wound_opening.fmu_start_values)
    loop.couple(...)           the fmpy master: WoundOpening + a closure FMU (PurseString, or
                               any other named by a loop.Closure), Gauss-Seidel (needs fmpy);
                               loop.observed_order, the worked example's values
    ssp_file.build(...)        an SSP file of WoundOpening and a closure FMU (docs/closure.md;
                               `python python/coupling/ssp.py build`)
    python -m wound_opening.coupling --out out
                               the worked example: opening, then purse-string closure
                               (example.py; CSV files and a chart)
"""

from .start import fmu_start_values

__all__ = ["fmu_start_values"]
