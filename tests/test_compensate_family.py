"""benchmarks/compensate_family.py's grid and summary (no simulation)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import compensate_family as cf  # noqa: E402


def test_grid_includes_its_stop_and_reads_lists() -> None:
    assert cf.grid("30:40:2") == pytest.approx([30, 32, 34, 36, 38, 40])
    assert cf.grid("30:31:0.5") == pytest.approx([30, 30.5, 31])
    assert cf.grid("26,29.5") == pytest.approx([26, 29.5])


def test_summary_names_the_smallest_max_and_a_fifth_of_the_start() -> None:
    start = (30.0, 30.0, 0.0, 300.0, 100.0, 2.0, 0.0)
    rows = [
        (30.0, 32.0, 0.0, 250.0, 60.0, 1.0, 0.0),
        (32.0, 30.0, 0.5, 180.0, 70.0, 1.0, 0.0),  # the smallest max
        (32.0, 32.0, 0.0, None, None, 1.0, 0.0),  # falls
    ]
    text = cf.summary("t", "coarse", "mm", start, rows)
    row = text.splitlines()[2]
    assert "| 2 |" in row  # two of three stand
    assert "60 mm |" in row  # a fifth of 300
    assert "180 mm (32, 30, 0.5)" in row
    assert "60 mm (30, 32, 0)" in row  # the smallest rms
    assert "alpha 30..32, beta 30..32, h_c 0..0.5, overbend 0 (3)" in row
    assert row.endswith("| 5 s |")
    fell = (30.0, 30.0, 0.0, None, None, 1.0, 0.0)
    assert "falls" in cf.summary("t", "coarse", "mm", fell, rows)


def test_the_polished_line_names_the_overbend_when_it_was_polished_too() -> None:
    start = (30.0, 30.0, 0.0, 300.0, 100.0, 2.0, 0.0)
    rows = [(32.0, 30.0, 0.5, 180.0, 70.0, 1.0, 0.0)]
    polished = (33.0, 29.0, 0.4, 150.0, 60.0, 40.0, 0.0)
    plain = cf.summary("t", "coarse", "mm", start, rows, polished)
    assert plain.splitlines()[-1] == (
        "Polished from the grid's best by Nelder-Mead on the largest distance itself: "
        "150 mm at alpha 33, beta 29 deg, h_c 0.4 (40 s CPU)."
    )
    both = cf.summary("t", "coarse", "mm", start, rows, polished, -7.5)
    assert both.splitlines()[-1] == (
        "Polished from the grid's best by Nelder-Mead on the largest distance itself (the "
        "crease overbend too): 150 mm at alpha 33, beta 29 deg, h_c 0.4, crease overbend "
        "-7.5 deg (40 s CPU)."
    )


def test_an_overbend_grid_names_the_overbend_of_the_best_folds() -> None:
    start = (30.0, 30.0, 0.0, 300.0, 100.0, 2.0, 0.0)
    rows = [
        (32.0, 30.0, 0.5, 180.0, 70.0, 1.0, 0.0),
        (32.0, 30.0, 0.5, 120.0, 50.0, 1.0, -8.0),  # the smallest max and rms
    ]
    row = cf.summary("t", "coarse", "mm", start, rows).splitlines()[2]
    assert "overbend -8..0 (2)" in row
    assert "120 mm (32, 30, 0.5, -8)" in row
    assert "50 mm (32, 30, 0.5, -8)" in row
    head = cf.summary("t", "coarse", "mm", start, rows).splitlines()[0]
    assert "smallest max on the grid (alpha, beta, h_c, overbend)" in head
