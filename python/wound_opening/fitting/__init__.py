"""The fit: weighted residuals and Jacobian of one wound (objective.py) and of several wounds
of one tissue (wounds.py), the user's constraints (parameters.py), starts (starts.py), local
fits (local.py), profile likelihood intervals (intervals.py, derived.py), the time-scale check
(plausibility.py), and the pipelines `fit` (single.py) and `fit_wounds` (wounds.py)."""
