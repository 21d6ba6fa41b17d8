"""The site file: a TOML list of placed designs, read and checked
(:func:`read_site`) before anything is built.

A site file::

    name = "patkau-three"          # file-safe: SITE.step, SITE.ifc, ...
    description = "..."            # optional, one line
    units = "mm"                   # the site's unit: positions and every sheet

    [[sheet]]
    name = "north"                 # file-safe, unique: its files go to DIR/north/
    template = "patkau-one-fold"   # a shipped template or a path (relative to this file)
    flags = { alpha = 32.0 }       # optional: design flags, as `onefold build --alpha 32`
    x = 0.0                        # where the sheet's resting origin stands (site unit)
    y = 0.0
    rotation = 0.0                 # about the vertical, deg, counter-clockwise seen from above

    [loads]                        # optional: `onefold loads` on every sheet (docs/loads.md),
    wind_speed = 25.0              # its anchors and ballast in SITE-order.csv
    terrain = "II"
    snow = 1.0

    [[sheet]]
    name = "inline"
    x = 9000.0
    y = 0.0
    [sheet.design]                 # instead of `template`: a template's tables inline
    ...

Every error is an :class:`~onefold_cad.errors.InvalidParameterError` whose
parameter names the file, the entry and the key
(``site.toml: sheet 2 'east': rotation``).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.templates import find_site_file, find_template, read_template, read_toml

__all__ = [
    "LOADS_KEYS",
    "MAX_SHEETS",
    "SHEET_KEYS",
    "SITE_KEYS",
    "SheetSpec",
    "SiteSpec",
    "find_site",
    "read_site",
]

#: The keys of the site file's top level and of one ``[[sheet]]`` entry.
SITE_KEYS = ("name", "description", "units", "sheet", "loads")
#: The keys of the optional ``[loads]`` table: ``onefold loads``'s options
#: without dashes, and the ``LoadSpec`` field each sets (``mesh``: the mesh).
LOADS_KEYS = {
    "wind_speed": "wind_speed", "terrain": "terrain", "velocity_pressure": "velocity_pressure_kPa",
    "height": "height", "cf_down": "cf_down", "cf_up": "cf_up", "directions": "directions",
    "snow": "snow_kPa", "exposure": "exposure", "thermal": "thermal", "person": "person_kN",
    "person_grid": "person_grid", "supports": "supports", "friction": "friction", "mesh": "mesh",
}  # fmt: skip
SHEET_KEYS = ("name", "template", "design", "flags", "x", "y", "rotation")
_UNITS = ("mm", "m", "in", "ft")
#: The most sheets a site takes, refused up front (:func:`read_site`), before
#: any is built. Every sheet's part stays in memory until the site's STEP,
#: GLB, IFC and clearance are written (about 11 MB more per default sheet
#: with its files, measured from 2 to 8 sheets over a start of 0.57 GB), the
#: clearance measures every pair (4 950 at 100 sheets) and each sheet takes
#: about 10 s to build: 100 sheets stay near 1.7 GB (extrapolated) and
#: 35 MB of staging.
#: A larger site is several site files.
MAX_SHEETS = 100
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*$")


@dataclass(frozen=True)
class SheetSpec:
    """One placed design of a site.

    Attributes:
        name: the sheet's name (its folder and its part's label).
        source: where its design comes from: the template file, or
            ``SITE.toml: sheet N`` for an inline design.
        data: the design's template data (as read, not yet validated).
        flags: design flags by their ``onefold build`` name without dashes
            (``alpha``, ``bend-radius``), values as written in the file.
        x, y: where the sheet's resting origin (the centre of mass's ground
            projection) stands on the site (site unit).
        rotation_deg: the turn about the vertical (deg, counter-clockwise
            seen from above).
        entry: how errors name the entry (``sheet 2 'east'``).
    """

    name: str
    source: Path | str
    data: dict[str, Any]
    flags: dict[str, Any]
    x: float
    y: float
    rotation_deg: float
    entry: str


@dataclass(frozen=True)
class SiteSpec:
    """A site file read and checked.

    Attributes:
        name: the site's name (its files' stem).
        description: one line (may be empty).
        units: the site's unit ('mm', 'in', 'ft'): positions, and every
            sheet is built in it.
        sheets: the placed designs, in the file's order.
        path: the file.
        loads: the ``[loads]`` table checked (``LoadSpec`` fields and
            ``mesh``), or None: no outdoors check.
    """

    name: str
    description: str
    units: str
    sheets: tuple[SheetSpec, ...]
    path: Path = field(default=Path("site.toml"))
    loads: dict[str, Any] | None = None


def _loads(raw: object, site: str) -> dict[str, Any] | None:
    """The ``[loads]`` table as ``LoadSpec`` fields (and ``mesh``), checked."""
    if raw is None:
        return None
    from onefold_cad.mechanics.loads.spec import LoadSpec

    where = f"{site}: loads"
    if not isinstance(raw, dict):
        raise _fail(where, "must be a table ([loads])")
    _unknown(raw, tuple(LOADS_KEYS), where)
    out = {LOADS_KEYS[k]: v for k, v in raw.items()}
    mesh = out.pop("mesh", "normal")
    if mesh not in ("coarse", "normal", "fine"):
        raise _fail(f"{where}: mesh", f"must be coarse, normal or fine, got {mesh!r}")
    try:
        LoadSpec(**out)
    except InvalidParameterError as exc:
        key = next((k for k, v in LOADS_KEYS.items() if v == exc.parameter), exc.parameter)
        raise _fail(f"{where}: {key}", str(exc).split(": ", 1)[1]) from None
    except TypeError as exc:
        raise _fail(where, str(exc)) from None
    return {**out, "mesh": mesh}


def find_site(ref: str | Path) -> Path:
    """The site file given as a path or as a shipped site's name (a
    templates folder's ``site-NAME.toml``: :func:`onefold_cad.templates.find_site_file`)."""
    return find_site_file(ref)


def _fail(where: str, message: str) -> InvalidParameterError:
    return InvalidParameterError(where, message)


def _number(value: object, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise _fail(where, f"must be a number, got {value!r}")
    if not math.isfinite(value):
        raise _fail(where, f"must be finite, got {value!r}")
    return float(value)


def _file_name(value: object, where: str) -> str:
    if not isinstance(value, str) or not _NAME.match(value):
        raise _fail(
            where,
            f"must be a file-safe name (letters, digits, '.', '_', '-'), got {value!r}",
        )
    return value


def _unknown(table: dict[str, Any], allowed: tuple[str, ...], where: str) -> None:
    for key in table:
        if key not in allowed:
            raise _fail(f"{where}: {key}", f"unknown key (allowed: {', '.join(allowed)})")


def _sheet(raw: object, i: int, base: Path, site: str) -> SheetSpec:
    head = f"{site}: sheet {i}"
    if not isinstance(raw, dict):
        raise _fail(head, f"must be a table ([[sheet]]), got {raw!r}")
    name = raw.get("name")
    entry = f"sheet {i}" + (f" {name!r}" if isinstance(name, str) else "")
    where = f"{site}: {entry}"
    _unknown(raw, SHEET_KEYS, where)
    for key in ("name", "x", "y"):
        if key not in raw:
            raise _fail(f"{where}: {key}", "missing")
    name = _file_name(raw["name"], f"{where}: name")
    x, y = _number(raw["x"], f"{where}: x"), _number(raw["y"], f"{where}: y")
    rotation = _number(raw.get("rotation", 0.0), f"{where}: rotation")
    has_t, has_d = "template" in raw, "design" in raw
    if has_t == has_d:
        raise _fail(f"{where}: template", "give exactly one of template = NAME or [sheet.design]")
    source: Path | str
    if has_t:
        ref = raw["template"]
        if not isinstance(ref, str) or not ref:
            raise _fail(f"{where}: template", f"must be a template name or path, got {ref!r}")
        local = base / ref
        try:
            source = find_template(local if local.is_file() else ref)
        except InvalidParameterError as exc:
            raise _fail(f"{where}: template", str(exc).split(": ", 1)[1]) from None
        data = read_template(source)
    else:
        if not isinstance(raw["design"], dict):
            raise _fail(f"{where}: design", "must be a table ([sheet.design])")
        source, data = f"{site}: {entry}: design", dict(raw["design"])
    flags = raw.get("flags", {})
    if not isinstance(flags, dict):
        raise _fail(f"{where}: flags", "must be a table, e.g. flags = { alpha = 32.0 }")
    for key, value in flags.items():
        if isinstance(value, dict | list):
            raise _fail(f"{where}: flags.{key}", f"must be a number or a string, got {value!r}")
    return SheetSpec(name, source, data, dict(flags), x, y, rotation, entry)


def read_site(ref: str | Path) -> SiteSpec:
    """Read and check a site file (a path or a shipped site's name).

    Raises:
        InvalidParameterError: the file cannot be read, is not UTF-8 TOML,
            nests too deeply (:func:`onefold_cad.templates.read_toml`), lists
            more than :data:`MAX_SHEETS` sheets, or an entry is malformed (an
            unknown key, a missing or mistyped value, an unknown template,
            two sheets of one name), named by the file, the entry and the key.
    """
    path = find_site(ref)
    site = path.name
    raw = read_toml(path, "SITE")
    sheet = raw.get("sheet")
    kinds = ("quadrilateral", "polygon", "rectangle")
    if "frame" in raw or (isinstance(sheet, dict) and any(k in sheet for k in kinds)):
        raise _fail(
            str(path), "a design template (it has a [sheet] or [frame] table), not a site "
            f"file: build it with onefold build {path}"
        )  # fmt: skip
    _unknown(raw, SITE_KEYS, site)
    name = _file_name(raw.get("name", path.stem), f"{site}: name")
    units = raw.get("units")
    if units not in _UNITS:
        raise _fail(f"{site}: units", f"must be one of {', '.join(_UNITS)}, got {units!r}")
    description = raw.get("description", "")
    if not isinstance(description, str):
        raise _fail(f"{site}: description", f"must be a string, got {description!r}")
    entries = raw.get("sheet")
    if not isinstance(entries, list) or not entries:
        raise _fail(f"{site}: sheet", "missing: a site lists its sheets as [[sheet]] tables")
    if len(entries) > MAX_SHEETS:
        raise _fail(
            f"{site}: sheet",
            f"at most {MAX_SHEETS} sheets in a site, got {len(entries)} (every sheet's part "
            "stays in memory until the site's files are written; split the site into several "
            "files)",
        )
    sheets = tuple(_sheet(e, i, path.parent, site) for i, e in enumerate(entries, 1))
    seen: dict[str, str] = {}
    for s in sheets:
        if s.name in seen:
            raise _fail(
                f"{site}: {s.entry}: name", f"{s.name!r} is also the name of {seen[s.name]}"
            )
        seen[s.name] = s.entry
    if name in seen:
        raise _fail(f"{site}: name", f"{name!r} is also a sheet's name (their files would mix)")
    loads = _loads(raw.get("loads"), site)
    return SiteSpec(name, description, str(units), sheets, path, loads)
