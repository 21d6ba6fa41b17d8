"""The sheet as a solid of thickness t (exact model), built face by face.

The boundary comes from :class:`onefold_cad.geometry.thick.slab.Slab`: each
side is ``F(theta, r, s) = A + r u(theta) + s n(theta)`` over the sheet (r
from the relief hole to the cut edge, s over the thickness), continued past
each crease half by a flat mitre block, and kept on the inner side of its
cutting planes (the fold's plane of symmetry y = 0; past each crease half
also the mitre plane that keeps the two halves' blocks apart); the -y side
is the mirror image of the same construction on the mirrored sheet. Every
face is ruled (F and the planes are linear in r and in s), so each is built
as the ruled surface between two B-spline curves parameterised by theta
(:class:`~onefold_cad.geometry.thick.slab.Patch`): its rulings join points
of equal theta exactly, and the curves carry the interpolation error
(refined until their deviation is below a tolerance). The sheet's faces past
a crease half are planar and each becomes one planar face. The outlines
left open on the cutting planes (where the two sides' sections of y = 0
differ because the sheet's edges at a crease end are not symmetric about
it, and where the mitre planes cut the blocks) are closed by planar faces
on those planes.

No boolean operation is involved: the faces are sewn once (curves that two
faces share are the same B-spline, interpolating every point where another
face ends on them, so a tolerance of 1e-9 of the sheet's size suffices) and
made into a solid.

Lengths are in the design unit; angles in radians.
"""

from __future__ import annotations

from collections import defaultdict

import build123d as bd
import numpy as np
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepBuilderAPI import (
    BRepBuilderAPI_MakeFace,
    BRepBuilderAPI_MakeSolid,
    BRepBuilderAPI_MakeWire,
    BRepBuilderAPI_Sewing,
)
from OCP.BRepLib import BRepLib
from OCP.collections import HSequence_TopoDS_Shape as TopTools_HSequenceOfShape
from OCP.Geom import Geom_BSplineCurve, Geom_Line
from OCP.Geom2d import Geom2d_Line
from OCP.GeomFill import GeomFill_Generator
from OCP.gp import gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d
from OCP.ShapeAnalysis import ShapeAnalysis_FreeBounds, ShapeAnalysis_ShapeTolerance
from OCP.ShapeFix import ShapeFix_Solid
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FORWARD, TopAbs_REVERSED, TopAbs_SHELL
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS, TopoDS_Edge, TopoDS_Face, TopoDS_Vertex, TopoDS_Wire

from onefold_cad.errors import ExportError
from onefold_cad.export.aligned_plane import aligned_plane, cutting_plane
from onefold_cad.export.brep.bspline_fit import (
    curve_values,
    fit_curve,
)
from onefold_cad.export.brep.kernel_budget import KernelBudget
from onefold_cad.export.brep.step_checks import MIN_RULING
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.thick.slab import Boundary, Patch, Slab
from onefold_cad.geometry.thick.slab_faces import slab_patches

__all__ = ["Array", "thick_solid"]


#: The solid's faces as a refusal names them (:class:`~onefold_cad.geometry.thick.slab.Patch`).
_FACES = {"s0": "sheet's face", "s1": "sheet's other face", "in": "relief hole's wall"}


class _Vertices:
    """Vertices by position: points closer than ``tol`` are one vertex."""

    def __init__(self, tol: float) -> None:
        self.tol = tol
        self.points = np.empty((0, 3))
        self.vertices: list[TopoDS_Vertex] = []
        self.builder = BRep_Builder()

    def at(self, p: Array) -> TopoDS_Vertex:
        if len(self.points):
            d = np.linalg.norm(self.points - p, axis=1)
            k = int(np.argmin(d))
            if d[k] <= self.tol:
                return self.vertices[k]
        v = TopoDS_Vertex()
        self.builder.MakeVertex(v, gp_Pnt(*map(float, p)), self.tol)
        self.points = np.vstack([self.points, p])
        self.vertices.append(v)
        return v


def _pnt_xyz(p: gp_Pnt) -> Array:
    return np.array([p.X(), p.Y(), p.Z()])


class _Builder:
    """Faces of the solid: ruled patches, planar pieces, and their curves."""

    def __init__(self, slab: Slab, tol: float, budget: KernelBudget) -> None:
        self.slab = slab
        self.tol = tol
        self.budget = budget
        self.b = BRep_Builder()
        # points meant to coincide do so to ~1e-13 of the sheet's size, distinct
        # vertices lie > 1e-5 of it apart
        self.verts = _Vertices(max(1e-10 * slab.sides[0].sheet.size, 1e-9))
        self.sew_tol = max(10.0 * self.verts.tol, 1e-7)
        self.curves: dict[tuple, tuple[float, float, Geom_BSplineCurve]] = {}
        self.splits: dict[tuple, Array] = {}
        self.deviation = 0.0

    # -- curves --------------------------------------------------------------
    def _key(self, b: Boundary, side: int) -> tuple:
        return (b.kind, b.radius, b.level, b.plane, b.side if b.side >= 0 else -1)

    def _kinks(self, b: Boundary, side: int) -> Array:
        s = self.slab
        if b.kind == "K":
            return np.array([s.domain[0], 0.0, s.total, s.domain[1]])
        return s.kinks(b.radius, side if b.side < 0 else b.side)

    def prepare(self, patches: list[Patch]) -> None:
        """Fit every boundary curve once, over all the theta its patches use,
        and note where the patches split it (its edges' ends)."""
        uses: dict[tuple, list[tuple[float, float]]] = defaultdict(list)
        sides: dict[tuple, int] = {}
        for p in patches:
            for b in (p.low, p.high):
                ks = self._kinks(b, p.side)
                i = int(np.searchsorted(ks, 0.5 * (p.t0 + p.t1)))
                key = (*self._key(b, p.side), i)
                uses[key].append((p.t0, p.t1))
                sides[key] = p.side
        # one curve per connected run of uses (a curve may serve both creases)
        runs: dict[tuple, list[tuple[float, float]]] = {}
        for key, ranges in uses.items():
            ranges.sort()
            run, k = [ranges[0]], 0
            for r in ranges[1:]:
                if r[0] > max(q[1] for q in run):
                    runs[(*key, k)] = run
                    run, k = [r], k + 1
                else:
                    run.append(r)
            runs[(*key, k)] = run
        for rkey, ranges in runs.items():
            key = rkey[:-1]
            self.budget.check()
            kind, radius, level, plane, side = key[:5]
            own = sides[key]
            a = min(r[0] for r in ranges)
            z = max(r[1] for r in ranges)
            b = Boundary(kind, radius, level, plane, side)

            def fn(t: Array, b: Boundary = b, own: int = own) -> Array:
                return self.slab.boundary_points(b, own, t)

            splits = np.unique(np.array([t for r in ranges for t in r]))
            # the two sides' ends closer than the sewing tolerance are one
            # point: sewing joins their edges (a sheet symmetric up to rounding)
            pts = fn(splits)
            keep = [0]
            for i in range(1, len(splits)):
                if np.linalg.norm(pts[i] - pts[keep[-1]]) > self.sew_tol:
                    keep.append(i)
            splits = splits[keep]
            what = "an edge curve of the thick sheet"
            curve, err = fit_curve(fn, a, z, self.tol, what, splits)
            self.deviation = max(self.deviation, err)
            self.curves[rkey] = (a, z, curve)
            self.splits[rkey] = splits

    def _curve(
        self, b: Boundary, side: int, t0: float, t1: float
    ) -> tuple[tuple, Geom_BSplineCurve]:
        ks = self._kinks(b, side)
        i = int(np.searchsorted(ks, 0.5 * (t0 + t1)))
        key = (*self._key(b, side), i)
        k = 0
        while True:
            a, z, curve = self.curves[(*key, k)]
            if a <= t0 and t1 <= z:
                return (*key, k), curve
            k += 1

    def _point(self, curve: Geom_BSplineCurve, t: float) -> TopoDS_Vertex:
        return self.verts.at(_pnt_xyz(curve.Value(float(t))))

    def _edges_along(
        self, key: tuple, curve: Geom_BSplineCurve, t0: float, t1: float
    ) -> list[tuple[TopoDS_Edge, float, float]]:
        """Edges on ``curve`` from t0 to t1, split where other patches end."""
        cut = self.splits[key]
        cut = cut[(cut > t0) & (cut < t1)]
        if len(cut):  # none within the sewing tolerance of the ends
            ends = curve_values(curve, np.array([t0, t1]))
            at = curve_values(curve, cut)
            far = np.minimum(*(np.linalg.norm(at - e, axis=1) for e in ends)) > self.sew_tol
            cut = cut[far]
        ts = np.concatenate([[t0], cut, [t1]])
        out = []
        for a, z in zip(ts[:-1], ts[1:], strict=True):
            e = TopoDS_Edge()
            self.b.MakeEdge(e, curve, self.tol)
            self.b.Add(e, self._point(curve, a).Oriented(TopAbs_FORWARD))
            self.b.Add(e, self._point(curve, z).Oriented(TopAbs_REVERSED))
            self.b.Range(e, float(a), float(z))
            out.append((e, float(a), float(z)))
        return out

    def _resolvable(self, p: Patch, ca: Geom_BSplineCurve, cb: Geom_BSplineCurve) -> None:
        """Refuse a patch the kernel cannot cut out of its curves (Segment fails
        in InsertKnots): a curve whose fit merged t0 and t1 (closer than the
        sewing tolerance: a nearly closed fold's mitre on a thin sheet) and so
        stops short, or both curves within MIN_RULING; named by face and place."""
        ends = np.array([p.t0, p.t1])
        spans = [float(np.ptp(curve_values(c, ends), axis=0).max()) for c in (ca, cb)]
        eps = 1e-12 * max(1.0, abs(p.t1))
        short = any(
            c.FirstParameter() > p.t0 + eps or c.LastParameter() < p.t1 - eps for c in (ca, cb)
        )
        if not short and max(spans) > MIN_RULING:
            return
        face = _FACES.get(p.face, "cut edge's wall")
        half = "plus_x" if p.t1 <= 0.0 else "minus_x"
        past = p.t1 <= 0.0 or p.t0 >= self.slab.total
        where = f"past the {half} crease (its mitre)" if past else "inside the sheet"
        bound = f"the sewing tolerance {self.sew_tol:.2g}" if short else f"{MIN_RULING:g}"
        raise ExportError(
            f"the {face} {where} would be {min(spans):.2g} wide on the {'+-'[p.side]}y side, "
            f"below what the CAD kernel resolves ({bound})"
        )

    # -- faces ---------------------------------------------------------------
    def ruled(self, p: Patch) -> TopoDS_Face:
        """The ruled face of patch ``p``: its two curves (split where other
        faces end on them) and the rulings at both ends (degenerate where the
        curves meet)."""
        ka, ca = self._curve(p.low, p.side, p.t0, p.t1)
        kb, cb = self._curve(p.high, p.side, p.t0, p.t1)
        self._resolvable(p, ca, cb)
        sa, sb = ca.Copy(), cb.Copy()
        sa.Segment(p.t0, p.t1)
        sb.Segment(p.t0, p.t1)
        gen = GeomFill_Generator()
        gen.AddCurve(sa)
        gen.AddCurve(sb)
        gen.Perform(1e-12)
        surf = gen.Surface()
        # u along the ruling, v along theta (the face reversed to keep its
        # side): OCC's default integration (FreeCAD's Volume, build123d's
        # volume) integrates along the edges crossing v with as many Gauss
        # points as the surface's v knots ask for (at most 61), and once
        # across u: with theta as u it took 8 points across theta on every
        # face and measured patkau-one-fold's solid 1.9 % light
        surf.ExchangeUV()
        face = TopoDS_Face()
        self.b.MakeFace(face, surf, self.tol)
        wire = TopoDS_Wire()
        self.b.MakeWire(wire)
        right = gp_Dir2d(0.0, 1.0)
        for e, a, z in self._edges_along(ka, ca, p.t0, p.t1):
            self.b.UpdateEdge(e, Geom2d_Line(gp_Pnt2d(0.0, 0.0), right), face, self.tol)
            self.b.Range(e, face, a, z)
            self.b.Add(wire, e)
        self._ruling(wire, face, surf, p.t1, ca, cb, reverse=False)
        for e, a, z in reversed(self._edges_along(kb, cb, p.t0, p.t1)):
            self.b.UpdateEdge(e, Geom2d_Line(gp_Pnt2d(1.0, 0.0), right), face, self.tol)
            self.b.Range(e, face, a, z)
            self.b.Add(wire, e.Reversed())
        self._ruling(wire, face, surf, p.t0, ca, cb, reverse=True)
        self.b.Add(face, wire)
        return TopoDS.Face(face.Reversed())

    def _ruling(
        self,
        wire: TopoDS_Wire,
        face: TopoDS_Face,
        surf,
        t: float,
        ca: Geom_BSplineCurve,
        cb: Geom_BSplineCurve,
        *,
        reverse: bool,
    ) -> None:
        """The ruling at ``t`` from curve a to curve b (degenerate where they
        meet), added to ``wire`` (reversed at the patch's start)."""
        va, vb = self._point(ca, t), self._point(cb, t)
        up = gp_Dir2d(1.0, 0.0)
        e = TopoDS_Edge()
        if va.IsSame(vb):
            self.b.MakeEdge(e)
            self.b.Degenerated(e, True)
        else:
            self.b.MakeEdge(e, surf.VIso(float(t)), self.tol)
            self.b.Range(e, 0.0, 1.0)
        self.b.Add(e, va.Oriented(TopAbs_FORWARD))
        self.b.Add(e, vb.Oriented(TopAbs_REVERSED))
        self.b.UpdateEdge(e, Geom2d_Line(gp_Pnt2d(0.0, t), up), face, self.tol)
        self.b.Range(e, face, 0.0, 1.0)
        self.b.Add(wire, e.Reversed() if reverse else e)

    def _line(self, p: Array, q: Array) -> TopoDS_Edge:
        e = TopoDS_Edge()
        d = q - p
        line = Geom_Line(gp_Pnt(*map(float, p)), gp_Dir(*map(float, d)))
        self.b.MakeEdge(e, line, self.tol)
        self.b.Add(e, self.verts.at(p).Oriented(TopAbs_FORWARD))
        self.b.Add(e, self.verts.at(q).Oriented(TopAbs_REVERSED))
        self.b.Range(e, 0.0, float(np.linalg.norm(d)))
        return e

    def planar(self, patches: list[Patch]) -> TopoDS_Face:
        """One planar face over consecutive patches of a sheet face past a crease half."""
        ps = sorted(patches, key=lambda p: p.t0)
        edges: list[TopoDS_Edge] = []
        for p in ps:  # the low curves, theta increasing
            key, c = self._curve(p.low, p.side, p.t0, p.t1)
            edges += [e for e, _, _ in self._edges_along(key, c, p.t0, p.t1)]
        last = ps[-1]
        a_end = self._curve(last.low, last.side, last.t0, last.t1)[1].Value(last.t1)
        b_end = self._curve(last.high, last.side, last.t0, last.t1)[1].Value(last.t1)
        if a_end.Distance(b_end) > self.verts.tol:
            edges.append(self._line(_pnt_xyz(a_end), _pnt_xyz(b_end)))
        for p in reversed(ps):  # the high curves back
            key, c = self._curve(p.high, p.side, p.t0, p.t1)
            edges += [
                TopoDS.Edge(e.Reversed())
                for e, _, _ in reversed(self._edges_along(key, c, p.t0, p.t1))
            ]
        first = ps[0]
        a0 = self._curve(first.low, first.side, first.t0, first.t1)[1].Value(first.t0)
        b0 = self._curve(first.high, first.side, first.t0, first.t1)[1].Value(first.t0)
        if a0.Distance(b0) > self.verts.tol:
            edges.append(TopoDS.Edge(self._line(_pnt_xyz(a0), _pnt_xyz(b0)).Reversed()))
        return self._face_of(edges)

    def _face_of(self, edges: list[TopoDS_Edge]) -> TopoDS_Face:
        mw = BRepBuilderAPI_MakeWire()
        for e in edges:
            mw.Add(e)
        if not mw.IsDone():
            raise ExportError("could not close the outline of a planar face of the thick sheet")
        mk = BRepBuilderAPI_MakeFace(mw.Wire(), True)
        if not mk.IsDone():
            raise ExportError("a planar face of the thick sheet is not planar")
        plane = BRep_Tool.Surface_s(mk.Face()).Pln()
        mk = BRepBuilderAPI_MakeFace(aligned_plane(plane, mw.Wire()), mw.Wire(), True)
        return _with_pcurves(mk.Face())


def _with_pcurves(face: TopoDS_Face) -> TopoDS_Face:
    """``face`` (planar) with its edges' curves on the plane stored (OCC would
    compute them on the fly; its area integration needs them on slivers)."""
    ex = TopExp_Explorer(face, TopAbs_EDGE)
    while ex.More():
        BRepLib.BuildPCurveForEdgeOnPlane_s(TopoDS.Edge(ex.Current()), face)
        ex.Next()
    return face


def thick_solid(
    slab: Slab, tol: float, budget: KernelBudget | None = None
) -> tuple[bd.Solid, float]:
    """The solid bounded by ``slab``'s faces, its curves within ``tol`` (length).

    Returns:
        ``(solid, deviation)``: one build123d Solid (not yet checked for
        validity or volume) and the largest deviation of its edge curves.

    Raises:
        ExportError: a curve misses the tolerance, or the faces do not close
            into one shell.
    """
    budget = budget or KernelBudget(None, "")
    patches = slab_patches(slab)
    builder = _Builder(slab, tol, budget)
    builder.prepare(patches)
    # past a crease half, each sheet face is one planar face
    planar: dict[tuple[int, str, int], list[Patch]] = defaultdict(list)
    ruled: list[Patch] = []
    for p in patches:
        if p.face in ("s0", "s1") and (p.t1 <= 0.0 or p.t0 >= slab.total):
            planar[p.side, p.face, 0 if p.t1 <= 0.0 else 1].append(p)
        else:
            ruled.append(p)
    faces: list[TopoDS_Face] = []
    for p in ruled:
        budget.check()
        faces.append(builder.ruled(p))
    for group in planar.values():
        faces.append(builder.planar(group))
    shell = _sew(faces, builder.sew_tol, budget, slab)
    stretched = ShapeAnalysis_ShapeTolerance().Tolerance(shell, 1, TopAbs_EDGE)
    if stretched > max(tol, 1e-7):
        raise ExportError(
            f"sewing the thick sheet's faces stretched an edge's tolerance to {stretched:.2g} "
            f"(the curves are within {tol:.2g}): a face is thinner than the kernel resolves"
        )
    solid = BRepBuilderAPI_MakeSolid(shell).Solid()
    fix = ShapeFix_Solid(solid)
    fix.Perform()
    return bd.Solid(fix.Solid()), builder.deviation


def _sew(faces: list[TopoDS_Face], tol: float, budget: KernelBudget, slab: Slab):
    """Sew the faces into one shell, closing the outlines left open on the
    cutting planes (where the two sides' sections of y = 0 differ, and where
    the mitre planes cut the blocks past the creases) with planar faces."""
    for f in faces:
        BRepLib.SameParameter_s(f, tol)
    sewing = BRepBuilderAPI_Sewing(tol)
    for f in faces:
        sewing.Add(f)
    sewing.Perform()
    budget.check()
    shape = sewing.SewedShape()
    if sewing.NbFreeEdges():
        edges = TopTools_HSequenceOfShape()
        for i in range(1, sewing.NbFreeEdges() + 1):
            edges.Append(sewing.FreeEdge(i))
        wires = TopTools_HSequenceOfShape()
        ShapeAnalysis_FreeBounds.ConnectEdgesToWires_s(edges, tol, False, wires)
        again = BRepBuilderAPI_Sewing(tol)
        again.Add(shape)
        for i in range(1, wires.Length() + 1):
            w = TopoDS.Wire(wires.Value(i))
            mk = BRepBuilderAPI_MakeFace(
                aligned_plane(cutting_plane(w, slab, 10.0 * tol), w), w, True
            )
            if not mk.IsDone():
                raise ExportError("could not close a gap in the thick sheet's faces")
            again.Add(_with_pcurves(mk.Face()))
        again.Perform()
        budget.check()
        shape = again.SewedShape()
        if again.NbFreeEdges():
            raise ExportError(f"the thick sheet's faces leave {again.NbFreeEdges()} open edges")
    if shape.ShapeType() != TopAbs_SHELL:
        raise ExportError(f"sewing the thick sheet gave a {shape.ShapeType().name}, not one shell")
    return TopoDS.Shell(shape)
