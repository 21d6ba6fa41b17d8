"""The thick sheet's offsets about the exact cone (geometry/thick_sheet.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad import (
    Design,
    FrameCurve,
    InvalidParameterError,
    Material,
    Sheet,
    SheetSurface,
    build_design,
)
from onefold_cad.geometry.thick_sheet import (
    SideMap,
    min_relief_hole,
    mitre_depth,
    sheet_offsets,
    slab_volume,
)


def _fold(alpha=50.0, beta=45.0, h_c=0.0, sheet=None, model="exact"):
    sheet = sheet or Sheet.quadrilateral(300, 200, 250, 150)
    return build_design(Design("t", FrameCurve(alpha, beta, h_c), sheet, model=model))


@settings(max_examples=25, deadline=None)
@given(
    alpha=st.floats(10, 80),
    beta=st.floats(10, 80),
    frac=st.floats(-0.6, 0.6),
    lower=st.booleans(),
)
def test_side_map_at_s0_is_the_folded_surface(alpha, beta, frac, lower):
    folded = _fold(alpha, beta, frac * 100 * math.cos(math.radians(alpha)))
    side = SideMap(folded, lower=lower)
    theta = np.linspace(0.05, math.pi - 0.05, 9)
    r = np.linspace(20.0, 120.0, 9)
    psi = -theta if lower else theta
    xy = np.stack([r * np.cos(psi), r * np.sin(psi)], axis=1)
    mirror = np.array([1.0, -1.0, 1.0]) if lower else np.ones(3)
    np.testing.assert_allclose(
        side.points(theta, r, 0.0) * mirror, folded.map_points(xy), atol=1e-9
    )
    # its normal is the top normal of that side (the -y side's, mirrored back)
    _, _, n = side.frames(theta)
    np.testing.assert_allclose(n * mirror, folded.normals(xy), atol=1e-9)


@settings(max_examples=20, deadline=None)
@given(alpha=st.floats(10, 80), beta=st.floats(10, 80), s=st.floats(-5.0, 5.0))
def test_jacobian_is_r_minus_s_k(alpha, beta, s):
    """dF/dtheta = (r - s k) e: the basis of the slab's volume formula."""
    side = SideMap(_fold(alpha, beta))
    theta, r, h = np.array([0.4, 1.3, 2.7]), np.full(3, 80.0), 1e-6
    dF = (side.points(theta + h, r, s) - side.points(theta - h, r, s)) / (2 * h)
    _, e, _ = side.frames(theta)
    expected = (r - s * side.curvature(theta))[:, None] * e
    np.testing.assert_allclose(dF, expected, atol=1e-5)


def test_sheet_offsets_follow_sheet_surface():
    t = 2.0
    got = {s: sheet_offsets(Material(thickness=t, sheet_surface=s)) for s in SheetSurface}
    assert got == {
        SheetSurface.INSIDE: (-2.0, 0.0),
        SheetSurface.OUTSIDE: (0.0, 2.0),
        SheetSurface.MID: (-1.0, 1.0),
    }


def test_mid_slab_volume_is_area_times_thickness():
    folded = _fold()
    m = Material(thickness=3.0, sheet_surface=SheetSurface.MID)
    hole = 20.0
    area = folded.sheet.area - math.pi * hole**2 / 4
    v_mid = slab_volume(folded, m, hole)
    assert v_mid == pytest.approx(area * 3.0, rel=1e-3)  # the mitre cancels to first order
    assert slab_volume(folded, m, hole, samples=2400) == pytest.approx(v_mid, rel=1e-5)
    # INSIDE and OUTSIDE differ from it in opposite directions
    v_in = slab_volume(folded, m.with_changes(sheet_surface=SheetSurface.INSIDE), hole)
    v_out = slab_volume(folded, m.with_changes(sheet_surface=SheetSurface.OUTSIDE), hole)
    assert (v_in - area * 3.0) * (v_out - area * 3.0) < 0


def test_min_relief_hole_grows_with_thickness_and_covers_the_mitre():
    folded = _fold()
    holes = [min_relief_hole(folded, Material(thickness=t)) for t in (1.0, 2.0, 4.0)]
    assert 0 < holes[0] < holes[1] < holes[2]
    # the regularity bound 2 max(s k) alone, computed here from the curvature
    side = SideMap(folded)
    k = side.curvature(np.linspace(0.01, side.total - 0.01, 400))
    s_range = sheet_offsets(Material(thickness=2.0))
    regular = 2 * max(float(np.max(s * k)) for s in s_range)
    assert holes[1] >= regular * (1 - 1e-3) and holes[1] >= 2 * mitre_depth(side, s_range)
    # a hole below the minimum puts the sheet's face over the apex region: the
    # offset point at r just under s k lies on the other side of the ruling
    theta = np.linspace(0.01, side.total - 0.01, 400)
    s = min(s_range) if regular == 2 * float(np.max(min(s_range) * k)) else max(s_range)
    worst = int(np.argmax(s * k))
    r = 0.9 * float(s * k[worst])
    h = 1e-4
    p0 = side.points(theta[worst : worst + 1] - h, np.array([r]), s)
    p1 = side.points(theta[worst : worst + 1] + h, np.array([r]), s)
    _, e, _ = side.frames(theta[worst : worst + 1])
    assert float((p1 - p0)[0] @ e[0]) < 0  # the offset runs backwards: folded over


def test_paper_model_is_refused():
    with pytest.raises(InvalidParameterError, match="model"):
        SideMap(_fold(model="paper"))
