"""Sheet material and fabrication inputs, and where the sheet's faces lie.

Lengths are in the design's unit; angles in degrees at the API edge. The
names follow build123d's sheet-metal vocabulary: ``thickness``,
``bend_radius``, ``k_factor`` and the reference surface ``sheet_surface``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from onefold_cad.choices import SheetSurface
from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.checks import closed_interval, finite

__all__ = ["Material", "default_relief_hole", "sheet_offsets"]


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
            the design's length unit (see :func:`onefold_cad.fabrication.mass.design_mass`).
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
        return default_relief_hole(self.thickness, self.bend_radius)

    def with_changes(self, **changes: Any) -> Material:
        """A copy with some fields replaced (validated again)."""
        return replace(self, **changes)


#: Where the sheet's faces lie for each reference surface, in thicknesses
#: along the top normal from the reference surface.
_S_RANGE = {
    SheetSurface.INSIDE: (-1.0, 0.0),
    SheetSurface.OUTSIDE: (0.0, 1.0),
    SheetSurface.MID: (-0.5, 0.5),
}


def sheet_offsets(material: Material) -> tuple[float, float]:
    """The sheet's two faces as signed distances from the reference surface
    along its top normal (length): INSIDE (-t, 0), OUTSIDE (0, t), MID (-t/2, t/2)."""
    lo, hi = _S_RANGE[material.sheet_surface]
    return lo * material.thickness, hi * material.thickness


def default_relief_hole(thickness: float, bend_radius: float) -> float:
    """The default relief hole's diameter before a solid's needs (length):
    none for a zero-thickness sheet, else max(3 t, 2 (t + r)). The one home of
    that rule (:attr:`Material.relief_hole_diameter`, the fabrication checks)."""
    if thickness == 0.0:
        return 0.0
    return max(3.0 * thickness, 2.0 * (thickness + bend_radius))
