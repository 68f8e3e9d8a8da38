"""python -m wound_opening.coupling: the coupled worked example (coupling/example.py)."""

from .example import main

main()
