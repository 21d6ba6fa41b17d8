"""NAME.fold: the design as a FOLD 1.2 file for origami tools.

- :mod:`.file`: the FOLD file: frames, crease pattern, fold angles.
- :mod:`.fan`: the paper fan a FOLD file folds, graded towards the crease.
- :mod:`.mesh`: the fan's crease pattern triangulated for simulators.
"""
