"""The bend model beside the material it describes: one source for the DXF
blank, the STEP solid, the report and the bend table (numpy only, cheap: no
CAD library is imported).

The designed surface is the sheet's reference surface with a sharp crease. A
real sheet of thickness t bends along each crease half with inside radius r;
the neutral surface sits K t from the inside face. For a half of fold angle
psi (from flat) whose reference surface lies s t from the inside face of that
bend (s = 0, 1/2, 1: the reference is the inside, middle or outside face):

- setback        SB = (r + s t) tan(psi / 2): from the reference surface's
  sharp crease (its mould line) to where the flat flange meets the bend;
- bend allowance BA = psi (r + K t): the neutral surface's length in the bend;
- bend deduction BD = 2 SB - BA;
- shift          SB - BA / 2 = BD / 2: how far each side of the flat blank
  moves towards the fold line, so that the flat flanges land where the design
  puts them.

The bend direction decides which face is inside: UP (the sides rotate towards
the flat sheet's top face) puts the top face inside, DOWN the bottom face. The
reference surface's place across the thickness comes from
:func:`onefold_cad.geometry.material.sheet_offsets`, the same offsets the
STEP solid is built from. A fold angle lies in :data:`FOLD_ANGLE_RANGE_DEG`,
[0, 180) deg: at 180 deg the sheet lies folded onto itself and the set-back
is infinite.

A zero-thickness sheet (t = 0) is a surface creased sharp: every value is 0.

Lengths are in the design's unit, angles in degrees at the API.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

from onefold_cad.choices import Compensation, SheetSurface
from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.checks import finite, shown
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets

__all__ = [
    "FOLD_ANGLE_RANGE_DEG",
    "BendReference",
    "BendValues",
    "BlankMove",
    "bend_model",
    "bend_values",
    "bendable",
    "blank_move",
    "crease_bends",
    "fold_angle",
    "reference_fraction",
]

#: The fold angles psi from flat (deg) the bend model takes: [lo, hi), 0 flat,
#: 180 the sheet folded onto itself (tan(psi / 2) infinite).
FOLD_ANGLE_RANGE_DEG = (0.0, 180.0)

_DIRECTIONS = ("UP", "DOWN")


def bendable(angle_deg: float) -> bool:
    """Whether the bend model takes the fold angle ``angle_deg`` (deg): in
    :data:`FOLD_ANGLE_RANGE_DEG` (a crease folded flat onto itself, 180 deg,
    has no bend allowance or set-back)."""
    lo, hi = FOLD_ANGLE_RANGE_DEG
    return bool(lo <= angle_deg < hi)


def fold_angle(angle_deg: float, name: str = "angle_deg") -> float:
    """``angle_deg`` as a float, if it is a fold angle in
    :data:`FOLD_ANGLE_RANGE_DEG` (the one check of that range).

    Raises:
        InvalidParameterError: naming ``name``, with the range.
    """
    psi = finite(name, angle_deg)
    if not bendable(psi):
        lo, hi = FOLD_ANGLE_RANGE_DEG
        raise InvalidParameterError(
            name, f"must be in [{lo:g}, {hi:g}) deg, got {shown(angle_deg)}"
        )
    return psi


class BendReference(StrEnum):
    """Where the reference surface lies across the thickness in one bend."""

    INSIDE = "INSIDE"
    MID = "MID"
    OUTSIDE = "OUTSIDE"


@dataclass(frozen=True)
class BendValues:
    """The bend model's numbers for one bend (one crease half).

    Attributes:
        half: 'plus_x' or 'minus_x' ('' for a bend not tied to a crease half).
        angle_deg: fold angle psi from flat (deg).
        direction: 'UP' (top face inside the bend) or 'DOWN' (bottom face inside).
        reference: the reference surface's place in this bend.
        s: the reference surface's distance from the inside face, in thicknesses.
        thickness: t (length).
        radius: inside bend radius r (length); 0 for a zero-thickness sheet.
        k_factor: K.
        allowance: BA = psi (r + K t) (length).
        setback: SB = (r + s t) tan(psi / 2) (length).
        outside_setback: OSSB = (r + t) tan(psi / 2), the outside mould line's
            set-back (length), for shops that work from it.
        deduction: BD = 2 SB - BA (length).
        shift: SB - BA / 2, how far each side moves towards the fold line
            (length; negative: the blank grows).
    """

    half: str
    angle_deg: float
    direction: str
    reference: BendReference
    s: float
    thickness: float
    radius: float
    k_factor: float
    allowance: float
    setback: float
    outside_setback: float
    deduction: float
    shift: float

    @property
    def included_deg(self) -> float:
        """The angle between the two flanges (deg): 180 - psi."""
        return 180.0 - self.angle_deg

    @property
    def inside_face(self) -> str:
        """'top' or 'bottom': the flat sheet's face that ends inside the bend."""
        return "top" if self.direction == "UP" else "bottom"


def reference_fraction(material: Material, direction: str) -> float:
    """s: the reference surface's distance from the inside face of a bend in
    ``direction`` ('UP' or 'DOWN'), in thicknesses (0, 1/2 or 1).

    Read from :func:`~onefold_cad.geometry.material.sheet_offsets`: the
    faces lie at (lo, hi) along the top normal; UP puts the top face (hi)
    inside, DOWN the bottom face (lo)."""
    if direction not in _DIRECTIONS:
        raise InvalidParameterError("bend", f"must be 'UP' or 'DOWN', got {direction!r}")
    lo, hi = sheet_offsets(material.with_changes(thickness=1.0))
    return hi if direction == "UP" else -lo


def bend_model(angle_deg: float, direction: str, material: Material, half: str = "") -> BendValues:
    """The bend model for a fold angle ``angle_deg`` in :data:`FOLD_ANGLE_RANGE_DEG`
    bent ``direction`` ('UP'/'DOWN') in ``material`` (see the module docstring)."""
    psi = math.radians(fold_angle(angle_deg))
    s = reference_fraction(material, direction)
    t, k = material.thickness, material.k_factor
    r = material.bend_radius if t > 0.0 else 0.0
    tan = math.tan(psi / 2.0)
    ba = psi * (r + k * t)
    sb = (r + s * t) * tan
    ref = (BendReference.INSIDE, BendReference.MID, BendReference.OUTSIDE)[round(2.0 * s)]
    return BendValues(
        half=half,
        angle_deg=math.degrees(psi),
        direction=direction,
        reference=ref,
        s=s,
        thickness=t,
        radius=r,
        k_factor=k,
        allowance=ba,
        setback=sb,
        outside_setback=(r + t) * tan,
        deduction=2.0 * sb - ba,
        shift=sb - ba / 2.0,
    )


def bend_values(angle_deg: float, material: Material, bend: str | None = None) -> BendValues:
    """The bend model's numbers for a bend of ``angle_deg`` in [0, 180) deg.

    One source: this calls :func:`bend_model` (setback SB = (r + s t)
    tan(psi/2), BA = psi (r + K t), BD = 2 SB - BA, shift SB - BA/2, with s
    the reference surface's place in the bend).

    Args:
        angle_deg: the fold angle psi from flat (deg).
        material: thickness, bend radius, K-factor and reference surface.
        bend: 'UP' or 'DOWN'. Needed for an INSIDE or OUTSIDE reference
            surface (the bend direction decides which face is inside); a MID
            reference is the same in both directions.

    Returns:
        The setback, allowance, deduction and shift (the material's length
        unit) and the angle.

    Raises:
        InvalidParameterError: an angle outside [0, 180) deg, or no ``bend``
            for an INSIDE or OUTSIDE reference surface.
    """
    psi = fold_angle(angle_deg)
    if bend is None:
        if material.sheet_surface is not SheetSurface.MID:
            raise InvalidParameterError(
                "bend",
                f"'UP' or 'DOWN' is needed for the {material.sheet_surface.value} reference "
                "surface: the bend direction decides whether it is the bend's inside or outside",
            )
        bend = "UP"
    return bend_model(psi, bend, material)


def crease_bends(folded: FoldedSheet, material: Material) -> tuple[BendValues, BendValues]:
    """The bend model of both crease halves ('plus_x', 'minus_x')."""
    a, b = (bend_model(c.fold_angle_deg, c.bend, material, half=c.name) for c in folded.crease)
    return a, b


@dataclass(frozen=True)
class BlankMove:
    """What the flat blank does about the bends: one rigid move per side.

    Both crease halves lie on one straight fold line and each side of the
    blank is one rigid piece, so a side cannot move by two different amounts
    along the two halves. The blank moves each side by the **mean** of the two
    halves' shifts, which halves the largest error.

    Attributes:
        compensation: 'sharp' or 'none'.
        shift: how far each side moved towards the fold line (length; 0 for 'none').
        errors: per half ('plus_x', 'minus_x'), the blank's width across that
            half minus the width the bend model asks for: 2 (own shift -
            shift) (length; > 0: the blank is too wide there).
    """

    compensation: Compensation
    shift: float
    errors: tuple[float, float]

    @property
    def residual(self) -> float:
        """The largest error per side, max |own shift - shift| (length)."""
        return max(abs(e) for e in self.errors) / 2.0


def blank_move(
    bends: tuple[BendValues, BendValues], compensation: Compensation | str = Compensation.SHARP
) -> BlankMove:
    """The move of each side of the blank for the two crease halves' bends."""
    comp = Compensation.parse(compensation)
    shift = 0.5 * (bends[0].shift + bends[1].shift) if comp is Compensation.SHARP else 0.0
    e0, e1 = (2.0 * (b.shift - shift) for b in bends)
    return BlankMove(comp, shift, (e0, e1))
