"""Flag values put into template data: :class:`Overrides` replaces template
values, :func:`changed_flags` says which flags changed one, :func:`mark_changes`
keeps the description and material name true, :func:`derived_name` names a
design after what defines it.
"""

from __future__ import annotations

import copy
import math
from typing import Any

from onefold_cad.errors import InvalidParameterError
from onefold_cad.flags.design_flags import DESIGN_FLAGS

__all__ = ["changed_flags", "derived_name", "flags_text", "mark_changes", "Overrides"]


# -- designs from templates and flags ---------------------------------------------
class Overrides:
    """Flag values that replace template values; None means "keep the template's"."""

    _FLAGS = {
        "frame.alpha": "--alpha",
        "frame.beta": "--beta",
        "frame.h_c": "--hc",
        "frame.radius": "--radius",
        "frame.divisions": "--divisions",
        "material.thickness": "--thickness",
        "material.bend_radius": "--bend-radius",
        "material.k_factor": "--k-factor",
        "material.kerf": "--kerf",
        "material.relief_hole": "--relief-hole",
        "material.density": "--density",
        "material.youngs_modulus": "--youngs-modulus",
        "material.poisson": "--poisson",
        "material.yield_stress": "--yield-stress",
        "material.hardening_modulus": "--hardening-modulus",
        "material.kinematic_hardening": "--kinematic-hardening",
        "material.crease_overbend": "--crease-overbend",
        "material.cone_forming": "--cone-forming",
    }
    _QUAD = {
        "x_plus": "--x-plus",
        "x_minus": "--x-minus",
        "y_plus": "--y-plus",
        "y_minus": "--y-minus",
    }

    def __init__(self, **values: Any) -> None:
        self.values = {k: v for k, v in values.items() if v is not None}

    def apply(self, data: dict[str, Any]) -> tuple[dict[str, Any], dict[str, str]]:
        """Template data with the flags applied, and the flag name of each changed key."""
        out = copy.deepcopy(data)
        v = self.values
        names: dict[str, str] = {}
        for key, flag in self._FLAGS.items():
            arg = flag[2:].replace("-", "_")
            if arg in v:
                table, fld = key.split(".")
                out.setdefault(table, {})[fld] = v[arg]
                names[key] = flag
        if "hc_fraction" in v:
            self._apply_hc_fraction(out, names)
        if "model" in v:
            out["model"] = v["model"]
            names["model"] = "--model"
        if "units" in v:
            out["units"] = v["units"]
            names["units"] = "--units"
        if "sheet_surface" in v:
            out.setdefault("material", {})["sheet_surface"] = v["sheet_surface"]
            names["material.sheet_surface"] = "--sheet-surface"
        if "name" in v:
            out["name"] = v["name"]
            names["name"] = "--name"
        self._apply_sheet(out, names)
        return out, names

    def _apply_hc_fraction(self, out: dict[str, Any], names: dict[str, str]) -> None:
        """``--hc-fraction F``: h_c = F R cos(alpha), with the frame's radius
        and alpha after the other flags (a template without a radius has the
        frame's default, 100).

        Raises:
            InvalidParameterError: ('--hc-fraction') given with ``--hc``, or
                not inside (-1, 1) (the f-line's ends).
        """
        f = self.values["hc_fraction"]
        if "hc" in self.values:
            raise InvalidParameterError("--hc-fraction", "cannot be combined with --hc")
        if not (isinstance(f, (int, float)) and -1.0 < f < 1.0):
            raise InvalidParameterError(
                "--hc-fraction",
                f"must be inside (-1, 1): the offset of H from the f-line's midpoint as a "
                f"fraction of the half f-line R cos(alpha) (-1 and 1 are its ends), got {f!r}",
            )
        from onefold_cad.geometry.frame_curve import half_chord

        frame = out.setdefault("frame", {})
        alpha, radius = frame.get("alpha"), frame.get("radius", _DEFAULT_RADIUS)
        try:  # a bad alpha or radius is the frame's to name: h_c is left to it
            half = half_chord(float(alpha), float(radius))
        except (TypeError, ValueError):
            half = math.nan
        if not (math.isfinite(half) and half > 0.0):
            frame["h_c"] = 0.0
        elif not (isinstance(frame.get("h_c"), (int, float)) and frame["h_c"] / half == f):
            frame["h_c"] = f * half  # (an h_c of this very fraction is kept to the bit)
        names["frame.h_c"] = "--hc-fraction"

    def _apply_sheet(self, out: dict[str, Any], names: dict[str, str]) -> None:
        v = self.values
        quad = {k: v[k] for k in self._QUAD if k in v}
        given = [
            f
            for f, on in (
                ("--polygon", "polygon" in v),
                ("--rectangle", "rectangle" in v),
                ("--x-plus/--x-minus/--y-plus/--y-minus", bool(quad)),
            )
            if on
        ]
        if len(given) > 1:
            raise InvalidParameterError(given[1], f"cannot be combined with {given[0]}")
        current = out.get("sheet")
        sheet = current if isinstance(current, dict) else {}
        if "polygon" in v:
            out["sheet"] = {"polygon": parse_polygon(v["polygon"])}
            names["sheet.polygon"] = "--polygon"
        elif "rectangle" in v:
            w, h = parse_rectangle(v["rectangle"])
            old = sheet.get("rectangle", {}) if isinstance(sheet.get("rectangle"), dict) else {}
            out["sheet"] = {"rectangle": {**old, "width": w, "height": h}}
            names["sheet.rectangle.width"] = names["sheet.rectangle.height"] = "--rectangle"
        elif quad:
            if "quadrilateral" in sheet:
                out["sheet"] = {"quadrilateral": {**sheet["quadrilateral"], **quad}}
            else:
                for key, flag in self._QUAD.items():
                    if key not in quad:
                        raise InvalidParameterError(
                            flag,
                            "missing: a quadrilateral sheet needs all of --x-plus, "
                            "--x-minus, --y-plus, --y-minus (each > 0)",
                        )
                out["sheet"] = {"quadrilateral": quad}
            for key, flag in self._QUAD.items():
                names[f"sheet.quadrilateral.{key}"] = flag
        if "apex_fraction" in v:
            rect = out.get("sheet", {}).get("rectangle")
            if not isinstance(rect, dict):
                raise InvalidParameterError(
                    "--apex-fraction", "applies to a rectangle sheet only (add --rectangle WxH)"
                )
            rect["apex_fraction"] = v["apex_fraction"]
            names["sheet.rectangle.apex_fraction"] = "--apex-fraction"


def _parse_number(text: str, flag: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise InvalidParameterError(flag, f"{text.strip()!r} is not a number") from None


def parse_polygon(text: str) -> list[list[float]]:
    pts = []
    for i, pair in enumerate(p for p in text.split(";") if p.strip()):
        parts = pair.split(",")
        if len(parts) != 2:
            raise InvalidParameterError(
                "--polygon",
                f'vertex {i} must be "x,y", got {pair.strip()!r} (format "x,y;x,y;...")',
            )
        pts.append([_parse_number(parts[0], "--polygon"), _parse_number(parts[1], "--polygon")])
    return pts


def parse_rectangle(text: str) -> tuple[float, float]:
    parts = text.lower().split("x")
    try:
        width, height = (float(p) for p in parts)
    except ValueError:
        raise InvalidParameterError(
            "--rectangle", f"must be WIDTHxHEIGHT (e.g. 3048x7315.2), got {text!r}"
        ) from None
    return width, height


#: The frame's radius where a template gives none (FrameCurve's default).
_DEFAULT_RADIUS = 100.0

_SHORT = {"hc": "hc", "hc_fraction": "hcf", "radius": "r", "divisions": "div",
          "apex_fraction": "af", "k_factor": "k", "bend_radius": "br", "relief_hole": "hole",
          "x_plus": "xp", "x_minus": "xm",
          "y_plus": "yp", "y_minus": "ym", "thickness": "t", "density": "rho",
          "youngs_modulus": "E", "poisson": "nu", "yield_stress": "sy", "hardening_modulus": "H",
          "kinematic_hardening": "kin", "crease_overbend": "ob"}  # fmt: skip


def derived_name(base: str, flags: dict[str, Any]) -> str:
    """``base`` followed by the design flags given, e.g. ``onefold-3048x7315.2-alpha35``:
    a file-safe name (at most 64 characters; a longer one keeps its start and
    ends in a hash of the whole) that says what defines the design."""
    parts = [base]
    for f in DESIGN_FLAGS:
        v = flags.get(f.dest)
        if v is None:
            continue
        if f.dest == "polygon":
            digest = _sha1(str(parse_polygon(v)))[:6]
            parts.append(f"polygon{len(parse_polygon(v))}-{digest}")
        elif f.dest == "rectangle":
            w, h = parse_rectangle(v)
            parts.append(f"{w:g}x{h:g}")
        elif f.dest in ("model", "units", "sheet_surface"):
            parts.append(str(v).lower())
        elif f.dest == "cone_forming":
            parts.append(f"cones-{v}")
        else:
            parts.append(f"{_SHORT.get(f.dest, f.dest)}{v:g}")
    name = "".join(c for c in "-".join(parts) if c.isalnum() or c in "._-")
    if len(name) > 64:
        name = f"{name[:55]}-{_sha1(name)[:8]}"
    return name


def _sha1(text: str) -> str:
    """The SHA-1 hex digest of ``text`` (hashlib, with OpenSSL, imported only
    when a name needs it: it costs solve more than the rest of this module)."""
    import hashlib

    return hashlib.sha1(text.encode()).hexdigest()


def _at(data: Any, key: str) -> Any:
    """The value at dotted ``key`` of template data (``material.thickness``), or
    :data:`_MISSING`."""
    for part in key.split("."):
        if not isinstance(data, dict) or part not in data:
            return _MISSING
        data = data[part]
    return data


_MISSING = object()


def changed_flags(before: dict[str, Any], after: dict[str, Any], names: dict[str, str]) -> set[str]:
    """The flags (``--alpha``) of ``names`` (key -> flag, from
    :meth:`Overrides.apply`) that changed a value of ``before`` into ``after``
    (a flag repeating the template's value changes nothing). ``before`` is
    the template's data with its defaults filled in (``design_to_data``), so
    that ``--hc 0`` on a template without ``h_c`` changes nothing."""
    return {
        flag for key, flag in names.items() if key != "name" and _at(before, key) != _at(after, key)
    }


def flags_text(flags: dict[str, Any]) -> str:
    """The design flags given (not None) with their values, as typed
    (``--rectangle 1000x400 --alpha 30``), in the order of :data:`DESIGN_FLAGS`."""
    parts = []
    for f in DESIGN_FLAGS:
        v = flags.get(f.dest)
        if v is None:
            continue
        if f.dest == "polygon":
            text = f"({len(parse_polygon(v))} vertices)"
        elif isinstance(v, float):
            text = f"{v:g}"
        else:
            text = str(v).strip()
        parts.append(f"{f.flag} {text}")
    return " ".join(parts)


def mark_changes(
    data: dict[str, Any],
    flags: dict[str, Any],
    changed: set[str],
    template: str,
    implicit: bool,
    by: str = "flags",
) -> dict[str, Any]:
    """Template data with flags applied, its description and material name
    made true again.

    Args:
        data: the template's data with the flags applied.
        flags: the design flags that define the design (dest -> value; None
            for a flag not given), listed in the description.
        changed: the flags that changed a value (:func:`changed_flags`).
        template: the template's name.
        implicit: no template was named (the default one was used).
        by: who set the values ('flags', 'the page').

    * Description: without a template the default template's is not
      inherited: ``from flags --rectangle 1000x400 --alpha 30 (other values:
      template patkau-one-fold)``. With one, its description is kept and
      followed by ``(changed by --alpha 40)``. No flag: unchanged.
    * Material name: when the thickness or bend radius changed, the inherited
      name no longer names the gauge it was. Its first part (up to the first
      comma: the material, by the templates' convention ``MATERIAL, GAUGE``)
      is kept and marked: ``304 stainless steel (from template
      patkau-one-fold), t and r from flags``.
    """
    text = flags_text(flags)
    if not text:
        return data
    out = copy.deepcopy(data)
    if implicit:
        out["description"] = f"from {by} {text} (other values: template {template})"
    else:
        base = str(data.get("description", "")).strip() or f"template {template}"
        out["description"] = f"{base} (changed by {text})"
    mat = out.get("material")
    own = [s for s, flag in (("t", "--thickness"), ("r", "--bend-radius")) if flag in changed]
    if own and isinstance(mat, dict) and str(mat.get("name", "")).strip():
        kind = str(mat["name"]).split(",", 1)[0].strip()
        mat["name"] = f"{kind} (from template {template}), {' and '.join(own)} from {by}"
    return out
