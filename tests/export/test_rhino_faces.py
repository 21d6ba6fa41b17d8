"""The .3dm's face nets: cubic curves along the hole and the sheet's edge that
stay on the exact cone to the tolerance asked for, more nodes for less; a
side's net the sectors' strung together, the same curves at the same angles,
with triple knots at the corners."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import BSpline

from onefold_cad import Design, ExportError, FrameCurve, Sheet, fold_design
from onefold_cad.export import rhino_faces
from onefold_cad.export.rhino_faces import face_nets, side_nets


@pytest.fixture(scope="module")
def folded():
    sheet = Sheet.polygon([[90, 0], [40, 70], [-80, 50], [-100, 0], [-30, -60], [70, -40]])
    return fold_design(Design("nets", FrameCurve(40, 30), sheet))


def _curves(net):
    t = np.concatenate([net.knots[:1], net.knots, net.knots[-1:]])
    return BSpline(t, net.inner, 3), BSpline(t, net.outer, 3)


@pytest.mark.parametrize("hole", [0.0, 6.0])
def test_nets_stay_on_the_cone_between_their_nodes(folded, hole):
    """Measured with the fold's own inverse (unfold) at many points between
    the nodes, not at the writer's probes: within the tolerance (and its
    rounding) of the cone, and on the sheet's edge and the hole's."""
    tol = 1e-7 * folded.sheet.size
    nets = face_nets(folded, hole, tol)
    assert len(nets) == sum(len(a) - 1 for a in folded.ruling_angles)
    for net in nets:
        assert net.deviation <= tol
        inner, outer = _curves(net)
        s = np.linspace(0.0, 1.0, 1001)
        if hole == 0.0:  # the apex edge collapses onto the apex
            assert np.abs(net.inner - folded.apex).max() <= 1e-12 * folded.sheet.size
        for v in (0.0, 0.3, 1.0) if hole > 0.0 else (0.3, 1.0):
            p = (1 - v) * inner(s) + v * outer(s)
            flat, off = folded.unfold(p)
            assert off.max() <= 2 * tol
        flat, _ = folded.unfold(outer(s))
        psi = np.arctan2(flat[:, 1], flat[:, 0])
        r = np.hypot(flat[:, 0], flat[:, 1])
        assert np.abs(r - folded.sheet.ray_lengths(psi)).max() <= 2 * tol
        if hole > 0.0:
            flat, _ = folded.unfold(inner(s))
            assert np.abs(np.hypot(flat[:, 0], flat[:, 1]) - hole).max() <= 2 * tol


def test_a_tighter_tolerance_takes_more_nodes(folded):
    size = folded.sheet.size
    loose = face_nets(folded, 0.0, 1e-5 * size)
    tight = face_nets(folded, 0.0, 1e-9 * size)
    assert sum(len(n.nodes) for n in tight) > sum(len(n.nodes) for n in loose)
    assert max(n.deviation for n in tight) <= 1e-9 * size


def test_a_tolerance_out_of_reach_is_refused(folded, monkeypatch):
    monkeypatch.setattr(rhino_faces, "MAX_NODES", 12)
    with pytest.raises(ExportError, match="from the exact cone"):
        face_nets(folded, 0.0, 1e-10 * folded.sheet.size)


@pytest.mark.parametrize("hole", [0.0, 6.0])
def test_a_sides_net_is_its_sectors_curves_end_to_end(folded, hole):
    """At each parameter u (the flat angle swept from the side's first crease
    half) the side's curves are the sector's there, evaluated at its own
    parameter; triple knots exactly at the corners between the sectors."""
    nets = face_nets(folded, hole, 1e-7 * folded.sheet.size)
    sides = side_nets(nets)
    assert [s.side for s in sides] == [0, 1]
    for side in sides:
        mine = [n for n in nets if n.side == side.side]
        assert sorted(n.sector for n in side.sectors) == sorted(n.sector for n in mine)
        t = np.concatenate([side.knots[:1], side.knots, side.knots[-1:]])
        inner, outer = BSpline(t, side.inner, 3), BSpline(t, side.outer, 3)
        values, counts = np.unique(side.knots, return_counts=True)
        assert np.allclose(side.corners, values[1:-1][counts[1:-1] == 3], rtol=0, atol=1e-12)
        assert counts[1:-1].max() == 3 and len(side.corners) == len(side.sectors) - 1
        theta = np.unique(folded.ruling_angles[side.side])
        assert side.knots[-1] == pytest.approx(theta[-1] - theta[0], abs=1e-12)
        for net in side.sectors:
            ta, tb = net.theta
            start = (theta[-1] - tb) if side.side == 0 else ta - theta[0]
            s = np.linspace(0.0, 1.0, 101)
            u = start + (tb - ta) * s
            own_in, own_out = _curves(net)
            tol = 1e-12 * folded.sheet.size
            assert np.abs(outer(u) - own_out(s)).max() <= tol
            assert np.abs(inner(u) - own_in(s)).max() <= tol
