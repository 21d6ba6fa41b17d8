"""The flat pattern of a design: the 2D geometry a cutting table needs.

Everything here is plain numpy (:func:`~onefold_cad.fabrication.kerf.offset_outline`
gives the kerf's mitred offset); :mod:`onefold_cad.export.dxf.pattern` and
:mod:`onefold_cad.export.dxf.cut` only draw it (the DXF's NOTES text is
:mod:`onefold_cad.export.dxf.notes`'s). Lengths are in the design's
unit, angles in degrees, points in the sheet's own frame (for a rectangle: a
corner at the origin, sides on the axes).

Thickness compensation (t > 0, ``compensation='sharp'``). The designed surface
has a sharp crease; the real sheet bends with inside radius r. The bend model
(:mod:`onefold_cad.geometry.bend_model`, one source for every writer) gives each
crease half its shift SB - BA/2: each side of the blank moves that far towards
the fold line, perpendicular to it, so that the flat flanges land where the
design puts them. The fold line has two halves with their own angles; one
rigid move per side keeps every straight edge straight, so both sides move by
the **mean** of the two shifts (:func:`~onefold_cad.geometry.bend_model.blank_move`);
the blank's width error across each half, 2 (own shift - mean), is recorded
(:attr:`FlatPattern.move`) and written in the DXF's notes (0 for symmetric designs).
Inside each half's bend zone (within BA/2 of the fold line) the outline is
bridged by a straight segment from the upper side's edge at +BA/2 to the lower
side's edge at -BA/2 (from the moved crease end itself where the mean shift
puts it outside that half's zone); the fold half ends at that bridge. Past the limits of
:func:`~onefold_cad.fabrication.bend_checks.check_bends` the pattern is refused with
:class:`~onefold_cad.errors.FabricationError`; ``compensation='none'`` then
gives the uncompensated blank (the designed outline) and says so in the notes.
With t = 0 nothing is compensated (a zero-thickness surface creased sharp).

Kerf: the cut contours are offset by kerf/2, the outline outwards with
mitred corners (each edge moves exactly kerf/2), the relief hole inwards.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.choices import Compensation, Units
from onefold_cad.design import Design, derived
from onefold_cad.errors import FabricationError, InvalidParameterError, InvalidSheetError
from onefold_cad.fabrication.bend_checks import BendProblem, bend_error, check_bends
from onefold_cad.fabrication.blank import at_height, compensate, dedupe, ruling_segments
from onefold_cad.fabrication.kerf import offset_outline
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, relief_hole_problem
from onefold_cad.geometry.bend_model import (
    BendValues,
    BlankMove,
    bend_model,
    blank_move,
    crease_bends,
)
from onefold_cad.geometry.checks import shown
from onefold_cad.geometry.fan_folds import ruling_folds
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.nearby import near_any
from onefold_cad.geometry.numeric import Array, polygon_area
from onefold_cad.geometry.polygon import boundary_distance, check_simple

__all__ = ["flat_pattern", "flat_pattern_once", "FlatPattern", "FoldHalf", "FoldRuling"]


@dataclass(frozen=True)
class FoldHalf:
    """One half of the fold line on the flat pattern.

    Attributes:
        name: 'plus_x' or 'minus_x' (the crease half of :class:`CreaseHalf`).
        start: ``(2,)`` H, where both halves meet (sheet frame).
        end: ``(2,)`` where the half meets the outline (sheet frame).
        angle_deg: fold angle (deg), 0 = flat.
        bend: 'UP' or 'DOWN', seen from the drawing's (top, +z) side.
        zone: ``(k, 2, 2)`` bend-zone limit lines at +-BA/2 (k = 2, or 0 when
            nothing is compensated or BA = 0), each ``(start, end)`` in the
            sheet frame.
        values: the bend model of this half (reference surface, SB, BA, BD,
            shift); all 0 when t = 0.
        set_angle_deg: the angle the crease half is set to (deg): the fold
            angle plus the material's crease overbend
            (:meth:`~onefold_cad.geometry.material.Material.crease_set_angle`).
    """

    name: str
    start: Array
    end: Array
    angle_deg: float
    bend: str
    zone: Array
    values: BendValues
    set_angle_deg: float

    @property
    def layer(self) -> str:
        """'BEND_UP' or 'BEND_DOWN'."""
        return f"BEND_{self.bend}"

    @property
    def label(self) -> str:
        """Direction and angle, e.g. 'DOWN 125.23 deg' (with a crease overbend
        'UP 82.82 deg, set to 87.82': the angle to set it to)."""
        over = self.set_angle_deg != self.angle_deg
        return f"{self.bend} {self.angle_deg:.2f} deg" + (
            f", set to {self.set_angle_deg:.2f}" if over else ""
        )

    @property
    def allowance(self) -> float:
        """Bend allowance BA (length)."""
        return self.values.allowance

    @property
    def deduction(self) -> float:
        """Bend deduction BD = 2 SB - BA (length)."""
        return self.values.deduction


@dataclass(frozen=True)
class FoldRuling:
    """A ruling of the paper model's fan along which two planar triangles meet
    at an angle: a fold like the crease halves, drawn and listed like them
    (:func:`~onefold_cad.geometry.fan_folds.ruling_folds`). The blank does
    not compensate it: its bend model's width error is 2 x shift.

    Attributes:
        name: '+y ruling k' or '-y ruling k' (k-th counter-clockwise from the
            +x or the -x crease half).
        start: ``(2,)`` where the line starts on the blank (sheet frame):
            outside the relief hole and the crease's bend zones.
        end: ``(2,)`` where it meets the outline (sheet frame).
        angle_deg: its fold angle from flat (deg).
        bend: 'UP' or 'DOWN', seen from the drawing's (top, +z) side.
        values: its bend model (SB, BA, BD, shift).
    """

    name: str
    start: Array
    end: Array
    angle_deg: float
    bend: str
    values: BendValues

    @property
    def layer(self) -> str:
        """'BEND_UP' or 'BEND_DOWN'."""
        return f"BEND_{self.bend}"


@dataclass(frozen=True)
class FlatPattern:
    """The flat pattern of one design, in the sheet's own frame.

    Attributes:
        name: the design's name.
        units: the design's length unit.
        outline: ``(n, 2)`` the part's contour, CCW, thickness-compensated
            (the designed outline when nothing is compensated).
        cut_outline: ``(n, 2)`` the cutting path: ``outline`` offset outwards
            by kerf/2 (equal to ``outline`` when kerf = 0).
        apex: ``(2,)`` H, the apex point (centre of the relief hole).
        hole_diameter: the relief hole's diameter (0 = none).
        cut_hole_diameter: the hole's cutting path diameter (hole - kerf).
        halves: the fold halves ('plus_x', 'minus_x').
        rulings: ``(m, 2, 2)`` ruling segments for etching (off the fold
            line, outside the bend zones and the hole): every ruling of the
            exact model (the sheet bends smoothly along them) and the paper
            model's rulings that are no folds (inside one planar triangle).
        fold_rulings: the paper model's ruling folds (empty for the exact
            model), counter-clockwise from the +x crease half.
        fold_direction: ``(2,)`` unit vector of the fold line (H -> +x half).
        move: what the blank does about the bends (compensation, the shift
            per side, the width error across each half).
        problems: the limits of the sharp-crease compensation that the design
            passes (empty unless ``compensation='none'`` was asked for).
        material: the design's material.
        kerf: the kerf used (length).
        thickness: sheet thickness (length).
    """

    name: str
    units: Units
    outline: Array
    cut_outline: Array
    apex: Array
    hole_diameter: float
    cut_hole_diameter: float
    halves: tuple[FoldHalf, FoldHalf]
    rulings: Array
    fold_rulings: tuple[FoldRuling, ...]
    fold_direction: Array
    move: BlankMove
    problems: tuple[BendProblem, ...]
    material: Material
    kerf: float
    thickness: float

    @property
    def compensation(self) -> str:
        """'sharp' or 'none': how the blank accounts for the bends."""
        return self.move.compensation.value

    @property
    def shift(self) -> float:
        """How far each side moved towards the fold line (length)."""
        return self.move.shift

    @property
    def residual(self) -> float:
        """The compensation's largest error per side, max |own shift - shift| (length)."""
        return self.move.residual

    @property
    def area(self) -> float:
        """Net flat area: outline minus relief hole (length^2)."""
        return polygon_area(self.outline) - math.pi * self.hole_diameter**2 / 4.0

    @property
    def size(self) -> tuple[float, float]:
        """Bounding-box width and height of the outline (length)."""
        ext = np.ptp(self.outline, axis=0)
        return float(ext[0]), float(ext[1])

    @property
    def scale(self) -> float:
        """The larger bounding-box side (length), for mark and text sizes."""
        return max(self.size)


def _require_simple(polygon: Array, param: str, what: str) -> None:
    """FabricationError naming ``param`` unless ``polygon`` is simple."""
    try:
        check_simple(polygon, param)
    except InvalidSheetError as exc:
        raise FabricationError(param, f"{what} ({exc})") from None


def flat_pattern(
    design: Design, folded: FoldedSheet, compensation: Compensation | str = "sharp"
) -> FlatPattern:
    """Compute the flat pattern of ``design`` from its fold.

    Args:
        design: the design (sheet, material, units, name).
        folded: ``fold_design(design)`` (fold angles and bend directions).
        compensation: 'sharp' (default): each side moves by the bend model's
            shift, refused past the limits of
            :func:`~onefold_cad.fabrication.bend_checks.check_bends`; 'none': the
            uncompensated blank (the designed outline), said so in the notes.

    Raises:
        InvalidParameterError: 'folded' not from this design's sheet;
            'compensation' not 'sharp' or 'none'; 'kerf' when the kerf is too
            large for the blank or the hole.
        FabricationError: the relief hole does not fit the sheet or the
            compensated blank (:func:`~onefold_cad.fabrication.relief_hole.relief_hole_problem`,
            the writers' one check); a limit of the sharp-crease compensation
            is passed (the message names the crease half, its fold angle, the
            numbers and what to change).
    """
    if folded.sheet is not design.sheet:
        raise InvalidParameterError("folded", "must be fold_design(design) of this design")
    comp = Compensation.parse(compensation)
    sheet, mat = design.sheet, design.material
    v = np.asarray(sheet.vertices, dtype=float)
    k = sheet.minus_x_index
    tol = 1e-12 * sheet.size
    t = mat.thickness
    u = design.units.value
    hole_problem = relief_hole_problem(design, folded)
    if hole_problem is not None:
        raise hole_problem
    problems = check_bends(folded, mat, design.units)
    error = bend_error(problems)
    # a crease folded onto itself (check_bends gives it alone) has no bend model to write
    if error is not None and (comp is Compensation.SHARP or problems[0].kind == "closed"):
        raise error
    bends = crease_bends(folded, mat)
    sharp = comp is Compensation.SHARP and t > 0.0
    move = blank_move(bends, comp if t > 0.0 else Compensation.NONE)
    shift = move.shift
    c_plus, c_minus = (b.allowance / 2.0 for b in bends) if sharp else (0.0, 0.0)

    if sharp:
        up, lo = compensate(v, k, shift, c_plus, c_minus)
        outline = dedupe(np.vstack([up, lo]), tol)
        bridges = ((up[0], lo[-1], c_plus), (up[-1], lo[0], c_minus))  # from +y to -y
        end_plus, end_minus = (at_height(a, b, 0.0) for a, b, _ in bridges)
        zones = [
            np.array([[[0.0, c], at_height(a, b, c)], [[0.0, -c], at_height(a, b, -c)]])
            for a, b, c in bridges
        ]
        _require_simple(outline, "bend_radius", "the compensated outline is invalid")
    else:
        outline = v.copy()
        end_plus, end_minus = v[0].copy(), v[k].copy()
        zones = [np.zeros((0, 2, 2)), np.zeros((0, 2, 2))]
    zones = [z if z.size and abs(z[0, 0, 1]) > tol else np.zeros((0, 2, 2)) for z in zones]

    origin = np.zeros(2)
    if sharp:  # the hole fits the designed sheet (above); the compensated blank is narrower
        hole_problem = relief_hole_problem(design, folded, blank=outline)
        if hole_problem is not None:
            raise hole_problem
    inner = boundary_distance(outline, origin)
    hole = relief_hole_diameter(design, folded)
    kerf = mat.kerf
    if kerf > 0.0 and kerf / 2.0 >= inner:
        raise InvalidParameterError(
            "kerf",
            f"must be < {2.0 * inner:.6g} {u} (twice the distance from H to the nearest edge "
            f"of the blank), got {shown(kerf)} {u}",
        )
    if hole > 0.0 and kerf >= hole:
        raise InvalidParameterError(
            "kerf", f"must be < the relief hole's diameter {hole:g} {u}, got {shown(kerf)} {u}"
        )
    place = sheet.to_sheet
    outline_s = place.apply(outline)
    if kerf > 0.0:
        cut = offset_outline(outline_s, kerf / 2.0)
        try:
            check_simple(cut, "kerf")
        except InvalidSheetError as exc:
            raise InvalidParameterError(
                "kerf", f"the kerf offset self-intersects ({exc})"
            ) from None
    else:
        cut = outline_s.copy()

    halves = []
    for crease, end, b, z in zip(folded.crease, (end_plus, end_minus), bends, zones, strict=True):
        zone = place.apply(z.reshape(-1, 2)).reshape(-1, 2, 2)
        halves.append(
            FoldHalf(
                crease.name,
                place.apply(origin),
                place.apply(end),
                b.angle_deg,
                crease.bend,
                zone,
                b,
                mat.crease_set_angle(b.angle_deg),
            )
        )
    ends = folded.rulings_flat[:, 1]
    ends = ends[np.abs(ends[:, 1]) > 1e-9 * sheet.size]
    folds = ruling_folds(folded)
    fold_ends = np.array([f.end_flat for f in folds]).reshape(-1, 2)
    if len(folds):  # the rulings that are folds are drawn as bends, not etched
        ends = ends[~near_any(ends, fold_ends, 1e-12 * sheet.size)]  # memory O(n), not O(n^2)
    c_max, hole_r = max(c_plus, c_minus), max(hole - kerf, 0.0) / 2.0
    rul, _ = ruling_segments(ends, shift, c_max, hole_r)
    fold_segments, drawn = ruling_segments(fold_ends, shift, c_max, hole_r)
    fold_rulings = tuple(
        FoldRuling(
            f.name,
            place.apply(seg[0]),
            place.apply(seg[1]),
            f.angle_deg,
            f.bend,
            bend_model(f.angle_deg, f.bend, mat, half=f.name),
        )
        for f, seg in zip((folds[i] for i in drawn), fold_segments, strict=True)
    )
    return FlatPattern(
        name=design.name,
        units=design.units,
        outline=outline_s,
        cut_outline=cut,
        apex=place.apply(origin),
        hole_diameter=hole,
        cut_hole_diameter=hole - kerf if hole > 0.0 else 0.0,
        halves=(halves[0], halves[1]),
        rulings=place.apply(rul.reshape(-1, 2)).reshape(-1, 2, 2),
        fold_rulings=fold_rulings,
        fold_direction=place.apply_direction(np.array([1.0, 0.0])),
        move=move,
        problems=problems,
        material=mat,
        kerf=kerf,
        thickness=t,
    )


def flat_pattern_once(
    design: Design, folded: FoldedSheet, compensation: Compensation | str = "sharp"
) -> FlatPattern:
    """:func:`flat_pattern`, computed once per design, fold and compensation
    (the writers of one build share it; its refusal too)."""
    comp = Compensation.parse(compensation)
    return derived(
        design, ("flat_pattern", folded, comp), lambda: flat_pattern(design, folded, comp)
    )
