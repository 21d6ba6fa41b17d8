"""The page's parameters: a bounded query string turned into a validated design.

The page sends every control's value as text (``alpha=30&beta=30&...``). This
module checks the query's shape (known names only, each once, bounded
lengths), hands the values to the ``onefold`` command's own option parser
(:data:`onefold_cad.flags.design_flags.DESIGN_FLAGS`, as ``--alpha=30`` ...), applies them to
the chosen template's data with :class:`onefold_cad.flags.overrides.Overrides` and
validates the result with :func:`onefold_cad.templates.design_from_data`. So
a bad value gets exactly the message ``onefold solve`` prints for it.

Templates are data held in memory (read when the server starts): the page
names one by its key, never by a path.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any
from urllib.parse import parse_qsl

from onefold_cad.design import Design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.templates import design_from_data, design_to_data

__all__ = [
    "MAX_QUERY",
    "MAX_VALUE",
    "MAX_POLYGON",
    "PAGE_FLAGS",
    "ParameterProblem",
    "QueryError",
    "design_from_params",
    "page_values",
    "parse_query",
]

#: Longest accepted query string (characters).
MAX_QUERY = 6000
#: Longest accepted value of one scalar control (characters).
MAX_VALUE = 40
#: Longest accepted polygon text ("x,y;x,y;..."; characters).
MAX_POLYGON = 4000

#: Page control -> the ``onefold solve`` flag it sets. ``width`` and
#: ``height`` (rectangle sheets) go together into ``--rectangle WxH``. The
#: page places H with ``hc_fraction`` (a fraction of the half f-line: it
#: stays on it whatever alpha and R); a query may give ``hc`` instead.
PAGE_FLAGS: dict[str, str] = {
    "model": "--model",
    "alpha": "--alpha",
    "beta": "--beta",
    "hc_fraction": "--hc-fraction",
    "hc": "--hc",
    "radius": "--radius",
    "divisions": "--divisions",
    "width": "--rectangle",
    "height": "--rectangle",
    "apex_fraction": "--apex-fraction",
    "x_plus": "--x-plus",
    "x_minus": "--x-minus",
    "y_plus": "--y-plus",
    "y_minus": "--y-minus",
    "polygon": "--polygon",
    "thickness": "--thickness",
    "bend_radius": "--bend-radius",
    "cone_forming": "--cone-forming",
}
#: The query names besides the controls: the template, and (``/api/state`` only) the
#: :func:`~onefold_cad.explore.state.design_state` ``mesh_key`` of the triangles the
#: page already has (the others ignore it).
_NAMES = frozenset(PAGE_FLAGS) | {"template", "mesh"}
_MAX_FIELDS = len(_NAMES) + 4


class QueryError(ValueError):
    """The request itself is malformed (unknown or repeated name, too long):
    answered with HTTP 400, not shown as a design message."""


class ParameterProblem(ValueError):
    """A value the design cannot take: the message ``onefold solve`` gives
    for it and the page controls it concerns.

    Attributes:
        message: one line, as the CLI prints it after ``onefold: error:``.
        controls: ids of the page controls to mark (may be empty).
    """

    def __init__(self, message: str, controls: tuple[str, ...] = ()) -> None:
        super().__init__(message)
        self.message = message
        self.controls = controls


def parse_query(query: str) -> dict[str, str]:
    """Split a query string into ``{name: text}`` after checking its shape.

    Raises:
        QueryError: too long, an unknown or repeated name, a value over
            :data:`MAX_VALUE` (:data:`MAX_POLYGON` for ``polygon``) characters,
            or bytes that are not UTF-8.
    """
    if len(query) > MAX_QUERY:
        raise QueryError(f"query too long ({len(query)} > {MAX_QUERY} characters)")
    try:
        pairs = parse_qsl(
            query,
            keep_blank_values=True,
            strict_parsing=False,
            errors="strict",
            max_num_fields=_MAX_FIELDS,
        )
    except (ValueError, UnicodeDecodeError) as exc:
        raise QueryError(f"malformed query ({exc})") from None
    out: dict[str, str] = {}
    for name, value in pairs:
        if name not in _NAMES:
            raise QueryError(f"unknown parameter {name[:40]!r}")
        if name in out:
            raise QueryError(f"parameter {name!r} given twice")
        limit = MAX_POLYGON if name == "polygon" else MAX_VALUE
        if len(value) > limit:
            raise QueryError(f"parameter {name!r} too long ({len(value)} > {limit} characters)")
        out[name] = value
    return out


def _controls_of(flag: str) -> tuple[str, ...]:
    return tuple(k for k, f in PAGE_FLAGS.items() if f == flag)


def _cli_flags(params: Mapping[str, str]) -> dict[str, Any]:
    """The design flags parsed as ``onefold solve`` parses them
    (:func:`onefold_cad.flags.parser.parse_design_flags`)."""
    from onefold_cad.flags.parser import UsageError, parse_design_flags

    args = []
    if "width" in params or "height" in params:
        args.append(f"--rectangle={params.get('width', '')}x{params.get('height', '')}")
    for name, text in params.items():
        if name in PAGE_FLAGS and PAGE_FLAGS[name] != "--rectangle":
            args.append(f"{PAGE_FLAGS[name]}={text}")
    try:
        return parse_design_flags(args)
    except UsageError as exc:  # the parser's one-line message, as `main` reports it
        text = " ".join(str(exc).split())
        flag = text.split(":", 1)[0]
        raise ParameterProblem(text, _controls_of(flag)) from None


def _without_default_forming(
    params: Mapping[str, str], template: Mapping[str, Any]
) -> Mapping[str, str]:
    """``params`` without a ``cone_forming`` of 'design' where the template
    gives none: the page sends every control, and the template's cones are
    formed to the design already (so the value changes nothing of it)."""
    material = template.get("material")
    given = material.get("cone_forming") if isinstance(material, dict) else None
    if params.get("cone_forming") == "design" and given is None:
        return {k: v for k, v in params.items() if k != "cone_forming"}
    return params


def design_from_params(
    params: Mapping[str, str], templates: Mapping[str, Mapping[str, Any]], default: str
) -> Design:
    """The design of the page's controls: the template's data with the values applied.

    Args:
        params: from :func:`parse_query`.
        templates: template key -> template data (as read from TOML).
        default: the key used when ``params`` names no template.

    Raises:
        ParameterProblem: a value the CLI would refuse, with its message.
    """
    from onefold_cad.flags.design_flags import FLAG_OF
    from onefold_cad.flags.overrides import Overrides, changed_flags, mark_changes

    key = params.get("template", default)
    if key not in templates:
        raise ParameterProblem(
            f"template: no such template {key!r} (choose one of: {', '.join(sorted(templates))})",
            ("template",),
        )
    template = dict(templates[key])
    params = _without_default_forming(params, template)
    flags = _cli_flags(params)
    try:
        data, names = Overrides(**flags).apply(template)
        # the page sends every control: only those that changed a value describe the design
        changed = changed_flags(design_to_data(design_from_data(template)), data, names)
        given = {k: v for k, v in flags.items() if FLAG_OF[k] in changed}
        name = str(template.get("name", key))
        data = mark_changes(data, given, changed, name, implicit=False, by="the page")
        return design_from_data(data, key_names=names)
    except InvalidParameterError as exc:
        raise ParameterProblem(" ".join(str(exc).split()), _controls_of(exc.parameter)) from None


def _text(x: float) -> str:
    """A number as the shortest text that reads back exactly."""
    return repr(float(x)) if not float(x).is_integer() else str(int(x))


def page_values(design: Design) -> dict[str, Any]:
    """The design as the page's control values (text) and the ranges the page needs.

    Returns:
        ``{"values": {control: text}, "sheet_kind": ..., "units": ...,
        "hc_limit": R cos(alpha), "sheet_size": ...}`` (``hc_fraction`` is
        h_c / hc_limit, strictly inside (-1, 1), see
        :class:`onefold_cad.FrameCurve`; ``sheet_size`` is the sheet's largest
        distance from H, a scale for the sliders).
    """
    data = design_to_data(design)
    frame, material = data["frame"], data["material"]
    values: dict[str, str] = {
        "model": data["model"],
        "alpha": _text(frame["alpha"]),
        "beta": _text(frame["beta"]),
        "hc_fraction": _text(frame["h_c"] / design.frame.half_chord),
        "radius": _text(frame["radius"]),
        "divisions": str(frame["divisions"]),
        "thickness": _text(material["thickness"]),
        "bend_radius": _text(material["bend_radius"]),
        "cone_forming": design.material.cones_formed,
    }
    kind = design.sheet.kind
    sheet = data["sheet"][kind]
    if kind == "polygon":
        values["polygon"] = ";".join(f"{_text(x)},{_text(y)}" for x, y in sheet)
    else:
        values.update({k: _text(v) for k, v in sheet.items()})
    limit = design.frame.half_chord
    return {
        "values": values,
        "sheet_kind": kind,
        "units": design.units.value,
        "hc_limit": limit if math.isfinite(limit) else None,
        "sheet_size": design.sheet.size,
    }
