"""The command line `wound-opening` (fit, sweep, simulate) in one place: its options
(options.py), what each command does, with the frames to fit, the recording's checks and the
settings a fit's report prints (commands.py), and the lab files' options and readers
(lab.py)."""

from .options import main, parser

__all__ = ["main", "parser"]
