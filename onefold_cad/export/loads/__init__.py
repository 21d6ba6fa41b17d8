"""The files of ``onefold loads``: ``cases_csv`` (NAME-loads.csv, one row per
load case) and ``picture`` (NAME-loads.png, the governing case's deformed
form coloured by utilisation, the feet's reactions drawn)."""
