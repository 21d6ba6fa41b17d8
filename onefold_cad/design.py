"""A whole design: frame curve, sheet, model, material and units, and its fold.

This is what the adapters (STEP, DXF, previews, report) and the CLI consume.
A design holds geometry and fabrication inputs; it never refuses a value for
a fabrication reason (a relief hole too large for the sheet, an implausible
density): :func:`fabrication_warnings` names those, ``solve`` prints them and
the writers refuse.
"""

from __future__ import annotations

import math
import re
import threading
import weakref
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from onefold_cad.errors import FabricationError, InvalidParameterError, OneFoldError
from onefold_cad.geometry.bend import Compensation, bend_error, check_bends
from onefold_cad.geometry.folding import FoldedSheet, fold
from onefold_cad.geometry.material import Material, Units
from onefold_cad.geometry.params import FrameCurve, Model, check_design_divisions
from onefold_cad.geometry.placement import RestingPlacement, rest_form
from onefold_cad.geometry.sheet import Sheet, boundary_distance
from onefold_cad.geometry.solver import solve
from onefold_cad.geometry.thick_sheet import min_relief_hole, sheet_offsets
from onefold_cad.geometry.validate import check_magnitudes

__all__ = [
    "KG_PER_LB",
    "Design",
    "Mass",
    "build_design",
    "default_body",
    "design_mass",
    "fabrication_warnings",
    "relief_hole_diameter",
    "relief_hole_problem",
    "resting_placement",
    "sheet_inradius",
    "solid_bend_problem",
    "solid_min_relief_hole",
]

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{0,63}$")

#: Kilograms per pound (the international avoirdupois pound, exact by definition).
KG_PER_LB = 0.45359237

#: Densities (kg/m^3) outside this range are not those of a sheet material: lighter
#: than air, or denser than osmium (22 590 kg/m^3), the densest element.
PLAUSIBLE_DENSITY = (1.0, 23_000.0)


@dataclass(frozen=True, eq=False)
class Design:
    """Everything needed to solve and fabricate one One-Fold form.

    Attributes:
        name: file-safe design name (letters, digits, '.', '_', '-').
        frame: the frame curve (alpha, beta, h_c, radius, divisions).
        sheet: the flat sheet in the fold frame.
        model: 'exact' (default) or 'paper'.
        material: thickness, bend radius, K-factor, kerf, relief hole, density.
        units: the design's length unit: every length of ``frame``, ``sheet``
            and ``material`` is in it (the density is in kg/m^3 whatever it is).
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

    def with_changes(self, **changes: Any) -> Design:
        """A copy with some fields replaced (validated again)."""
        return replace(self, **changes)

    def in_units(self, units: Units | str) -> Design:
        """The same design with every length converted into ``units``.

        Converted: the frame's radius and h_c, the sheet (its inputs, so a
        rectangle stays a rectangle), the thickness, bend radius, kerf and
        an explicit relief hole. Angles, divisions, the K-factor and the
        density (kg/m^3) do not depend on the length unit. The factor is
        ``Units.factor_to`` (1 in = 25.4 mm, 1 ft = 304.8 mm exactly).
        """
        to = Units.parse(units)
        if to is self.units:
            return self
        f = self.units.factor_to(to)
        fr, m = self.frame, self.material
        frame = fr.with_changes(radius=fr.radius * f, h_c=fr.h_c * f)
        material = m.with_changes(
            thickness=m.thickness * f,
            bend_radius=m.bend_radius * f,
            kerf=m.kerf * f,
            relief_hole=None if m.relief_hole is None else m.relief_hole * f,
        )
        return replace(
            self, frame=frame, sheet=_scaled_sheet(self.sheet, f), material=material, units=to
        )


def _scaled_sheet(sheet: Sheet, f: float) -> Sheet:
    """``sheet`` with every length multiplied by ``f``, rebuilt from its inputs."""
    inputs = sheet.inputs
    if sheet.kind == "rectangle":
        return Sheet.rectangle(
            float(inputs["width"]) * f,  # type: ignore[arg-type]
            float(inputs["height"]) * f,  # type: ignore[arg-type]
            float(inputs["apex_fraction"]),  # type: ignore[arg-type]
        )
    if sheet.kind == "quadrilateral":
        return Sheet.quadrilateral(**{k: float(v) * f for k, v in inputs.items()})  # type: ignore[arg-type]
    points = np.asarray(inputs.get("polygon", sheet.vertices), dtype=float) * f
    return Sheet.polygon(points, name="polygon")


def sheet_inradius(sheet: Sheet) -> float:
    """Distance from H to the nearest point of the sheet's boundary (length)."""
    return boundary_distance(sheet.vertices)


#: Results computed once per fold: the fold's identity holds them (freed with
#: the fold), keyed by what else they depend on; each a value or the
#: OneFoldError it raised.
_PER_FOLD: weakref.WeakKeyDictionary[FoldedSheet, dict[Any, Any]] = weakref.WeakKeyDictionary()
_PER_FOLD_LOCK = threading.Lock()


def _once_per_fold(folded: FoldedSheet, key: Any, compute: Any) -> Any:
    """``compute()`` the first time ``(folded, key)`` is asked for, then its result
    (or the OneFoldError it raised) again."""
    with _PER_FOLD_LOCK:
        known = _PER_FOLD.setdefault(folded, {}).get(key, _MISSING)
    if known is _MISSING:
        try:
            known = compute()
        except OneFoldError as exc:
            known = exc
        with _PER_FOLD_LOCK:
            _PER_FOLD.setdefault(folded, {})[key] = known
    if isinstance(known, Exception):
        raise known
    return known


_MISSING = object()


def solid_min_relief_hole(folded: FoldedSheet, material: Material) -> float:
    """The smallest relief hole a STEP solid of ``material`` needs on ``folded``
    (length): :func:`~onefold_cad.geometry.thick_sheet.min_relief_hole`,
    computed once per fold and material (the report, the default hole and
    the flat pattern all ask for it).

    Raises:
        InvalidParameterError: as ``min_relief_hole`` (e.g. a flat fold has
            no mitre; 'model' for the paper model).
    """
    # it depends on the material only through its faces' offsets (not on the
    # relief hole, which the callers may or may not have resolved yet)
    key = ("min_hole", sheet_offsets(material))
    return _once_per_fold(folded, key, lambda: float(min_relief_hole(folded, material)))


def resting_placement(
    design: Design, folded: FoldedSheet, body: str | None = None
) -> RestingPlacement:
    """How the body the STEP holds (``body``, default :func:`default_body`)
    stands on the ground: :func:`~onefold_cad.geometry.placement.rest_form`
    with the material's relief hole resolved (:func:`relief_hole_diameter`),
    computed once per fold, material and body. The report, the STEP, the GLB
    and the previews all place the form with it.

    A relief hole that does not fit the sheet (:func:`relief_hole_problem`,
    which every writer of the part refuses and ``solve`` warns about) leaves
    no part to stand: the form is then placed as the sheet without a hole, on
    its reference surface."""
    body = default_body(design) if body is None else body
    m = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    if relief_hole_problem(design, folded) is not None:
        m, body = m.with_changes(relief_hole=0.0), "shell"
    return _once_per_fold(folded, ("rest", m, body), lambda: rest_form(folded, m, body))


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


@dataclass(frozen=True)
class Mass:
    """The mass of the cut part.

    Attributes:
        value: the mass, in ``unit``.
        unit: 'kg' (mm designs) or 'lb' (inch and foot designs).
        density: the density used, kg/m^3.
    """

    value: float
    unit: str
    density: float

    def __str__(self) -> str:
        return f"{self.value:.6g} {self.unit} (density {self.density:g} kg/m^3)"


def design_mass(design: Design, net_area: float) -> Mass | None:
    """The mass of a part of ``net_area`` (design unit^2) cut from the design's
    sheet, or None without a density or thickness. The one mass formula:
    density (kg/m^3) x thickness x area, the volume converted to m^3 with the
    design unit's length in metres; reported in kg for mm designs and in lb
    (1 lb = 0.45359237 kg) for inch and foot designs."""
    m = design.material
    if m.density is None or m.thickness <= 0.0:
        return None
    metres = design.units.mm / 1000.0
    kg = m.density * m.thickness * net_area * metres**3
    unit = design.units.mass_unit
    return Mass(kg if unit == "kg" else kg / KG_PER_LB, unit, m.density)


def relief_hole_problem(
    design: Design, folded: FoldedSheet | None = None, blank: np.ndarray | None = None
) -> FabricationError | None:
    """The one check of the relief hole :func:`relief_hole_diameter` cuts
    against the part around H: the refusal every writer of the cut part (DXF,
    STEP, flat preview) gives when the hole does not fit, or None when it fits.

    Args:
        design: the design.
        folded: ``build_design(design)`` (solved here when None).
        blank: ``(n, 2)`` the compensated blank's outline (fold frame), when
            checking the flat pattern's; None: the designed sheet.

    Returns:
        A FabricationError named after the relief hole when the user set it;
        for the default hole, after what made it that large: ``thickness`` (3 t,
        or the smallest hole a STEP solid of that thickness needs) or
        ``bend_radius`` (2 (t + r) with r > t / 2).
    """
    m, u = design.material, design.units.value
    folded = build_design(design) if folded is None else folded
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


def solid_bend_problem(
    design: Design, folded: FoldedSheet, compensation: Compensation | str = Compensation.SHARP
) -> FabricationError | None:
    """The one check of a STEP solid against the bend model's limits
    (:func:`~onefold_cad.geometry.bend.check_bends`): the refusal every
    writer of the solid (STEP, GLB, the explorer's STEP download) gives, or
    None. Past those limits the solid does not stand for the bent part; with
    ``compensation`` 'none' the user asked for the design as it is, and the
    blank's width limit is never the solid's (the solid is the designed part,
    with no blank in it).

    Raises:
        InvalidParameterError: an unknown ``compensation``.
    """
    if Compensation.parse(compensation) is Compensation.NONE:
        return None
    return bend_error(tuple(q for q in check_bends(design, folded) if q.kind != "width"))


def fabrication_warnings(design: Design, folded: FoldedSheet | None = None) -> list[str]:
    """What the design's own values tell about fabricating it, one line each:
    a relief hole that does not fit inside the sheet around H (the DXF and
    STEP writers refuse it: :func:`relief_hole_problem`) and a density no
    sheet material has. Empty when nothing is wrong. The geometry is solved
    regardless (here, when ``folded`` is None)."""
    out = []
    hole = relief_hole_problem(design, folded)
    if hole is not None:
        out.append(f"{hole}; build refuses the DXF and STEP")
    m = design.material
    lo, hi = PLAUSIBLE_DENSITY
    if m.density is not None and not lo <= m.density <= hi:
        out.append(
            f"density: {m.density:g} kg/m^3 is no sheet material's (densities are in kg/m^3, "
            f"e.g. 7850 for steel, 800 for paper; expected {lo:g} to {hi:g}); the mass is "
            "computed with it as given"
        )
    return out


def default_body(design: Design) -> str:
    """The STEP body ``build`` writes by default: 'solid' for an exact-model
    design with thickness and a relief hole (the default hole when thickness
    > 0), else 'shell' (the reference surface)."""
    m = design.material
    exact = design.model.value == "exact"
    return "solid" if exact and m.thickness > 0.0 and m.relief_hole_diameter > 0.0 else "shell"


#: The fold of each live design object (a design is immutable, and so is its
#: fold): ``build`` folds a design to check it and again to write it, and the
#: results computed once per fold (resting placement, relief hole) then serve both.
_FOLDS: weakref.WeakKeyDictionary[Design, FoldedSheet] = weakref.WeakKeyDictionary()


def build_design(design: Design) -> FoldedSheet:
    """Solve the direction-surface and fold the sheet of ``design`` (once per
    design object: the same :class:`FoldedSheet` again afterwards)."""
    with _PER_FOLD_LOCK:
        folded = _FOLDS.get(design)
    if folded is None:
        folded = fold(solve(design.frame, design.model), design.sheet)
        with _PER_FOLD_LOCK:
            folded = _FOLDS.setdefault(design, folded)
    return folded
