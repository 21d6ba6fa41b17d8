"""What a sweep measures on each design: the registry :data:`MEASURES`.

Every design is solved, folded and stood on the ground (the body the STEP
holds, :func:`~onefold_cad.fabrication.rules.resting_placement`): the
:data:`REST` columns. ``--measure NAME,...`` adds the columns of further
:class:`Measure` entries (``bends``, ``mass``, ``simulate``). A measure is a
name, its columns (with their units) and a function of the design, its fold,
its resting placement and the sweep's settings (``simulate``'s options) that
returns one plain value per column; the runner only reads this table, so a
new measure is one more :func:`register` call in this module and nothing else.

Units are kinds (:data:`UNIT_KINDS`) resolved per design: ``length`` is the
design's unit (``mm``, ``in``, ``ft``), ``mass`` the report's (kg for mm
designs, lb otherwise). Every value equals the one ``onefold solve --json``
reports for the same flags (``simulate``'s: ``onefold simulate --json``'s,
with the same settings).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # the parser reads this table: no numpy at import
    from onefold_cad.design import Design
    from onefold_cad.geometry.folding import FoldedSheet
    from onefold_cad.geometry.placement import RestingPlacement

__all__ = [
    "MEASURES",
    "REST",
    "UNIT_KINDS",
    "Column",
    "Measure",
    "Settings",
    "measure_help",
    "measure_names",
    "register",
    "resolve_unit",
]

#: A sweep's measure settings: name -> value.
Settings = Mapping[str, Any]

#: The unit kinds of a column, and what each means.
UNIT_KINDS = {
    "": "no unit (a count, a ratio, a word)",
    "deg": "degrees",
    "length": "the design's length unit (mm, m, in or ft: the units column)",
    "length^2": "the design's length unit squared",
    "mass": "kg for mm designs, lb for inch and foot designs (the mass_unit column)",
    "kg/m^3": "kilograms per cubic metre",
    "s": "seconds",
    "N": "newtons",
    "J": "joules",
    "MPa": "megapascals",
}


@dataclass(frozen=True)
class Column:
    """One output column.

    Attributes:
        name: the column's name (``tipping_margin_deg``).
        kind: its type: 'float', 'int', 'bool' or 'str'.
        unit: its unit kind (a key of :data:`UNIT_KINDS`).
        help: what it holds, in a few words.
    """

    name: str
    kind: str
    unit: str
    help: str


@dataclass(frozen=True)
class Measure:
    """A named set of output columns and how to compute them.

    Attributes:
        name: what ``--measure`` calls it.
        help: one line for ``--help``.
        columns: the columns it fills.
        compute: ``(design, folded, rest, settings) -> {column: value}``,
            plain values (float, int, bool, str or None), in the units of
            ``columns``; ``settings``: the sweep's measure settings (name ->
            value, :attr:`~onefold_cad.sweep.plan.SweepPlan.settings`).
    """

    name: str
    help: str
    columns: tuple[Column, ...]
    compute: Callable[[Design, FoldedSheet, RestingPlacement, Settings], Mapping[str, Any]]


def resolve_unit(kind: str, units: str, mass_unit: str | None = None) -> str:
    """The concrete unit of a column of unit ``kind`` for a design in ``units``
    (``length`` in mm is ``mm``, ``length^2`` is ``mm^2``)."""
    if kind == "length":
        return units
    if kind == "length^2":
        return f"{units}^2"
    if kind == "mass":
        return mass_unit or ("kg" if units == "mm" else "lb")
    return kind


def _rest(
    design: Design, folded: FoldedSheet, rest: RestingPlacement, settings: Settings
) -> dict[str, Any]:
    plus, minus = folded.crease
    return {
        "units": design.units.value,
        "body": rest.body,
        "apex_height": float(folded.solution.apex_height),
        "fold_angle_plus_x_deg": float(plus.fold_angle_deg),
        "fold_angle_minus_x_deg": float(minus.fold_angle_deg),
        "bend_plus_x": plus.bend,
        "bend_minus_x": minus.bend,
        "height": rest.height,
        "span": rest.width,
        "depth": rest.depth,
        "footprint_area": rest.footprint_area,
        "tilt_deg": float(rest.tilt_deg),
        "tipping_margin_deg": float(rest.tipping_margin_deg),
        "stable": bool(rest.stable),
        "touching_points": len(rest.contacts),
    }


#: What every design gets: solve, fold and rest.
REST = Measure(
    "rest",
    "solve, fold and stand the design (always)",
    (
        Column("units", "str", "", "the design's length unit"),
        Column("body", "str", "", "the body that stands: solid or shell (the STEP's)"),
        Column("apex_height", "float", "length", "the paper's h at the frame radius R"),
        Column("fold_angle_plus_x_deg", "float", "deg", "fold angle of the +x crease half"),
        Column("fold_angle_minus_x_deg", "float", "deg", "fold angle of the -x crease half"),
        Column("bend_plus_x", "str", "", "bend direction of the +x half: UP or DOWN"),
        Column("bend_minus_x", "str", "", "bend direction of the -x half: UP or DOWN"),
        Column("height", "float", "length", "height of the form as it rests"),
        Column("span", "float", "length", "footprint width (along the resting x axis)"),
        Column("depth", "float", "length", "footprint depth (along the resting y axis)"),
        Column("footprint_area", "float", "length^2", "area of the form's shadow on the ground"),
        Column("tilt_deg", "float", "deg", "tilt of the resting form from the fold frame"),
        Column("tipping_margin_deg", "float", "deg", "smallest tilt that tips it over"),
        Column("stable", "bool", "", "the centre of mass lies over the support polygon"),
        Column("touching_points", "int", "", "points that touch the ground"),
    ),
    _rest,
)


def _bends(
    design: Design, folded: FoldedSheet, rest: RestingPlacement, settings: Settings
) -> dict[str, Any]:
    from onefold_cad.fabrication.bend_checks import check_bends
    from onefold_cad.geometry.bend_model import crease_bends

    out: dict[str, Any] = {}
    for half, bv in zip(folded.crease, crease_bends(folded, design.material), strict=True):
        out[f"crease_length_{half.name}"] = float(half.length)
        out[f"bend_allowance_{half.name}"] = float(bv.allowance)
        out[f"bend_deduction_{half.name}"] = float(bv.deduction)
    out["bend_problems"] = len(check_bends(folded, design.material, design.units))
    return out


def _mass(
    design: Design, folded: FoldedSheet, rest: RestingPlacement, settings: Settings
) -> dict[str, Any]:
    from onefold_cad.fabrication.mass import design_mass
    from onefold_cad.fabrication.report import report_flat_pattern

    fp = report_flat_pattern(design, folded)
    mass = None if fp is None else design_mass(design, fp.area)
    return {
        "flat_area": None if fp is None else float(fp.area),
        "mass": None if mass is None else float(mass.value),
        "mass_unit": None if mass is None else mass.unit,
    }


def _half_columns(stem: str, unit: str, what: str) -> tuple[Column, ...]:
    return tuple(
        Column(f"{stem}_{h}", "float", unit, f"{what} of the {s} crease half")
        for h, s in (("plus_x", "+x"), ("minus_x", "-x"))
    )


#: The measures by name (``rest`` first; the order of their columns).
MEASURES: dict[str, Measure] = {"rest": REST}


def register(measure: Measure) -> Measure:
    """Add ``measure`` to :data:`MEASURES` (a name already there is an error)."""
    if measure.name in MEASURES:
        raise ValueError(f"measure {measure.name!r} is registered already")
    MEASURES[measure.name] = measure
    return measure


register(
    Measure(
        "bends",
        "crease lengths, bend allowance and deduction, and the bend model's problems",
        (
            *_half_columns("crease_length", "length", "length"),
            *_half_columns("bend_allowance", "length", "bend allowance"),
            *_half_columns("bend_deduction", "length", "bend deduction"),
            Column("bend_problems", "int", "", "limits of the bend model it breaks (0: none)"),
        ),
        _bends,
    )
)
register(
    Measure(
        "mass",
        "net area of the flat pattern and the part's mass (needs a density)",
        (
            Column("flat_area", "float", "length^2", "net area of the cut part"),
            Column("mass", "float", "mass", "mass of the cut part"),
            Column("mass_unit", "str", "", "kg or lb"),
        ),
        _mass,
    )
)


def _simulate(
    design: Design, folded: FoldedSheet, rest: RestingPlacement, settings: Settings
) -> dict[str, Any]:
    """The simulation's headline values, as ``onefold simulate --json``'s
    ``simulation`` section has them (None where its stage is not run)."""
    from onefold_cad.mechanics.simulate import simulate

    data = simulate(
        design,
        folded,
        supports=settings["supports"],
        reference=settings["reference"],
        crease=settings["crease"],
        law=settings["law"],
        level=settings["mesh"],
        convergence=settings["check"],
    ).to_data()
    formed, released = data.get("formed") or {}, data.get("released") or {}
    standing, designed = data["standing"], data.get("designed") or {}
    return {
        "sim_weight_N": data["weight_N"],
        "sim_nodes": data["mesh"]["nodes"],
        "sim_mesh_change": (data["convergence"] or {}).get("max_deviation_change"),
        "formed_bending_energy_J": formed.get("bending_energy_J"),
        "formed_plastic_share": formed.get("plastic_area_share"),
        "released_max_deviation": released.get("max_deviation"),
        "released_rms_deviation": released.get("rms_deviation"),
        "standing_stands": standing["stands"],
        "standing_reason": standing["reason"] or "",
        **{f"standing_{k}": standing[k] for k in _STANDING},
        "designed_max_displacement": designed.get("max_displacement"),
        "designed_max_stress_MPa": designed.get("max_stress_MPa"),
        "sim_warnings": len(data["warnings"]),
    }


#: The standing stage's number columns: its key in the simulation's data -> (unit, help).
_STANDING = {
    "load_factor": ("", "share of its weight carried on its load path (1: all of it)"),
    "max_deviation": ("length", "largest distance from the designed form, standing"),
    "rms_deviation": ("length", "rms distance from the designed form, standing"),
    "max_displacement": ("length", "largest movement under its weight, standing"),
    "height": ("length", "height of the simulated form, standing"),
    "tipping_margin_deg": ("deg", "tipping margin of the simulated form, standing"),
    "max_stress_MPa": ("MPa", "largest stress at the sheet's faces, standing"),
    "utilisation": ("", "largest stress over the yield stress, standing"),
}

#: The simulation's other columns, before and after the standing ones: (name, kind, unit,
#: help).
_SIMULATED = (
    ("sim_weight_N", "float", "N", "the sheet's weight"),
    ("sim_nodes", "int", "", "nodes of the simulation's mesh"),
    ("sim_mesh_change", "float", "", "relative change of the largest deviation on a mesh of "
     "twice the nodes (empty without --check)"),
    ("formed_bending_energy_J", "float", "J", "work of bending the flat sheet into the design "
     "(reference flat)"),
    ("formed_plastic_share", "float", "", "share of the sheet's area that yields when bent "
     "into the design (reference flat)"),
    ("released_max_deviation", "float", "length", "largest springback from the designed form, "
     "let go (reference flat)"),
    ("released_rms_deviation", "float", "length", "rms springback from the designed form, let "
     "go (reference flat)"),
    ("standing_stands", "bool", "", "the simulated sheet stands on its supports"),
    ("standing_reason", "str", "", "why it does not stand (empty when it does)"),
)  # fmt: skip
_LAST = (
    ("designed_max_displacement", "float", "length", "largest movement of the designed form "
     "under its weight (reference designed)"),
    ("designed_max_stress_MPa", "float", "MPa", "largest stress of the designed form under its "
     "weight (reference designed)"),
    ("sim_warnings", "int", "", "warnings of the simulation (onefold simulate prints them)"),
)  # fmt: skip

register(
    Measure(
        "simulate",
        "the sheet as steel, as onefold simulate (the simulation options): formed, sprung "
        "back, standing under its weight",
        (
            *(Column(*c) for c in _SIMULATED),
            *(Column(f"standing_{k}", "float", u, h) for k, (u, h) in _STANDING.items()),
            *(Column(*c) for c in _LAST),
        ),
        _simulate,
    )
)


def measure_names() -> tuple[str, ...]:
    """The names ``--measure`` takes (every measure but the always-on ``rest``)."""
    return tuple(n for n in MEASURES if n != REST.name)


def measure_help() -> str:
    """The measures, one line each (``--help``): name, what, columns."""
    import textwrap

    lines = []
    width = max(len(n) for n in MEASURES)
    for m in MEASURES.values():
        cols = ", ".join(c.name for c in m.columns)
        lines += textwrap.wrap(
            f"{m.name:<{width}} {m.help}; columns:", 96, initial_indent="  ",
            subsequent_indent=" " * (width + 3),
        )  # fmt: skip
        pad = " " * (width + 3)
        lines += textwrap.wrap(cols, 96, initial_indent=pad, subsequent_indent=pad)
    return "\n".join(lines)
