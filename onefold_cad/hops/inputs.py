"""The Hops components' inputs and how a Hops request's values become the
design flags of ``onefold solve``.

Each input of ``onefold/solve`` is a design flag of
:data:`~onefold_cad.flags.design_flags.DESIGN_FLAGS` (its name without the
dashes, ``alpha``, ``hc``, ``bend_radius``; its help as the description), but
the sheet: a closed polyline (``sheet``, as ``--polygon``) or
``sheet_width`` and ``sheet_height`` (together ``--rectangle WIDTHxHEIGHT``).
An input left empty is a flag not given: the template's value stands.

A Hops request carries one ``{"ParamName": NAME, "InnerTree": {PATH:
[{"type": ..., "data": JSON text}, ...]}}`` per input (an empty tree for an
input without data). :func:`read_values` reads one value per input from it;
:func:`flag_args` turns them into the command line ``onefold solve`` reads,
and :func:`parse_solve_args` reads that with the command's own parser, so a
bad value gets the command's one-line message. Standard library only.
"""

from __future__ import annotations

import functools
import json
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.flags.design_flags import (
    DESIGN_FLAGS,
    PLACEMENTS,
    parse_choice,
    parse_float,
    parse_int,
)
from onefold_cad.flags.parser import FlagParser, add_design_flags, design_flag_values
from onefold_cad.templates import DEFAULT_TEMPLATE

__all__ = [
    "FIT_INPUTS",
    "HOPS_TYPES",
    "KINDS",
    "SOLVE_INPUTS",
    "HopsInput",
    "StaleInputsError",
    "flag_args",
    "hops_request",
    "parse_solve_args",
    "read_values",
]

#: The kinds of input: a Hops Number, Integer, Text or Curve parameter.
KINDS = ("number", "integer", "text", "curve")


@dataclass(frozen=True)
class HopsInput:
    """One input of a Hops component.

    Attributes:
        name: its ParamName (a design flag's name without dashes, ``x_plus``).
        kind: one of :data:`KINDS`.
        description: what Grasshopper shows for it.
        flag: the command-line flag it becomes ('' for none).
        required: the component cannot solve without it (else it is
            optional: empty means the template's value).
    """

    name: str
    kind: str
    description: str
    flag: str = ""
    required: bool = False


def _flag_input(dest: str) -> HopsInput:
    f = next(f for f in DESIGN_FLAGS if f.dest == dest)
    kinds: dict[Callable[[str], Any], str] = {parse_float: "number", parse_int: "integer"}
    kind = kinds.get(f.kind, "text")
    return HopsInput(dest, kind, f"{f.help} (as {f.flag}; empty: the template's)", f.flag)


_TEMPLATE = HopsInput(
    "template",
    "text",
    f"template name: a shipped template, or one of the folder the server was started with "
    f"(onefold hops --templates DIR); never a path (default: {DEFAULT_TEMPLATE})",
)

#: The inputs of ``onefold/solve``, in the component's order.
SOLVE_INPUTS: tuple[HopsInput, ...] = (
    _TEMPLATE,
    *(_flag_input(d) for d in ("model", "units", "alpha", "beta", "hc", "radius", "divisions")),
    HopsInput(
        "sheet",
        "curve",
        "the flat sheet as a closed polyline in the XY plane, star-shaped about H (the "
        "origin), the fold line on the x axis (as --polygon)",
        "--polygon",
    ),
    HopsInput(
        "sheet_width",
        "number",
        "rectangle sheet folded along its diagonal: width (with sheet_height, as "
        "--rectangle WIDTHxHEIGHT)",
        "--rectangle",
    ),
    HopsInput(
        "sheet_height",
        "number",
        "rectangle sheet: height (with sheet_width, as --rectangle WIDTHxHEIGHT)",
        "--rectangle",
    ),
    *(
        _flag_input(d)
        for d in (
            "apex_fraction",
            "x_plus",
            "x_minus",
            "y_plus",
            "y_minus",
            "thickness",
            "bend_radius",
            "k_factor",
            "kerf",
            "relief_hole",
            "sheet_surface",
        )
    ),
    HopsInput(
        "placement",
        "text",
        "where the form stands: rest (default: on the ground z = 0, as the report's "
        "resting numbers) or frame (the fold frame: H at the origin, the fold line on x)",
        "--placement",
    ),
    _flag_input("hc_fraction"),  # last: a definition made before it keeps its wiring
)

#: The inputs of ``onefold/fit`` (``onefold fit``'s options).
FIT_INPUTS: tuple[HopsInput, ...] = (
    _TEMPLATE,
    HopsInput("height", "number", "target height of the resting form, > 0", required=True),
    HopsInput(
        "span",
        "number",
        "target footprint width of the resting form (along the fold line), > 0",
        required=True,
    ),
    HopsInput("depth", "number", "target footprint depth of the resting form (optional), > 0"),
    HopsInput("min_tipping_margin", "number", "smallest tipping margin allowed, deg (optional)"),
)


class StaleInputsError(Exception):
    """The request names inputs the component does not have: the Hops
    component was made for another version of it (Hops rebuilds it when the
    answer's first error is 'Bad inputs')."""


def _value(inp: HopsInput, item: Mapping[str, Any]) -> Any:
    """One Hops value item (``{"type", "data"}``) read for ``inp``."""
    data = item.get("data")
    if not isinstance(data, str):
        raise InvalidParameterError(inp.name, f"a Hops value needs its data as text, got {data!r}")
    try:
        value = json.loads(data)
    except ValueError:
        if inp.kind != "text":
            raise InvalidParameterError(
                inp.name, f"cannot read {data[:40]!r} as a {inp.kind}"
            ) from None
        value = data  # a bare string
    if inp.kind == "curve":
        if not isinstance(value, dict):
            raise InvalidParameterError(inp.name, f"must be a curve, got {item.get('type')!r}")
        return value
    if inp.kind == "text":
        return value if isinstance(value, str) else data
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InvalidParameterError(inp.name, f"must be a {inp.kind}, got {data[:40]!r}")
    if inp.kind == "integer":
        if isinstance(value, float) and not value.is_integer():
            raise InvalidParameterError(inp.name, f"must be a whole number, got {value!r}")
        return int(value)
    return float(value)


def read_values(inputs: Sequence[HopsInput], values: object) -> dict[str, Any]:
    """The value of each input in a Hops request's ``values`` (None for an
    input without data), read as :data:`KINDS` say: a float, an int, a
    string, or a curve's CommonObject JSON (a dict, decoded by the caller).

    Raises:
        StaleInputsError: a value names no input of the component.
        InvalidParameterError: named by the input: a required input without
            data, more than one value for an input, or a value of the wrong kind.
    """
    if not isinstance(values, list | tuple):
        raise InvalidParameterError("values", "must be a list of Hops' values")
    given: dict[str, Mapping[str, Any]] = {}
    for entry in values:
        tree = entry.get("InnerTree") if isinstance(entry, Mapping) else None
        if not isinstance(tree, Mapping) or not all(
            isinstance(branch, list) and all(isinstance(item, Mapping) for item in branch)
            for branch in tree.values()
        ):
            raise InvalidParameterError(
                "values", "each value needs a ParamName and an InnerTree (Hops' DataTree)"
            )
        given[str(entry.get("ParamName"))] = tree
    names = {inp.name for inp in inputs}
    unknown = sorted(set(given) - names)
    if unknown:
        raise StaleInputsError(
            f"no input named {', '.join(unknown)} (the component's inputs: "
            f"{', '.join(inp.name for inp in inputs)})"
        )
    out: dict[str, Any] = {}
    for inp in inputs:
        tree = given.get(inp.name, {})
        items = [item for branch in tree.values() for item in branch]
        if not items:
            if inp.required:
                raise InvalidParameterError(inp.name, f"missing: {inp.description}")
            out[inp.name] = None
            continue
        if len(items) > 1:
            raise InvalidParameterError(
                inp.name, f"takes one value per solve, got {len(items)} (a list or a tree)"
            )
        out[inp.name] = _value(inp, items[0])
    return out


#: The type names Hops gives a value of each kind (RhinoCommon's, .NET's).
HOPS_TYPES = {
    "number": "System.Double",
    "integer": "System.Int32",
    "text": "System.String",
    "curve": "Rhino.Geometry.PolylineCurve",
}


def hops_request(
    pointer: str,
    inputs: Sequence[HopsInput],
    values: Mapping[str, Any],
    model_units: str = "Millimeters",
) -> dict[str, Any]:
    """The JSON body Hops posts to ``/solve`` for ``values`` (Resthopper's
    ``Schema``: ``pointer`` names the component, e.g. ``onefold/solve``): one
    entry per input, in order, its tree ``{"{0}": [{"type", "data"}]}`` with
    the value as JSON text, or ``{}`` for an input without a value (None).
    A curve is given as its CommonObject JSON (rhino3dm's ``Encode()``).
    The inverse of :func:`read_values`; a Python client can post it too."""
    entries = []
    for inp in inputs:
        v = values.get(inp.name)
        tree = {} if v is None else {"{0}": [{"type": HOPS_TYPES[inp.kind], "data": json.dumps(v)}]}
        entries.append({"ParamName": inp.name, "InnerTree": tree})
    return {
        "absolutetolerance": 0.001,
        "angletolerance": 1.0,
        "modelunits": model_units,
        "dataversion": 7,
        "algo": None,
        "pointer": pointer,
        "cachesolve": False,
        "values": entries,
        "warnings": [],
        "errors": [],
    }


def _text(value: Any) -> str:
    """A value as the command line gives it (a float in full: ``repr``)."""
    return repr(value) if isinstance(value, float) else str(value)


def flag_args(inputs: Sequence[HopsInput], values: Mapping[str, Any]) -> list[str]:
    """The command line of the values given (not None), one ``--flag=value``
    each; ``sheet_width`` and ``sheet_height`` make one ``--rectangle=WxH``
    (a side not given is left empty, as the command would read it); the
    ``sheet`` must already be ``--polygon``'s text (``x,y;x,y;...``)."""
    args = []
    w, h = values.get("sheet_width"), values.get("sheet_height")
    if w is not None or h is not None:
        args.append(f"--rectangle={'' if w is None else _text(w)}x{'' if h is None else _text(h)}")
    for inp in inputs:
        v = values.get(inp.name)
        if v is None or not inp.flag or inp.flag == "--rectangle":
            continue
        args.append(f"{inp.flag}={_text(v)}")
    return args


@functools.cache
def _parser() -> FlagParser:
    p = FlagParser(prog="onefold hops", allow_abbrev=False)
    add_design_flags(p)
    p.add_argument("--placement", type=parse_choice(PLACEMENTS), default=PLACEMENTS[0])
    return p


def parse_solve_args(args: Sequence[str]) -> tuple[dict[str, Any], str]:
    """The design flags of ``args`` (as ``onefold solve`` reads them: dest ->
    value, None for a flag not given) and the placement ('rest' or 'frame').

    Raises:
        UsageError: a value the command refuses (its one-line message).
    """
    ns = _parser().parse_intermixed_args(list(args))
    return design_flag_values(ns), ns.placement
