"""The fit: the coordinates each problem declares by name (parameters.py), weighted residuals
and Jacobian of one wound (objective.py) and of several wounds of one tissue (wounds.py),
the user's knowledge read against those coordinates (parameters.py), starts (starts.py),
local fits (local.py), the stages and verdict (stages.py), the optimum and its profile
intervals (optimum.py over the walker intervals.py; derived.py and wound_profiles.py for
quantities walked in their own coordinate), the time-scale check (plausibility.py), and the
pipelines `fit` (single.py) and `fit_wounds` (wounds.py)."""
