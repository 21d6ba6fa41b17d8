"""A thumbnail drawn on the thread's kept figure is the one a fresh figure
gives: nothing of the last picture carries over."""

from __future__ import annotations

import threading

from onefold_cad import Design, FrameCurve, Sheet, fold_design
from onefold_cad.export.pictures.preview import thumbnail_png
from onefold_cad.export.pictures.reuse import empty_axes3d


def _fresh_thread(fn):
    """``fn()`` in a new thread (which has no kept figure yet)."""
    out = []
    t = threading.Thread(target=lambda: out.append(fn()))
    t.start()
    t.join()
    return out[0]


def test_a_kept_figure_draws_what_a_fresh_one_does():
    a = fold_design(Design("a", FrameCurve(40, 40), Sheet.rectangle(300, 200, 0.5)))
    b = fold_design(Design("b", FrameCurve(70, 20, 25.0), Sheet.rectangle(200, 400, 0.3)))
    first_a = _fresh_thread(lambda: thumbnail_png(a))
    first_b = _fresh_thread(lambda: thumbnail_png(b))
    assert first_a != first_b
    # one thread: a, then b on a's figure, then a on b's
    again = _fresh_thread(lambda: [thumbnail_png(a), thumbnail_png(b), thumbnail_png(a)])
    assert again == [first_a, first_b, first_a]


def test_the_kept_axes_come_back_empty_and_per_thread():
    fig, ax = empty_axes3d((120, 90), (0.0, 0.0, 1.0, 1.0))
    ax.plot([0, 1], [0, 1], [0, 1])
    ax.scatter([0], [0], [0])
    again = empty_axes3d((120, 90), (0.0, 0.0, 1.0, 1.0))
    assert again == (fig, ax)
    assert not ax.lines and not ax.collections and not ax.artists
    other = _fresh_thread(lambda: empty_axes3d((120, 90), (0.0, 0.0, 1.0, 1.0)))
    assert other[0] is not fig
