"""The part's fabrication rules that ``solve`` and every writer share: the
default body, how it stands, the solid's bend limits and the design's own
fabrication warnings (numpy only).

Lengths are in the design's unit.
"""

from __future__ import annotations

from onefold_cad.choices import Body, Compensation
from onefold_cad.design import Design, rest_once
from onefold_cad.errors import FabricationError, InvalidParameterError
from onefold_cad.fabrication.bend_checks import bend_error, check_bends
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, relief_hole_problem
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.placement import RestingPlacement

__all__ = [
    "PLAUSIBLE_DENSITY",
    "default_body",
    "fabrication_warnings",
    "resting_placement",
    "solid_bend_problem",
    "solid_problem",
]

#: Densities (kg/m^3) outside this range are not those of a sheet material: lighter
#: than air, or denser than osmium (22 590 kg/m^3), the densest element.
PLAUSIBLE_DENSITY = (1.0, 23_000.0)


def default_body(design: Design) -> Body:
    """The STEP body ``build`` writes by default: 'solid' for an exact-model
    design with thickness and a relief hole (the default hole when thickness
    > 0), else 'shell' (the reference surface)."""
    m = design.material
    exact = design.model.value == "exact"
    return (
        Body.SOLID if exact and m.thickness > 0.0 and m.relief_hole_diameter > 0.0 else Body.SHELL
    )


def resting_placement(
    design: Design, folded: FoldedSheet, body: Body | None = None
) -> RestingPlacement:
    """How the body the STEP holds (``body``, default :func:`default_body`)
    stands on the ground: :func:`~onefold_cad.geometry.placement.rest_form`
    with the material's relief hole resolved (:func:`relief_hole_diameter`),
    computed once per fold, material and body. The report, the STEP, the GLB
    and the previews all place the form with it.

    A relief hole that does not fit the sheet (:func:`relief_hole_problem`,
    which every writer of the part refuses and ``solve`` warns about) leaves
    no part to stand: the form is then placed as the sheet without a hole, on
    its reference surface. So is a default solid that cannot be made
    (:func:`solid_problem`, which ``solve`` warns about and the STEP refuses),
    with the reference surface's own centre of mass (the thick sheet's mass
    needs the solid's mitre blocks)."""
    m, kind = _resting_material(design, folded, body)
    if body is None and kind == "solid":
        try:
            return rest_once(folded, m, Body.SOLID)
        except InvalidParameterError:  # solid_problem: no mitre at the crease
            m, kind = m.with_changes(thickness=0.0, bend_radius=0.0), Body.SHELL
    return rest_once(folded, m, kind)


def _resting_material(
    design: Design, folded: FoldedSheet, body: Body | None
) -> tuple[Material, Body]:
    """The material (its relief hole resolved) and the body :func:`resting_placement`
    stands, before a default solid's own problem."""
    body = default_body(design) if body is None else body
    m = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
    if relief_hole_problem(design, folded) is not None:
        return m.with_changes(relief_hole=0.0), Body.SHELL
    return m, body


def solid_problem(design: Design, folded: FoldedSheet) -> InvalidParameterError | None:
    """Why the default body, a solid (:func:`default_body`), cannot be made
    and stood (a fold flat or folded through has no mitre at the crease), or
    None (it can, or the default body is the shell)."""
    m, body = _resting_material(design, folded, None)
    if body != "solid":
        return None
    try:
        rest_once(folded, m, Body.SOLID)
    except InvalidParameterError as exc:
        return exc
    return None


def solid_bend_problem(
    design: Design, folded: FoldedSheet, compensation: Compensation | str = Compensation.SHARP
) -> FabricationError | None:
    """The one check of a STEP solid against the bend model's limits
    (:func:`~onefold_cad.fabrication.bend_checks.check_bends`): the refusal every
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
    return bend_error(
        tuple(q for q in check_bends(folded, design.material, design.units) if q.kind != "width")
    )


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
