"""The files of ``onefold loads``:

- :mod:`.cases_csv`: NAME-loads.csv, one row per load case;
- :mod:`.picture`: NAME-loads.png, the governing case's deformed form
  coloured by utilisation, the feet's reactions drawn.
"""
