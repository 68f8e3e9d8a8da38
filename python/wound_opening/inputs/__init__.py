"""What a fit reads: a wound's radius series and velocity profile (series.py), the lab's CSV
files in their units (lab_files.py) over one column reader that refuses with the file line
(columns.py, InputError)."""
