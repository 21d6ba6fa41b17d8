"""The designs the FOLD tests draw (tests/export/fold/test_mesh.py and
test_fold_fan.py): a frame, a division count, a model, a quadrilateral sheet
and a relief hole, over the ranges the file must handle."""

from __future__ import annotations

import math

from hypothesis import strategies as st

from onefold_cad import Design, FrameCurve, Material, Sheet
from onefold_cad.geometry.sheet import sheet_inradius


@st.composite
def fold_designs(draw: st.DrawFn) -> Design:
    """alpha and beta in [10, 80] deg, H anywhere within 80 % of the f-line's
    half, 2 to 120 divisions, either model, quadrilateral distances 50 to 1000,
    and no hole or one of 1 % or 10 % of twice H's distance to the nearest
    edge."""
    alpha = draw(st.floats(10.0, 80.0))
    beta = draw(st.floats(10.0, 80.0))
    frac = draw(st.floats(-0.8, 0.8))
    divisions = draw(st.integers(2, 120))
    model = draw(st.sampled_from(["paper", "exact"]))
    quad = draw(st.tuples(*[st.floats(50.0, 1000.0)] * 4))
    hole = draw(st.sampled_from([0.0, 0.01, 0.1]))
    frame = FrameCurve(alpha, beta, frac * 100.0 * math.cos(math.radians(alpha)), 100.0, divisions)
    sheet = Sheet.quadrilateral(*quad)
    material = Material(relief_hole=hole * 2.0 * sheet_inradius(sheet))
    return Design("p", frame, sheet, model=model, material=material)
