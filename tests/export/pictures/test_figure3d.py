"""The pictures' shared heading and legend (export/pictures/figure3d.py): a
long design name wraps inside the picture and the legend keeps clear of it."""

from __future__ import annotations

import pytest
from matplotlib.lines import Line2D

from onefold_cad.export.pictures.figure3d import (
    HEADING_WIDTH,
    agg_figure,
    heading,
    legend_below,
)

#: A design named by its flags, as ``onefold build`` and ``simulate`` name it.
LONG = "patkau-one-fold-alpha56.4-beta9.705-hc-1.533-ob-15.3-rectangle3048x7315.2-t3.57"


@pytest.mark.parametrize(
    ("text", "lines"),
    [
        ("p: the standing form's deviation from the design", 1),
        (f"{LONG}: the standing form's deviation from the design", 2),
        (f"{LONG}-{LONG}-{LONG}: stress", 3),
    ],
)
def test_a_heading_wraps_inside_the_picture_and_the_legend_sits_below_it(text, lines):
    fig = agg_figure((900, 700))
    fig.add_axes((0.0, 0.1, 0.8, 0.85))
    head = heading(fig, text)
    handles = [Line2D([], [], ls="--", label="designed form's outline"),
               Line2D([], [], marker="X", ls="", label="largest stress")]  # fmt: skip
    legend_below(fig, handles, head)
    renderer = fig.canvas.get_renderer()
    fig.draw(renderer)
    h = head.get_window_extent(renderer)
    (legend,) = fig.legends
    g = legend.get_window_extent(renderer)
    assert head.get_text().count("\n") + 1 == lines
    assert all(len(line) <= HEADING_WIDTH for line in head.get_text().splitlines())
    assert 0 <= h.x0 and h.x1 <= 900 and h.y1 <= 700  # inside the picture
    assert g.y1 <= h.y0  # the legend below the heading, not across it
    assert g.x1 <= 900 and g.x0 >= 0.6 * 900  # at the right


def test_without_a_heading_the_legend_is_at_the_top():
    fig = agg_figure((900, 700))
    legend_below(fig, [Line2D([], [], label="x")], None)
    renderer = fig.canvas.get_renderer()
    fig.draw(renderer)
    assert fig.legends[0].get_window_extent(renderer).y1 >= 0.97 * 700
