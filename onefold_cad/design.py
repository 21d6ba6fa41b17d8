"""A whole design: frame curve, sheet, model, material and units, and its fold.

This is what the adapters (STEP, DXF, previews, report) and the CLI consume.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.folding import FoldedSheet, fold
from onefold_cad.geometry.material import Material, Units
from onefold_cad.geometry.params import FrameCurve, Model, check_design_divisions
from onefold_cad.geometry.sheet import Sheet, boundary_distance
from onefold_cad.geometry.solver import solve
from onefold_cad.geometry.thick_sheet import min_relief_hole
from onefold_cad.geometry.validate import check_magnitudes

__all__ = ["Design", "build_design", "relief_hole_diameter", "sheet_inradius"]

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{0,63}$")


@dataclass(frozen=True, eq=False)
class Design:
    """Everything needed to solve and fabricate one One-Fold form.

    Attributes:
        name: file-safe design name (letters, digits, '.', '_', '-').
        frame: the frame curve (alpha, beta, h_c, radius, divisions).
        sheet: the flat sheet in the fold frame.
        model: 'exact' (default) or 'paper'.
        material: thickness, bend radius, K-factor, kerf, relief hole, density.
        units: the design's length unit.
        description: free text for reports and notes.
    """

    name: str
    frame: FrameCurve
    sheet: Sheet
    model: Model = Model.EXACT
    material: Material = field(default_factory=Material)
    units: Units = Units.MM
    description: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not _NAME.match(self.name):
            raise InvalidParameterError(
                "name",
                "must be 1-64 characters of letters, digits, '.', '_' or '-', "
                f"starting with a letter or digit, got {self.name!r}",
            )
        object.__setattr__(self, "model", Model.parse(self.model))
        object.__setattr__(self, "units", Units.parse(self.units))
        check_design_divisions(self.frame)
        check_magnitudes(self.frame.radius, self.sheet.size, self.material)
        hole = self.material.relief_hole_diameter
        if hole > 0.0:
            inner = sheet_inradius(self.sheet)
            if hole / 2.0 >= inner and self.material.relief_hole is None:
                raise InvalidParameterError(
                    "thickness",
                    f"{self.material.thickness:g} is too thick for this sheet: the default "
                    f"relief hole max(3 t, 2 (t + r)) = {hole:g} must be < {2.0 * inner:.6g} "
                    "(twice the distance from H to the nearest sheet edge); set a relief_hole",
                )
            if hole / 2.0 >= inner:
                raise InvalidParameterError(
                    "relief_hole",
                    f"diameter must be < {2.0 * inner:.6g} (twice the distance from H to the "
                    f"nearest sheet edge), got {hole:g}",
                )

    def with_changes(self, **changes: Any) -> Design:
        """A copy with some fields replaced (validated again)."""
        return replace(self, **changes)


def sheet_inradius(sheet: Sheet) -> float:
    """Distance from H to the nearest point of the sheet's boundary (length)."""
    return boundary_distance(sheet.vertices)


def relief_hole_diameter(design: Design, folded: FoldedSheet) -> float:
    """The relief hole every export cuts (length): the material's when it is
    set; else none for a zero-thickness sheet, and otherwise the larger of
    max(3 t, 2 (t + r)) and, for the exact model, 1.1 x the smallest hole a
    solid of that thickness needs (:func:`min_relief_hole`), rounded up to
    two significant digits."""
    m = design.material
    default = m.relief_hole_diameter
    if m.relief_hole is not None or m.thickness <= 0.0 or design.model.value != "exact":
        return default
    try:
        need = 1.1 * min_relief_hole(folded, m)
    except InvalidParameterError:  # no mitre (a flat fold): the solid will say so
        return default
    if need <= default:
        return default
    step = 10.0 ** (math.floor(math.log10(need)) - 1)
    return max(default, math.ceil(need / step - 1e-9) * step)


def build_design(design: Design) -> FoldedSheet:
    """Solve the direction-surface and fold the sheet of ``design``."""
    return fold(solve(design.frame, design.model), design.sheet)
