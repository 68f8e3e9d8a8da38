"""What a fit returns: the names (names.py), profiles (profiles.py), FitResult (result.py) and
TissueFitResult (wounds.py), the tables and CSV files (export.py), the HTML report
(report.py) and the figures (plots.py)."""
