"""Sheet material and fabrication inputs, and the bend formulas.

Lengths are in the design's unit; angles in degrees at the API edge. The
names follow build123d's sheet-metal vocabulary: ``thickness``,
``bend_radius``, ``k_factor`` and the reference surface ``sheet_surface``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.choice import Choice
from onefold_cad.geometry.validate import closed_interval, finite

if TYPE_CHECKING:
    from onefold_cad.geometry.bend import BendValues

__all__ = ["SheetSurface", "Units", "Material", "BendValues", "bend_values"]


class SheetSurface(Choice):
    """Which face of the sheet the designed (reference) surface is.

    INSIDE: the top (+z) face; the material lies below it.
    OUTSIDE: the bottom face; the material lies above it.
    MID: the mid-surface; half the thickness each way.
    """

    INSIDE = "INSIDE"
    OUTSIDE = "OUTSIDE"
    MID = "MID"


class Units(Choice):
    """Length unit of a design."""

    MM = "mm"
    IN = "in"
    FT = "ft"

    @property
    def mm(self) -> float:
        """Millimetres per unit (exact: 1 in = 25.4 mm, 1 ft = 304.8 mm)."""
        return {"mm": 1.0, "in": 25.4, "ft": 304.8}[self.value]

    def factor_to(self, other: Units | str) -> float:
        """The factor that turns a length in this unit into one in ``other``."""
        return self.mm / Units.parse(other).mm

    @property
    def mass_unit(self) -> str:
        """The unit masses are reported in: 'kg' for mm designs, 'lb' for inch
        and foot designs."""
        return "kg" if self is Units.MM else "lb"


@dataclass(frozen=True)
class Material:
    """Fabrication inputs (lengths in the design unit).

    Attributes:
        thickness: sheet thickness t >= 0; 0 means a zero-thickness surface.
        bend_radius: inside bend radius r >= 0.
        k_factor: neutral-axis position K in [0, 1].
        kerf: cutting kerf >= 0; cut contours are offset by kerf/2.
        relief_hole: diameter of the relief hole at the apex >= 0 (0 = none);
            None chooses the default: none for t = 0, 2 * t + 2 * r otherwise
            (at least 3 * t).
        density: kg/m^3 > 0 (e.g. 7850 for steel), or None; independent of
            the design's length unit (see :func:`onefold_cad.design.design_mass`).
        name: a material description for the notes (e.g. '304 stainless').
        sheet_surface: the reference surface (INSIDE, OUTSIDE, MID).
    """

    thickness: float = 0.0
    bend_radius: float = 0.0
    k_factor: float = 0.44
    kerf: float = 0.0
    relief_hole: float | None = None
    density: float | None = None
    name: str = ""
    sheet_surface: SheetSurface = SheetSurface.MID

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        for key in ("thickness", "bend_radius", "kerf"):
            v = finite(key, getattr(self, key))
            if v < 0.0:
                raise InvalidParameterError(key, f"must be >= 0, got {v:g}")
            set_(self, key, v)
        set_(self, "k_factor", closed_interval("k_factor", self.k_factor, 0.0, 1.0))
        if self.relief_hole is not None:
            v = finite("relief_hole", self.relief_hole)
            if v < 0.0:
                raise InvalidParameterError("relief_hole", f"must be >= 0 (0 = no hole), got {v:g}")
            set_(self, "relief_hole", v)
        if self.density is not None:
            v = finite("density", self.density)
            if v <= 0.0:
                raise InvalidParameterError("density", f"must be > 0, got {v:g}")
            set_(self, "density", v)
        set_(self, "sheet_surface", SheetSurface.parse(self.sheet_surface))
        set_(self, "name", str(self.name))

    @property
    def relief_hole_diameter(self) -> float:
        """The relief hole's diameter after applying the default (length)."""
        if self.relief_hole is not None:
            return self.relief_hole
        if self.thickness == 0.0:
            return 0.0
        return max(3.0 * self.thickness, 2.0 * (self.thickness + self.bend_radius))

    def with_changes(self, **changes: Any) -> Material:
        """A copy with some fields replaced (validated again)."""
        return replace(self, **changes)


def bend_values(angle_deg: float, material: Material, bend: str | None = None) -> BendValues:
    """The bend model's numbers for a bend of ``angle_deg`` in [0, 180) deg.

    One source: this calls :func:`onefold_cad.geometry.bend.bend_model`
    (setback SB = (r + s t) tan(psi/2), BA = psi (r + K t), BD = 2 SB - BA,
    shift SB - BA/2, with s the reference surface's place in the bend).

    Args:
        angle_deg: the fold angle psi from flat (deg).
        material: thickness, bend radius, K-factor and reference surface.
        bend: 'UP' or 'DOWN'. Needed for an INSIDE or OUTSIDE reference
            surface (the bend direction decides which face is inside); a MID
            reference is the same in both directions.
    """
    from onefold_cad.geometry.bend import bend_model

    psi = finite("angle_deg", angle_deg)
    if not 0.0 <= psi < 180.0:
        raise InvalidParameterError("angle_deg", f"must be in [0, 180) deg, got {angle_deg:g}")
    if bend is None:
        if material.sheet_surface is not SheetSurface.MID:
            raise InvalidParameterError(
                "bend",
                f"'UP' or 'DOWN' is needed for the {material.sheet_surface.value} reference "
                "surface: the bend direction decides whether it is the bend's inside or outside",
            )
        bend = "UP"
    return bend_model(psi, bend, material)


def __getattr__(name: str) -> Any:
    """``BendValues`` lives with the bend model (imported on first use: the
    bend model imports this module)."""
    if name == "BendValues":
        from onefold_cad.geometry.bend import BendValues

        return BendValues
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
