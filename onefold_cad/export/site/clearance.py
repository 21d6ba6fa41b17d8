"""The clearance check of a site on the sheets' exact B-reps: the smallest
distance between every two placed parts, and the area their footprints share.
What counts as touching is :mod:`onefold_cad.site.clearance`'s.

The distance: the two parts' coarse meshes (:func:`onefold_cad.export.site.mesh.mesh_shape`,
:data:`SEED_DEFLECTION`; every node on its B-rep) give
the nearest pair of nodes; from it, alternate exact projections (a point of
one part onto the other's B-rep, OCCT's BRepExtrema_DistShapeShape between a
vertex and the part, and back) descend to the B-reps' closest points, to
rounding. That is a local minimum of the exact distance between the B-reps,
never more than the nodes' distance (0 when a point of one lies inside the
other solid); a pair closer than :data:`CLOSE` of the sheet's size but apart
is measured again with BRepExtrema on the whole parts (exact, global, tens of
seconds). The whole-part
computation everywhere gives the same numbers (tests/export/) twenty times
slower. The B-reps lie within their ``fit_tolerance`` of the designed
surfaces (the accuracy reported). Lengths in the site's unit.
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import combinations
from typing import Any

import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
from OCP.BRepExtrema import BRepExtrema_DistShapeShape
from OCP.gp import gp_Pnt
from scipy.spatial import cKDTree

from onefold_cad.errors import ExportError
from onefold_cad.export.site.context import SiteSheet
from onefold_cad.export.site.mesh import mesh_shape
from onefold_cad.geometry.numeric import Array
from onefold_cad.site.clearance import Clearance, PairDistance, clearance, convex_overlap

__all__ = ["CLOSE", "SEED_ANGLE", "SEED_DEFLECTION", "exact_distance", "measure_clearance"]

#: The seeding meshes: deflection relative to the sheet's size, angle (rad).
SEED_DEFLECTION = 1e-2
SEED_ANGLE = 0.3
#: Pairs closer than this (relative to the larger sheet's size) are measured on
#: the whole parts and checked for shared volume.
CLOSE = 0.01
_ROUNDS = 50


def _extrema(a: Any, b: Any) -> tuple[float, Array, Array]:
    """OCCT's smallest distance between two shapes and where it is reached."""
    ext = BRepExtrema_DistShapeShape(a, b)
    ext.Perform()
    if not ext.IsDone() or ext.NbSolution() < 1:
        raise ExportError("OCCT could not measure the distance between two sheets")
    pa, pb = ext.PointOnShape1(1), ext.PointOnShape2(1)
    return float(ext.Value()), np.array(pa.Coord()), np.array(pb.Coord())


def _project(point: Array, shape: Any) -> tuple[float, Array]:
    vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, point))).Vertex()
    d, _, q = _extrema(vertex, shape)
    return d, q


def exact_distance(a: Any, b: Any) -> tuple[float, Array, Array]:
    """The smallest distance between the whole parts ``a`` and ``b`` (build123d
    shapes; OCCT's BRepExtrema_DistShapeShape) and its two points."""
    return _extrema(a.wrapped, b.wrapped)


def _descend(a: Any, b: Any, pa: Array, scale: float) -> tuple[float, Array, Array]:
    """Alternate projections from ``pa`` (on ``a``) onto ``b`` and back, until
    the distance stops falling (relative 1e-12 of ``scale``)."""
    d, pb = _project(pa, b.wrapped)
    for _ in range(_ROUNDS):
        d_back, pa_new = _project(pb, a.wrapped)
        d_new, pb_new = _project(pa_new, b.wrapped)
        if d - d_new <= 1e-12 * scale:
            if d_new < d:
                d, pa, pb = d_new, pa_new, pb_new
            break
        d, pa, pb = d_new, pa_new, pb_new
    return d, pa, pb


def _pair(a: SiteSheet, b: SiteSheet, nodes: dict[str, Array]) -> PairDistance:
    scale = max(float(a.design.sheet.size), float(b.design.sheet.size))
    gaps, nearest = cKDTree(nodes[b.name]).query(nodes[a.name])
    k = int(np.argmin(gaps))
    d, pa, pb = _descend(a.placed, b.placed, nodes[a.name][k], scale)
    if 0.0 < d <= CLOSE * scale:  # close: the global minimum on the whole parts
        d, pa, pb = exact_distance(a.placed, b.placed)
    feet = [s.site.apply(np.asarray(s.resting.footprint, dtype=float)) for s in (a, b)]
    return PairDistance(a.name, b.name, d, pa, pb, convex_overlap(*feet), scale)


def measure_clearance(sheets: Sequence[SiteSheet]) -> Clearance:
    """Every pair's smallest distance (site file's order), and the accuracy:
    the sum of the two largest fit tolerances of the sheets' B-reps."""
    nodes = {
        s.name: mesh_shape(s.placed, SEED_DEFLECTION * float(s.design.sheet.size), SEED_ANGLE)[0]
        for s in sheets
    }
    tolerances = sorted(float(getattr(s.part, "fit_tolerance", 0.0)) for s in sheets)
    pairs = [_pair(a, b, nodes) for a, b in combinations(sheets, 2)]
    return clearance(pairs, sum(tolerances[-2:]))
