"""The paper fan a FOLD file folds: few divisions, its crease the design's.

Simulators fold a FOLD file with explicit solvers that a vertex of many
edges makes unstable (docs/formats.md, "vertex load"), so the file cannot
hold the design's 90 divisions a side (nor the exact cone's infinitely
many). It folds a fan of :func:`fold_divisions` divisions a side over the
design's frame curve at the design's own apex, *tangent-ended*
(:func:`onefold_cad.geometry.tangent_fan.tangent_ended`): the wedge beside
each crease half lies in the design's tangent plane along it, so the file's
crease folds as the design's (to rounding), and the directions between are
moved off the division points just enough for the angle condition to hold
exactly (the folded frame is isometric to the crease pattern).

A fan over division points on the curve (the file before) folded its crease
shallower: each wedge beside the crease is the chord plane of its stretch of
the cone, turned from the tangent plane by about k_g x gamma / 2; 10 equal
divisions folded it 16 to 22 deg less than the design.

Without a relief hole the fan is also *graded*
(:meth:`onefold_cad.geometry.arc.ArcSpacing.graded`): its division points
are spaced in arc parameter by widths growing by :data:`GRADING_RATIO` from
each end of the arc up to an even width between, the wedge beside each
crease half as narrow as the mesh's bounds let it be: a flat angle at H of
:data:`CREASE_WEDGE_DEG` (the face-angle bound
``fold_mesh.MIN_FACE_ANGLE_DEG`` with 1 % to spare); a paper-model design
keeps its own first division where that is wider. The narrow wedges keep
the file close to the design's surface near the crease.

A design with a relief hole is graded gently: its file's fan has
:data:`HOLE_DIVISIONS` divisions a side (a paper-model design of fewer is
its own fan), the first and last :data:`HOLE_FIRST_WIDTH` of the arc wide,
growing by :data:`HOLE_GRADING_RATIO`. The hole is cut as the polygon of its
crossings with the rays, so a narrow wedge gives it a side 2 r sin(gamma /
2) short against the sheet; Origami Simulator's explicit solver went NaN on
such sides (broken-vault, 2.5e-5 of the size), crept (patkau-one-fold 41 %
from its form after 160 000 steps) or, with the sides held at 2e-4 of the
size, settled broken-vault with a crease folded the wrong way
(docs/formats.md, "Relief hole"); it folded 10 equal divisions right. A
tangent-ended wedge leaves the cone by about k_g gamma^2 / 2 at its far
ray, so equal divisions (18 deg) would put the file 3.9 to 4.5 % of the
sheet's size from the design's fold; 11 to 12 deg wedges beside the crease
keep it near 1.5 % and the hole's sides over 2.8e-4 of the size, and
Origami Simulator folds them (patkau-one-fold 0.76 %, broken-vault 1.15 %
of the size from the file's form after 160 000 steps, no crease the wrong
way: docs/formats.md).

A fan the tangent-ended construction cannot make (fewer than
``tangent_fan.MIN_DIVISIONS`` divisions, asked for with
``fold_data(divisions=...)``) is the plain fan over the division points,
solved for its own apex; :func:`fold_note` then says how far its crease is
from the design's, in the file and the build's report.
"""

from __future__ import annotations

import math

import numpy as np

from onefold_cad.choices import Model
from onefold_cad.design import Design, derived
from onefold_cad.errors import InvalidParameterError, NoSolutionError
from onefold_cad.export.fold_mesh import MIN_FACE_ANGLE_DEG
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.geometry.arc import ArcSpacing
from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.folding import FoldedSheet, fold
from onefold_cad.geometry.frame_curve import FrameCurve
from onefold_cad.geometry.solver import Solution, solve
from onefold_cad.geometry.tangent_fan import MIN_DIVISIONS, tangent_ended

__all__ = [
    "CREASE_TOLERANCE_DEG",
    "CREASE_WEDGE_DEG",
    "FOLD_DIVISIONS",
    "GRADING_RATIO",
    "HOLE_DIVISIONS",
    "HOLE_FIRST_WIDTH",
    "HOLE_GRADING_RATIO",
    "fold_divisions",
    "fold_fan",
    "fold_note",
    "fold_spacing",
]

#: The FOLD file's divisions per side without a relief hole: a paper-model
#: design of at most this many is written as its own fan (exact; 32 equal
#: rays at H, a vertex load of 13.5 at most), every other design as a graded
#: fan of this many (a load of at most 7.5 on the templates: its narrow
#: wedges' short edges shorten the simulator's step).
FOLD_DIVISIONS = 16
#: With a relief hole: the file's fan has this many divisions a side, gently
#: graded (a paper-model design of fewer is its own fan; see the module notes).
HOLE_DIVISIONS = 10
#: With a relief hole: the first and last wedges' share of the arc (an even
#: fan's is 1 / HOLE_DIVISIONS) and the growth of the widths between.
HOLE_FIRST_WIDTH = 0.06
HOLE_GRADING_RATIO = 1.6
#: The growth of the graded fan's wedge widths (arc parameter) from each
#: end of the arc towards the even width between.
GRADING_RATIO = 3.0
#: The flat angle at H (deg) of the wedge beside each crease half, where
#: nothing asks for a wider one: the mesh's face-angle bound, 1 % above.
CREASE_WEDGE_DEG = 1.01 * MIN_FACE_ANGLE_DEG
#: A file whose crease halves fold more than this (deg) away from the
#: design's says so (:func:`fold_note`), in the file and the build's report.
CREASE_TOLERANCE_DEG = 1.0
#: Rounds of the first widths' fit to their flat angles (each a 16-division solve).
_FIT_ROUNDS = 5


def fold_divisions(design: Design, folded: FoldedSheet) -> int:
    """The FOLD file's own division count: :data:`FOLD_DIVISIONS`, or with a
    relief hole :data:`HOLE_DIVISIONS`; a paper-model design's own
    ``divisions`` where fewer."""
    hole = relief_hole_diameter(design, folded) > 0.0
    most = HOLE_DIVISIONS if hole else FOLD_DIVISIONS
    n = design.frame.divisions
    return min(n, most) if design.model is Model.PAPER else most


def fold_spacing(design: Design, folded: FoldedSheet, n: int) -> ArcSpacing:
    """The graded spacing of the file's fan of ``n`` divisions, growing by
    :data:`GRADING_RATIO` (a design without a relief hole): a paper design's
    own first and last arc steps (1 / divisions of the arc) where their
    wedges are at least :data:`CREASE_WEDGE_DEG` wide, else (and for the
    exact model) first widths fitted so that the wedges beside the crease
    halves have that flat angle (to 0.2 %) in the fan the file folds
    (:func:`_file_fan`).

    Raises:
        NoSolutionError: a trial fan has no apex.
    """
    target = np.radians(np.full(2, CREASE_WEDGE_DEG))
    frame = design.frame.with_changes(divisions=n)
    surface = folded.solution.surface
    if isinstance(surface, PaperFan):
        first = np.full(2, 1.0 / design.frame.divisions)
    else:  # the flat angles are about the arc's share of pi
        first = target / math.pi
    first = np.minimum(first, 1.0 / n)
    paper = isinstance(surface, PaperFan)
    for _ in range(_FIT_ROUNDS):
        spacing = ArcSpacing.graded(n, (float(first[0]), float(first[1])), GRADING_RATIO)
        graded = _file_fan(frame, spacing, folded.solution).surface
        assert isinstance(graded, PaperFan) and graded.gammas is not None
        gammas = graded.gammas
        ends = gammas[[0, -1]]
        wide = ends >= target
        if np.all(wide) and (paper or np.all(ends <= 1.002 * target)):
            break
        # aim 0.1 % above the target: the flat angle grows about as the width
        grow = np.where(wide & paper, 1.0, 1.001 * target / ends)
        first = np.minimum(first * grow, 1.0 / n)
    return spacing


def fold_fan(design: Design, folded: FoldedSheet, divisions: int | None = None) -> FoldedSheet:
    """The paper-model fan the FOLD file triangulates: ``folded`` itself when
    it is a paper-model design's and ``divisions`` (None:
    :func:`fold_divisions`) is its own; otherwise the paper fan over the
    design's frame curve with ``divisions`` triangles per side (None:
    :func:`fold_divisions`), graded (:func:`fold_spacing`) unless the design
    has a relief hole, solved for its own apex and folded; once per design,
    fold and division count (the build's note and the file share it). See
    the module notes.

    Raises:
        InvalidParameterError: ('divisions') the fan of that many divisions has
            no non-trivial apex (always so for 1 division).
    """
    own = design.frame.divisions
    n = fold_divisions(design, folded) if divisions is None else divisions
    if isinstance(folded.solution.surface, PaperFan) and n == own:
        return folded
    return derived(design, ("fold_fan", folded, n), lambda: _fold_fan(design, folded, n))


def _file_fan(frame: FrameCurve, spacing: ArcSpacing | None, design: Solution) -> Solution:
    """The fan over ``frame`` (its divisions) the file folds: tangent-ended
    at the design's apex where it can be (:func:`tangent_ended`), else the
    plain fan over the division points at its own apex (see the module notes).

    Raises:
        NoSolutionError: the plain fan has no apex.
    """
    if frame.divisions >= MIN_DIVISIONS:
        try:
            return tangent_ended(frame, spacing, design)
        except ValueError:
            pass  # the plain fan below; fold_note says how far its crease is
    return solve(frame, Model.PAPER, spacing)


def _fold_fan(design: Design, folded: FoldedSheet, n: int) -> FoldedSheet:
    """:func:`fold_fan`'s fan of ``n`` divisions, computed."""
    hole = relief_hole_diameter(design, folded) > 0.0
    try:
        spacing = (
            ArcSpacing.graded(n, (min(HOLE_FIRST_WIDTH, 1.0 / n),) * 2, HOLE_GRADING_RATIO)
            if hole
            else fold_spacing(design, folded, n)
        )
        frame = design.frame.with_changes(divisions=n)
        return fold(_file_fan(frame, spacing, folded.solution), design.sheet)
    except NoSolutionError:
        raise InvalidParameterError(
            "divisions",
            f"the FOLD file folds the paper fan of {n} triangles per side over this "
            "frame curve, which has no non-trivial apex for this frame; use more "
            "divisions (at least 2)",
        ) from None


def fold_note(design: Design, folded: FoldedSheet, divisions: int | None = None) -> str | None:
    """The line the FOLD file (``onefold:notes``) and the build's report
    hold when the file's crease halves (:func:`fold_fan` of ``divisions``)
    fold more than :data:`CREASE_TOLERANCE_DEG` away from the design's, with
    both halves' fold angles in degrees (the file's and the design's); None
    otherwise. Shown, never silent: the file is a model for simulators, the
    DXF and STEP carry the design's angles."""
    fan = fold_fan(design, folded, divisions)
    if fan is folded:
        return None
    pairs = zip(fan.crease, folded.crease, strict=True)
    gap = max(abs(a.fold_angle_deg - b.fold_angle_deg) for a, b in pairs)
    if gap <= CREASE_TOLERANCE_DEG:
        return None
    surface = fan.solution.surface
    assert isinstance(surface, PaperFan) and surface.gammas is not None
    n = len(surface.gammas)
    kind = f"a fan of {n}" if surface.spacing is None else f"a graded fan of {n}"
    own = " / ".join(f"{h.fold_angle_deg:.2f}" for h in folded.crease)
    file = " / ".join(f"{h.fold_angle_deg:.2f}" for h in fan.crease)
    return (
        f"the .fold file folds {kind} divisions a side over the frame curve at its "
        f"own apex: its crease halves fold {file} deg, the design's {own} deg, "
        f"more than {CREASE_TOLERANCE_DEG:g} deg apart (docs/formats.md, 'Which polyhedron')"
    )
