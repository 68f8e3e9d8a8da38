"""`python -m wound_opening.cli`: the command line."""

import sys

from .options import main

sys.exit(main())
