"""The flat pattern of a paper fan in memory linear in its divisions (once,
a (2n, 2n, 2) array of distances needed about 6 GB at 10 000 divisions, the
largest a design takes, and the build 18 GB)."""

from __future__ import annotations

import tracemalloc

import numpy as np

from onefold_cad import fold_design
from onefold_cad.fabrication.flat_pattern import flat_pattern
from onefold_cad.templates import find_template, load_template

#: Bytes of peak memory allowed per ruling end of the fan: the pattern keeps
#: a FoldRuling with its bend model for each (about 1.3 KB measured); the old
#: dense test took 3 x 16 bytes per *pair* of ends (23 MB at 400 divisions).
PER_END = 4096


def test_a_paper_fan_flat_pattern_takes_memory_linear_in_its_rulings():
    d = load_template(find_template("patkau-one-fold"))
    d = d.with_changes(model="paper", frame=d.frame.with_changes(divisions=400))
    folded = fold_design(d)
    ends = len(folded.rulings_flat)
    tracemalloc.start()  # sees numpy's buffers as well as Python's objects
    try:
        pattern = flat_pattern(d, folded)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # every division ray but the crease halves' is a fold, none is etched twice
    assert len(pattern.fold_rulings) == 2 * 400 - 2
    folds = np.array([[f.start, f.end] for f in pattern.fold_rulings])
    for seg in pattern.rulings:  # an etched ruling is none of the folds
        assert np.min(np.abs(folds - seg).max(axis=(1, 2))) > 1e-9 * d.sheet.size
    assert peak < PER_END * ends, (peak, ends)
