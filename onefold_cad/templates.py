"""Design templates: TOML files of data only, turned into validated designs.

A template names every input of a :class:`~onefold_cad.design.Design`::

    name = "table1-row1"            # file-safe design name
    description = "..."             # one line, shown by `onefold templates`
    units = "mm"                    # mm, m, in or ft
    model = "exact"                 # exact or paper

    [frame]                         # the frame curve (degrees, design unit)
    alpha = 50.0
    beta = 45.0
    h_c = 0.0
    radius = 100.0
    divisions = 90

    [sheet.quadrilateral]           # exactly one of quadrilateral, polygon, rectangle
    x_plus = 300.0
    x_minus = 300.0
    y_plus = 300.0
    y_minus = 300.0

    [material]                      # all optional
    name = "office paper, 80 g/m^2" # MATERIAL, GAUGE (the gauge is dropped when
                                    # a flag changes t or r; see docs/cli.md)
    thickness = 0.1                 # design unit, like every length here
    density = 800.0                 # kg/m^3, whatever the design unit

``[sheet]`` instead holds ``polygon = [[x, y], ...]`` (fold frame: fold line
on the x axis, H at the origin) or a ``[sheet.rectangle]`` table with
``width``, ``height`` and ``apex_fraction``. Unknown keys and values of the
wrong type raise :class:`~onefold_cad.errors.InvalidParameterError` naming
the full key (``frame.alpah``). Every length (frame radius and h_c, the sheet,
thickness, bend radius, kerf, relief hole) is in the template's ``units``;
the density is in kg/m^3 (a material property, the same whatever the length
unit: 7850 for steel), and the mass is reported in kg for mm designs and in
lb for inch and foot designs. The shipped templates live in the repository's
``templates/`` folder; a wheel carries them inside the package as
``onefold_cad/shipped/`` (setup.py), found wherever pip puts the package.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.toml_file import MAX_TOML_DEPTH, read_toml

if TYPE_CHECKING:  # imported where used: listing templates needs no numpy
    from onefold_cad.design import Design

__all__ = [
    "DEFAULT_TEMPLATE",
    "TemplateInfo",
    "design_from_data",
    "design_to_data",
    "SITE_PREFIX",
    "check_design_file",
    "find_site_file",
    "find_template",
    "list_sites",
    "list_templates",
    "load_template",
    "read_template",
    "read_toml",
    "shipped_files",
    "MAX_TOML_DEPTH",
    "template_dirs",
    "template_units",
]

#: The template `make demo` builds and that `onefold solve` starts from without one.
DEFAULT_TEMPLATE = "patkau-one-fold"

_NUMBER = "number"
_TOP: dict[str, str] = {"name": "str", "description": "str", "units": "str", "model": "str"}
_FRAME: dict[str, str] = {
    "alpha": _NUMBER,
    "beta": _NUMBER,
    "h_c": _NUMBER,
    "radius": _NUMBER,
    "divisions": "int",
}
_QUAD: dict[str, str] = {k: _NUMBER for k in ("x_plus", "x_minus", "y_plus", "y_minus")}
_RECT: dict[str, str] = {k: _NUMBER for k in ("width", "height", "apex_fraction")}
_MATERIAL: dict[str, str] = {
    "name": "str",
    "thickness": _NUMBER,
    "bend_radius": _NUMBER,
    "k_factor": _NUMBER,
    "kerf": _NUMBER,
    "relief_hole": _NUMBER,
    "density": _NUMBER,
    "sheet_surface": "str",
    "youngs_modulus": _NUMBER,
    "poisson": _NUMBER,
    "yield_stress": _NUMBER,
    **{k: _NUMBER for k in ("hardening_modulus", "kinematic_hardening")},
    "crease_overbend": _NUMBER,
    "cone_forming": "str",
}
_HARDENING = ("hardening_modulus", "kinematic_hardening")
_SHEET_KINDS = ("quadrilateral", "polygon", "rectangle")


@dataclass(frozen=True)
class TemplateInfo:
    """A shipped template: its name (file stem), file and one-line description."""

    name: str
    path: Path
    description: str


# -- locating templates ------------------------------------------------------
def template_dirs() -> list[Path]:
    """Folders that may hold the shipped templates, in search order.

    The package's own ``shipped/`` (package data: where a wheel puts them,
    whatever the install scheme: venv, ``--user``, ``--prefix``, ``--target``)
    and the repository's ``templates/`` (source checkouts and editable
    installs, whose package folder is the repository's). The package's
    folder is what ``importlib.resources.files`` gives for an unzipped
    install; importing that would load tempfile and shutil into every solve.
    """
    here = Path(__file__).resolve().parent
    candidates = [here / "shipped", here.parent / "templates"]
    seen: list[Path] = []
    for c in candidates:
        if c.is_dir() and c not in seen:
            seen.append(c)
    return seen


#: Shipped files named ``site-*.toml`` are site files (``onefold site``), not designs.
SITE_PREFIX = "site-"


def shipped_files(sites: bool = False) -> dict[str, Path]:
    """The shipped design templates (or, with ``sites``, site files) by name:
    their files, not read."""
    found: dict[str, Path] = {}
    for d in template_dirs():
        for p in sorted(d.glob("*.toml")):
            if p.stem.startswith(SITE_PREFIX) == sites:
                found.setdefault(p.stem, p)
    return found


def find_site_file(ref: str | Path) -> Path:
    """The file of a site given as a path or as a shipped site's name
    (``site-patkau-three``: ``templates/site-patkau-three.toml``)."""
    p = Path(ref)
    if p.is_file():
        return p
    shipped = shipped_files(sites=True)
    key = p.name.removesuffix(".toml")
    if str(ref) == key and key in shipped:
        return shipped[key]
    if str(ref) == key and key in shipped_files():
        raise InvalidParameterError(
            str(ref), f"a shipped design template, not a site: build it with onefold build {key}"
        )
    names = ", ".join(sorted(shipped)) or "none found"
    raise InvalidParameterError(
        "SITE", f"no such file or shipped site: {str(ref)!r} (shipped sites: {names})"
    )


def list_templates() -> list[TemplateInfo]:
    """The shipped templates, sorted by name."""
    out = []
    for name, path in sorted(shipped_files().items()):
        data = read_template(path)
        out.append(TemplateInfo(name, path, str(data.get("description", "")).strip()))
    return out


def list_sites() -> list[TemplateInfo]:
    """The shipped site files (``onefold site NAME``), sorted by name."""
    out = []
    for name, path in sorted(shipped_files(sites=True).items()):
        data = read_template(path)
        out.append(TemplateInfo(name, path, str(data.get("description", "")).strip()))
    return out


def find_template(ref: str | Path) -> Path:
    """The file of a template given as a path or as a shipped template's name."""
    p = Path(ref)
    if p.is_file():
        return p
    shipped = shipped_files()
    key = p.name.removesuffix(".toml")
    if str(ref) == key and key in shipped:
        return shipped[key]
    if str(ref) == key and key in shipped_files(sites=True):
        raise InvalidParameterError(
            str(ref), f"a shipped site, not a design template: build it with onefold site {key}"
        )
    names = ", ".join(sorted(shipped)) or "none found"
    raise InvalidParameterError(
        "template",
        f"no such file or shipped template: {str(ref)!r} (shipped templates: {names})",
    )


# -- reading -------------------------------------------------------------------
def check_design_file(data: Mapping[str, Any], path: str | Path) -> None:
    """Refuse a site file (``[[sheet]]`` tables: a list, where a design has
    one ``[sheet]`` table) given where a design template is read.

    Raises:
        InvalidParameterError: ``data`` is a site file's, named by its path
            and the command that builds it.
    """
    if isinstance(data.get("sheet"), list):
        raise InvalidParameterError(
            str(path), "a site file (it has [[sheet]] tables), not a design template: "
            f"build it with onefold site {path}"
        )  # fmt: skip


def read_template(path: str | Path) -> dict[str, Any]:
    """The raw TOML data of a template file (not yet validated): :func:`read_toml`."""
    return read_toml(path, "template")


def load_template(path: str | Path) -> Design:
    """Read and validate the template at ``path`` (a file or a shipped name)."""
    p = find_template(path)
    data = read_template(p)
    check_design_file(data, p)
    template_units(data, p)
    return design_from_data(data)


def template_units(data: Mapping[str, Any], path: str | Path) -> str:
    """The ``units`` a template file states (a template must state them).

    Raises:
        InvalidParameterError: ``units`` is missing (named with the file).
    """
    units = data.get("units")
    if units is None:
        raise InvalidParameterError(
            f"{path}: units", 'missing: a template states its units, e.g. units = "mm" '
            "(mm, m, in or ft)"
        )  # fmt: skip
    return str(units)


# -- validating ------------------------------------------------------------------
def _check_table(data: object, spec: Mapping[str, str], where: str) -> dict[str, Any]:
    """Check keys and value types of one table; return a plain dict copy."""
    if not isinstance(data, Mapping):
        raise InvalidParameterError(where or "template", "must be a table")
    out: dict[str, Any] = {}
    for key, value in data.items():
        full = f"{where}.{key}" if where else key
        kind = spec.get(key)
        if kind is None:
            allowed = ", ".join(spec)
            raise InvalidParameterError(full, f"unknown key (allowed here: {allowed})")
        ok = {
            "str": isinstance(value, str),
            "int": isinstance(value, int) and not isinstance(value, bool),
            _NUMBER: isinstance(value, int | float) and not isinstance(value, bool),
        }[kind]
        if not ok:
            wanted = {"str": "a string", "int": "an integer", _NUMBER: "a number"}[kind]
            raise InvalidParameterError(
                full, f"must be {wanted}, got {type(value).__name__} {value!r}"
            )
        out[key] = value
    return out


def _sheet_kind(data: Mapping[str, Any], where: str = "sheet") -> str:
    kinds = [k for k in data if k in _SHEET_KINDS]
    for key in data:
        if key not in _SHEET_KINDS:
            raise InvalidParameterError(
                f"{where}.{key}", f"unknown key (allowed here: {', '.join(_SHEET_KINDS)})"
            )
    if len(kinds) != 1:
        raise InvalidParameterError(
            where, f"needs exactly one of {', '.join(_SHEET_KINDS)}, got {len(kinds)}"
        )
    return kinds[0]


def _polygon_points(value: object, where: str) -> list[list[float]]:
    if not isinstance(value, list):
        raise InvalidParameterError(where, "must be a list of [x, y] pairs")
    pts = []
    for i, pair in enumerate(value):
        if (
            not isinstance(pair, list)
            or len(pair) != 2
            or not all(isinstance(c, int | float) and not isinstance(c, bool) for c in pair)
        ):
            raise InvalidParameterError(
                f"{where}[{i}]", f"must be a pair [x, y] of numbers, got {pair!r}"
            )
        pts.append([float(pair[0]), float(pair[1])])
    return pts


def _renamed(exc: InvalidParameterError, name: str) -> InvalidParameterError:
    msg = str(exc)
    prefix = f"{exc.parameter}: "
    return type(exc)(name, msg[len(prefix) :] if msg.startswith(prefix) else msg)


def design_from_data(
    data: Mapping[str, Any],
    *,
    key_names: Mapping[str, str] | None = None,
) -> Design:
    """Validate template data (as read from TOML) and build the design.

    Args:
        data: the template's tables.
        key_names: how to name a full key (``frame.alpha``) in errors, e.g.
            ``{"frame.alpha": "--alpha"}`` when the value came from a flag.

    Raises:
        InvalidParameterError: an unknown key, a value of the wrong type or
            out of range; the message names the full key.
    """
    from onefold_cad.design import Design
    from onefold_cad.geometry.frame_curve import FrameCurve
    from onefold_cad.geometry.material import Material
    from onefold_cad.geometry.sheet import Sheet

    names = dict(key_names or {})

    def fail(key: str, exc: InvalidParameterError) -> InvalidParameterError:
        return _renamed(exc, names.get(key, key))

    try:
        top_spec = {**_TOP, "frame": "table", "sheet": "table", "material": "table"}
        for key in data:
            if key not in top_spec:
                raise InvalidParameterError(
                    key, f"unknown key (allowed at top level: {', '.join(top_spec)})"
                )
        top = _check_table({k: v for k, v in data.items() if k in _TOP}, _TOP, "")
        frame = _check_table(data.get("frame", {}), _FRAME, "frame")
        material = _check_table(data.get("material", {}), _MATERIAL, "material")
        sheet_data = data.get("sheet")
        if sheet_data is None:
            raise InvalidParameterError(
                "sheet", "missing: give sheet.quadrilateral, sheet.polygon or sheet.rectangle"
            )
        if not isinstance(sheet_data, Mapping):
            raise InvalidParameterError("sheet", "must be a table")
        kind = _sheet_kind(sheet_data)
        if kind == "polygon":
            sheet_args: Any = _polygon_points(sheet_data[kind], "sheet.polygon")
        else:
            spec = _QUAD if kind == "quadrilateral" else _RECT
            sheet_args = _check_table(sheet_data[kind], spec, f"sheet.{kind}")
    except InvalidParameterError as exc:
        raise fail(exc.parameter, exc) from None

    missing = [k for k in ("alpha", "beta") if k not in frame]
    if missing:
        raise fail(
            f"frame.{missing[0]}", InvalidParameterError("x", "missing (a number in (0, 90) deg)")
        )
    required = {"quadrilateral": tuple(_QUAD), "rectangle": ("width", "height")}.get(kind, ())
    for key in required:
        if key not in sheet_args:
            raise fail(f"sheet.{kind}.{key}", InvalidParameterError("x", "missing (a number > 0)"))

    try:
        fc = FrameCurve(**frame)
    except InvalidParameterError as exc:
        raise fail(f"frame.{exc.parameter}", exc) from None
    try:
        if kind == "polygon":
            sheet = Sheet.polygon(sheet_args, name="polygon")
        elif kind == "quadrilateral":
            sheet = Sheet.quadrilateral(**sheet_args)
        else:
            sheet = Sheet.rectangle(**sheet_args)
    except InvalidParameterError as exc:
        key = "sheet.polygon" if kind == "polygon" else f"sheet.{kind}.{exc.parameter}"
        raise fail(key, exc) from None
    try:
        mat = Material(**material)
    except InvalidParameterError as exc:
        raise fail(f"material.{exc.parameter}", exc) from None
    try:
        return Design(
            name=top.get("name", "onefold"),
            frame=fc,
            sheet=sheet,
            model=top.get("model", "exact"),
            material=mat,
            units=top.get("units", "mm"),
            description=top.get("description", "").strip(),
        )
    except InvalidParameterError as exc:
        key = "material.relief_hole" if exc.parameter == "relief_hole" else exc.parameter
        raise fail(key, exc) from None


def _num(x: float) -> float | int:
    return int(x) if isinstance(x, int) else float(x)


def design_to_data(design: Design) -> dict[str, Any]:
    """The template data of ``design`` (the inverse of :func:`design_from_data`).

    The ``sheet`` table holds the sheet's own inputs (quadrilateral, rectangle
    or polygon vertices in the fold frame). An unset relief hole is left out.
    """
    f, m, s = design.frame, design.material, design.sheet
    if s.kind in ("quadrilateral", "rectangle"):
        sheet: dict[str, Any] = {s.kind: {k: _num(v) for k, v in s.inputs.items()}}
    else:
        pts = s.inputs.get("polygon", s.vertices.tolist())
        sheet = {"polygon": [[float(x), float(y)] for x, y in pts]}
    material: dict[str, Any] = {
        "name": m.name,
        "thickness": m.thickness,
        "bend_radius": m.bend_radius,
        "k_factor": m.k_factor,
        "kerf": m.kerf,
        "sheet_surface": m.sheet_surface.value,
    }
    optional = ("relief_hole", "density", "youngs_modulus", "poisson", "yield_stress", *_HARDENING,
                "crease_overbend", "cone_forming")  # fmt: skip
    material |= {k: getattr(m, k) for k in optional if getattr(m, k) is not None}  # unset: left out
    return {
        "name": design.name,
        "description": design.description,
        "units": design.units.value,
        "model": design.model.value,
        "frame": {k: getattr(f, k) for k in ("alpha", "beta", "h_c", "radius", "divisions")},
        "sheet": sheet,
        "material": material,
    }
