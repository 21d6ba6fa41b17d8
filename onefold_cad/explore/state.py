"""One state of the page: a design solved, folded, placed, meshed and measured.

Every number and every vertex the page shows comes from here; the page only
draws. The 3D form is :meth:`FoldedSheet.mesh` moved by
:func:`onefold_cad.fabrication.rules.resting_placement` (standing as the STEP's body
rests on the ground, z up: the placement the report, STEP, GLB and previews use), the
flat pattern is :func:`onefold_cad.fabrication.flat_pattern.flat_pattern` drawn by
:func:`onefold_cad.explore.flat_svg.flat_pattern_svg`, and the numbers and warnings are
those of :func:`onefold_cad.fabrication.report.design_report`, from the functions it
calls (:func:`~onefold_cad.fabrication.report.report_warnings`,
:func:`~onefold_cad.fabrication.report.resting_numbers`); what only the report shows
(the surface's developability and area, the problem's conditioning) is left to the
JSON download: the page asks for a state on every move of a slider.

A design the fabrication model cannot make (a bend zone reaching a corner,
...) still shows its form: the flat pattern's error is one message among the
others, exactly as the command prints it.
"""

from __future__ import annotations

import base64
import hashlib
import time
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from onefold_cad.design import Design, fold_design
from onefold_cad.errors import OneFoldError
from onefold_cad.explore.controls import PAGE_FLAGS, ParameterProblem, page_values
from onefold_cad.explore.flat_svg import flat_pattern_svg
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, relief_hole_problem
from onefold_cad.fabrication.rules import resting_placement

if TYPE_CHECKING:
    from onefold_cad.fabrication.flat_pattern import FlatPattern

__all__ = ["MESH_ANGULAR", "MESH_RADIAL", "design_state", "mesh_key", "problem_state", "message"]

_RESTING = ("height", "span", "width", "depth", "footprint_area", "tilt_deg", "stable")

#: Mesh density of the 3D view (:meth:`FoldedSheet.mesh` arguments): 60 angular steps
#: draw the default template's form as 120 do (the canvas differs in under 0.2 % of
#: its pixels, on the outline's anti-aliased lines) with half the triangles, which
#: software WebGL draws in a third less time; the 16 radial steps keep the shading
#: near the apex (the rays are straight: they change nothing else).
MESH_ANGULAR = 60
MESH_RADIAL = 16


def message(level: str, text: str, controls: Sequence[str] = ()) -> dict[str, Any]:
    """One message for the page: ``level`` 'error' or 'warning', the text on one
    line as the CLI prints it, and the page controls it concerns."""
    return {"level": level, "text": " ".join(str(text).split()), "controls": list(controls)}


def _b64(a: np.ndarray, dtype: str) -> str:
    return base64.b64encode(np.ascontiguousarray(a, dtype=dtype).tobytes()).decode("ascii")


def _controls(exc: OneFoldError) -> tuple[str, ...]:
    name = getattr(exc, "parameter", "")
    return (name,) if name in PAGE_FLAGS else ()


def _add(messages: list[dict[str, Any]], m: dict[str, Any]) -> None:
    """Append ``m`` unless it repeats a message already there: the same text,
    or that text with a tail (the report's warning of a refusal already shown
    as the error: ``...; build refuses the DXF ...``, ``... (flat pattern; ...)``)."""
    if not any(m["text"].startswith(old["text"]) for old in messages):
        messages.append(m)


def problem_state(problem: ParameterProblem) -> dict[str, Any]:
    """The state of a page whose values the design refuses: the message only."""
    return {"ok": False, "messages": [message("error", problem.message, problem.controls)]}


def _numbers(
    design: Design, folded: Any, pattern: FlatPattern | None, report: bool
) -> dict[str, Any]:
    """The numbers the page prints (design units, degrees), as the report gives
    them (:func:`~onefold_cad.fabrication.report.design_report`'s ``crease``,
    ``direction_surface``, ``resting``, ``relief_hole_diameter`` and
    ``flat_size``); those of the resting form, the hole and the flat pattern
    None unless ``report`` (the report's part of them could be made)."""
    from onefold_cad.fabrication.report import resting_numbers

    sol = folded.solution
    numbers: dict[str, Any] = {
        "fold_angles": {
            c.name: {"deg": float(c.fold_angle_deg), "bend": c.bend} for c in folded.crease
        },
        "apex_height": float(sol.apex_height),
        "angle_condition_error_deg": float(sol.angle_condition_error_deg),
        **dict.fromkeys(_RESTING, None),
        "relief_hole": None,
        "flat_size": None,
    }
    if report:
        r = resting_numbers(design, folded)
        numbers.update(
            height=r["height"],
            span=r["span"],
            width=r["footprint"]["width"],
            depth=r["footprint"]["depth"],
            footprint_area=r["footprint"]["area"],
            tilt_deg=r["tilt_deg"],
            stable=r["stable"],
            relief_hole=float(relief_hole_diameter(design, folded)),
            flat_size=None if pattern is None else list(pattern.size),
        )
    return numbers


def mesh_key(pts: np.ndarray, faces: np.ndarray) -> str:
    """A short name of a mesh's triangles: its vertex and triangle counts and a
    hash of the indices (the page keeps the triangles while it stays the same)."""
    digest = hashlib.blake2b(np.ascontiguousarray(faces).tobytes(), digest_size=8).hexdigest()
    return f"{len(pts)}-{len(faces)}-{digest}"


def design_state(design: Design, known_mesh: str | None = None) -> dict[str, Any]:
    """Solve, fold, place, mesh and measure ``design`` for the page.

    Returns:
        A JSON-ready dict: ``ok`` (the form was solved), ``messages`` (errors
        and warnings, each as the CLI words it), ``page`` (the design's
        control values, see :func:`onefold_cad.explore.controls.page_values`),
        and when solved ``numbers``, ``form`` (the resting mesh as base64
        float32 positions and uint16 or uint32 (``index_type``) triangle
        indices, the apex, the crease halves, the bounding box; z up, design
        units; ``mesh_key``: :func:`mesh_key`, and the indices None when it is
        ``known_mesh``, the page's), ``flat_svg`` (or None when the flat pattern
        cannot be made) and ``server_ms``.
    """
    from onefold_cad.fabrication.flat_pattern import flat_pattern
    from onefold_cad.fabrication.report import report_warnings

    t0 = time.perf_counter()
    messages: list[dict[str, Any]] = []
    state: dict[str, Any] = {"ok": False, "messages": messages, "page": page_values(design)}
    try:
        folded = fold_design(design)
    except OneFoldError as exc:
        messages.append(message("error", str(exc), _controls(exc)))
        return state

    verts, faces = folded.mesh(MESH_ANGULAR, MESH_RADIAL)
    place = resting_placement(design, folded)
    pts = place.apply(verts)
    if not np.all(np.isfinite(pts)):
        messages.append(message("error", "design: the folded form has non-finite coordinates"))
        return state
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    apex = place.apply(folded.apex[None, :])[0]
    crease = [
        {
            "half": c.name,
            "bend": c.bend,
            "fold_angle_deg": float(c.fold_angle_deg),
            "points": [apex.tolist(), place.apply(c.end_3d[None, :])[0].tolist()],
        }
        for c in folded.crease
    ]

    small = len(pts) < 2**16
    key = mesh_key(pts, faces)
    # the flat pattern's refusal, as `onefold build` words it (the relief hole first)
    pattern = None
    refusal: OneFoldError | None = relief_hole_problem(design)
    if refusal is None:
        try:
            pattern = flat_pattern(design, folded)
        except OneFoldError as exc:
            refusal = exc
    if refusal is not None:
        messages.append(message("error", str(refusal), _controls(refusal)))
    # the report's warnings and numbers, without its measurements of the surface
    # (developability, conditioning: the JSON download has them)
    try:
        warnings, measured, _ = report_warnings(design, folded, pattern)
        numbers = _numbers(design, folded, measured, report=True)
    except OneFoldError as exc:
        _add(messages, message("error", str(exc), _controls(exc)))
        numbers = _numbers(design, folded, None, report=False)
    else:
        for w in warnings:
            _add(messages, message("warning", w))

    state.update(
        ok=True,
        numbers={"units": design.units.value, **numbers},
        form={
            "positions": _b64(pts, "<f4"),
            "indices": None if key == known_mesh else _b64(faces, "<u2" if small else "<u4"),
            "mesh_key": key,
            "index_type": "uint16" if small else "uint32",
            "vertex_count": int(len(pts)),
            "triangle_count": int(len(faces)),
            "apex": apex.tolist(),
            "crease": crease,
            "bbox": {"min": lo.tolist(), "max": hi.tolist()},
        },
        flat_svg=None if pattern is None else flat_pattern_svg(pattern),
    )
    state["server_ms"] = 1e3 * (time.perf_counter() - t0)
    return state
