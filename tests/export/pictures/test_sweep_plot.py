"""The sweep's picture: parallel coordinates with the Pareto front marked."""

from __future__ import annotations

import numpy as np

from onefold_cad.export.pictures.sweep_plot import draw_parallel_coordinates


def test_parallel_coordinates_draw_the_front_in_red(tmp_path):
    import matplotlib.image as mpimg

    rng = np.random.default_rng(1)
    n = 50
    axes = [
        ("alpha", "deg", rng.uniform(10, 80, n)),
        ("height", "mm", rng.uniform(0, 3e3, n)),
        ("constant", "", np.full(n, 2.0)),
        ("partly", "", np.r_[np.nan, np.ones(n - 1)]),
    ]
    front = np.zeros(n, dtype=bool)
    front[:3] = True
    out = draw_parallel_coordinates(
        tmp_path / "p.png", axes, front=front, colour=("height (mm)", axes[1][2]), title="t"
    )
    img = mpimg.imread(out)[:, :, :3]
    assert img.shape[:2] == (700, 1400)
    red = (img[:, :, 0] > 0.7) & (img[:, :, 1] < 0.3) & (img[:, :, 2] < 0.3)
    assert red.sum() > 500
    assert [p.name for p in tmp_path.iterdir()] == ["p.png"]
    # no front, no colour, no designs: still a picture
    empty = draw_parallel_coordinates(tmp_path / "e.png", [("a", "", np.array([]))])
    assert empty.read_bytes().startswith(b"\x89PNG")
