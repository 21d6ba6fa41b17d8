"""The relief hole at the apex: the diameter every export cuts and the one
check of it against the part around H (numpy only).

The default hole (no ``relief_hole`` set) is max(3 t, 2 (t + r))
(:func:`~onefold_cad.geometry.material.default_relief_hole`), and for a solid
of the exact model at least 1.1 x the smallest hole its offsets need.
Lengths are in the design's unit.
"""

from __future__ import annotations

import math

import numpy as np

from onefold_cad.design import Design, derived, fold_design
from onefold_cad.errors import FabricationError, InvalidParameterError
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material, sheet_offsets
from onefold_cad.geometry.polygon import boundary_distance
from onefold_cad.geometry.thick_map import min_relief_hole

__all__ = ["relief_hole_diameter", "relief_hole_problem", "solid_min_relief_hole"]


def solid_min_relief_hole(folded: FoldedSheet, material: Material) -> float:
    """The smallest relief hole a STEP solid of ``material`` needs on ``folded``
    (length): :func:`~onefold_cad.geometry.thick_map.min_relief_hole`,
    computed once per fold and material (the report, the default hole and
    the flat pattern all ask for it).

    Raises:
        InvalidParameterError: as ``min_relief_hole`` (e.g. a flat fold has
            no mitre; 'model' for the paper model).
    """
    # it depends on the material only through its faces' offsets (not on the
    # relief hole, which the callers may or may not have resolved yet)
    key = ("min_hole", sheet_offsets(material))
    return derived(folded, key, lambda: float(min_relief_hole(folded, material)))


def _solid_hole(design: Design, folded: FoldedSheet) -> float | None:
    """1.1 x the smallest hole a solid needs, rounded up to two significant
    digits in millimetres (so the physical hole does not depend on the
    design's unit), in the design's unit; None when no solid is made (paper
    model, t = 0) or the fold has no mitre."""
    m = design.material
    if m.thickness <= 0.0 or design.model.value != "exact":
        return None
    try:
        need_mm = 1.1 * solid_min_relief_hole(folded, m) * design.units.mm
    except InvalidParameterError:  # no mitre (a flat fold): the solid will say so
        return None
    step = 10.0 ** (math.floor(math.log10(need_mm)) - 1)
    return math.ceil(need_mm / step - 1e-9) * step / design.units.mm


def relief_hole_diameter(design: Design, folded: FoldedSheet) -> float:
    """The relief hole every export cuts (length): the material's when it is
    set; else none for a zero-thickness sheet, and otherwise the larger of
    max(3 t, 2 (t + r)) and, for the exact model, 1.1 x the smallest hole a
    solid of that thickness needs (:func:`solid_min_relief_hole`), rounded
    up to two significant digits in millimetres whatever the design's unit
    (13 mm, 0.51181... in)."""
    m = design.material
    default = m.relief_hole_diameter
    if m.relief_hole is not None:
        return default
    solid = _solid_hole(design, folded)
    return default if solid is None else max(default, solid)


def relief_hole_problem(
    design: Design, folded: FoldedSheet | None = None, blank: np.ndarray | None = None
) -> FabricationError | None:
    """The one check of the relief hole :func:`relief_hole_diameter` cuts
    against the part around H: the refusal every writer of the cut part (DXF,
    STEP, flat preview) gives when the hole does not fit, or None when it fits.

    Args:
        design: the design.
        folded: ``fold_design(design)`` (solved here when None).
        blank: ``(n, 2)`` the compensated blank's outline (fold frame), when
            checking the flat pattern's; None: the designed sheet.

    Returns:
        A FabricationError named after the relief hole when the user set it;
        for the default hole, after what made it that large: ``thickness`` (3 t,
        or the smallest hole a STEP solid of that thickness needs) or
        ``bend_radius`` (2 (t + r) with r > t / 2).
    """
    m, u = design.material, design.units.value
    folded = fold_design(design) if folded is None else folded
    hole = relief_hole_diameter(design, folded)
    outline = design.sheet.vertices if blank is None else blank
    inner = boundary_distance(outline)
    if not (hole > 0.0 and hole / 2.0 >= inner):
        return None
    edge = "sheet edge" if blank is None else "edge of the compensated blank"
    limit = f"{2.0 * inner:.6g} {u} (twice the distance from H to the nearest {edge})"
    if m.relief_hole is not None:
        return FabricationError("relief_hole", f"diameter {hole:g} {u} must be < {limit}")
    t, r = m.thickness, m.bend_radius
    if hole > m.relief_hole_diameter:  # raised for the STEP solid
        need = solid_min_relief_hole(folded, m)
        return FabricationError(
            "thickness",
            f"{t:g} {u} is too thick for this sheet: the default relief hole {hole:g} {u} "
            f"(1.1 x the {need:.4g} {u} a STEP solid of this thickness needs, rounded up) must "
            f"be < {limit}; set a smaller relief_hole (and --body shell), or a smaller thickness",
        )
    by_radius = 2.0 * (t + r) > 3.0 * t  # r > t / 2: the radius made the hole this large
    name, value, what = ("bend_radius", r, "large") if by_radius else ("thickness", t, "thick")
    return FabricationError(
        name,
        f"{value:g} {u} is too {what} for this sheet: the default relief hole max(3 t, 2 (t + r)) "
        f"= {hole:g} {u} must be < {limit}; set a relief_hole, or a smaller thickness or "
        "bend_radius",
    )
