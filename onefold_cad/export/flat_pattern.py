"""The flat pattern of a design: the 2D geometry a cutting table needs.

Everything here is plain numpy (plus :func:`ezdxf.math.offset_vertices_2d`
for the kerf's mitred offset); :mod:`onefold_cad.export.dxf` only draws it.
Lengths are in the design's unit, angles in degrees, points in the sheet's
own frame (for a rectangle: a corner at the origin, sides on the axes).

Thickness compensation (t > 0). The designed surface has a sharp crease; the
real sheet bends with inside radius r. For a bend of angle psi the material
on each side of the fold line moves towards it by BD/2, measured
perpendicular to the fold line (BD = 2 OSSB - BA, the bend deduction of
:func:`onefold_cad.bend_values`), so that the flanges' mold lines of the
formed part meet where the designed crease is. The fold line has two halves
with their own angles psi+ and psi-. One rigid move per side keeps every
straight edge straight, so both sides move by the **mean** deduction:
``shift = (BD+ + BD-) / 4`` per side. The residual, the largest difference
between the deduction applied across a half and that half's own BD, is
``|BD+ - BD-| / 2`` (0 for symmetric designs); it is reported in
:attr:`FlatPattern.residual` and in the notes. Inside the bend zone (within
BA/2 of each half) the outline is bridged by a straight segment from the
upper side's edge at +BA/2 to the lower side's edge at -BA/2; the fold half
ends at that bridge. Every sheet corner off the fold line must lie farther
than BD/2 + BA/2 from it (else 'thickness' is rejected). With t = 0 nothing is
compensated (sharp crease), whatever the bend radius.

OSSB = (r + t) tan(psi/2) is the outside set-back, so the compensation makes
the outside mold lines meet on the designed crease; for a MID or INSIDE
reference surface the set-back of that surface, (r + s t) tan(psi/2) with
s = 1/2 or 0 (by bend direction), would be the refinement.

Kerf: the cut contours are offset by kerf/2, the outline outwards with
mitred corners (each edge moves exactly kerf/2), the relief hole inwards.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.design import Design, design_mass, relief_hole_diameter
from onefold_cad.errors import InvalidParameterError, InvalidSheetError
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Units, bend_values
from onefold_cad.geometry.sheet import _check_simple, boundary_distance

__all__ = ["FoldHalf", "FlatPattern", "flat_pattern", "polygon_area", "polygon_perimeter"]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class FoldHalf:
    """One half of the fold line on the flat pattern.

    Attributes:
        name: 'plus_x' or 'minus_x' (the crease half of :class:`CreaseHalf`).
        start: ``(2,)`` H, where both halves meet (sheet frame).
        end: ``(2,)`` where the half meets the outline (sheet frame).
        angle_deg: fold angle (deg), 0 = flat.
        bend: 'UP' or 'DOWN', seen from the drawing's (top, +z) side.
        allowance: bend allowance BA (length); 0 when t = 0.
        deduction: bend deduction BD (length); 0 when t = 0.
        zone: ``(k, 2, 2)`` bend-zone limit lines at +-BA/2 (k = 2, or 0 when
            t = 0 or BA = 0), each ``(start, end)`` in the sheet frame.
    """

    name: str
    start: Array
    end: Array
    angle_deg: float
    bend: str
    allowance: float
    deduction: float
    zone: Array

    @property
    def layer(self) -> str:
        """'BEND_UP' or 'BEND_DOWN'."""
        return f"BEND_{self.bend}"

    @property
    def label(self) -> str:
        """Direction and angle, e.g. 'DOWN 125.23 deg'."""
        return f"{self.bend} {self.angle_deg:.2f} deg"


@dataclass(frozen=True)
class FlatPattern:
    """The flat pattern of one design, in the sheet's own frame.

    Attributes:
        name: the design's name.
        units: the design's length unit.
        outline: ``(n, 2)`` the part's contour, CCW, thickness-compensated.
        cut_outline: ``(n, 2)`` the cutting path: ``outline`` offset outwards
            by kerf/2 (equal to ``outline`` when kerf = 0).
        apex: ``(2,)`` H, the apex point (centre of the relief hole).
        hole_diameter: the relief hole's diameter (0 = none).
        cut_hole_diameter: the hole's cutting path diameter (hole - kerf).
        halves: the fold halves ('plus_x', 'minus_x').
        rulings: ``(m, 2, 2)`` ruling segments for etching (off the fold
            line, outside the bend zones and the hole).
        fold_direction: ``(2,)`` unit vector of the fold line (H -> +x half).
        shift: how far each side moved towards the fold line (length).
        residual: ``|BD+ - BD-| / 2``, the compensation's largest error
            across a fold half (length).
        kerf: the kerf used (length).
        thickness: sheet thickness (length).
        notes: the text lines for the NOTES layer.
    """

    name: str
    units: Units
    outline: Array
    cut_outline: Array
    apex: Array
    hole_diameter: float
    cut_hole_diameter: float
    halves: tuple[FoldHalf, FoldHalf]
    rulings: Array
    fold_direction: Array
    shift: float
    residual: float
    kerf: float
    thickness: float
    notes: tuple[str, ...]

    @property
    def area(self) -> float:
        """Net flat area: outline minus relief hole (length^2)."""
        return polygon_area(self.outline) - math.pi * self.hole_diameter**2 / 4.0

    @property
    def size(self) -> tuple[float, float]:
        """Bounding-box width and height of the outline (length)."""
        ext = np.ptp(self.outline, axis=0)
        return float(ext[0]), float(ext[1])

    @property
    def scale(self) -> float:
        """The larger bounding-box side (length), for mark and text sizes."""
        return max(self.size)


def polygon_area(p: Array) -> float:
    """Signed shoelace area of a closed polygon ``(n, 2)`` (CCW > 0)."""
    q = np.roll(p, -1, axis=0)
    return 0.5 * float(np.sum(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]))


def polygon_perimeter(p: Array) -> float:
    """Perimeter of a closed polygon ``(n, 2)``."""
    return float(np.sum(np.hypot(*(np.roll(p, -1, axis=0) - p).T)))


def _clip_chain(chain: Array, c_start: float, c_end: float) -> Array:
    """Keep the part of a side's chain (y > 0 side) beyond the bend zones.

    ``chain`` runs from one fold-line end to the other (both ends below the
    limits); returns ``[crossing of y = c_start, vertices..., crossing of y = c_end]``.
    """
    y = chain[:, 1]
    i = int(np.argmax(y > c_start))
    j = len(y) - 1 - int(np.argmax(y[::-1] > c_end))
    top = max(c_start, c_end)
    if not (y[i] > c_start and y[j] > c_end) or i > j or np.any(y[i : j + 1] <= top):
        raise InvalidParameterError(
            "thickness",
            "the thickness-compensated outline is invalid: a sheet corner lies within a bend "
            f"zone (closer than BD/2 + BA/2 = {max(c_start, c_end) + abs(y[0]):.6g} to the fold "
            "line); reduce thickness or bend_radius, or use a wider sheet",
        )

    def cross(a: Array, b: Array, c: float) -> Array:
        s = (c - a[1]) / (b[1] - a[1])
        return np.array([a[0] + s * (b[0] - a[0]), c])

    return np.vstack(
        [
            cross(chain[i - 1], chain[i], c_start),
            chain[i : j + 1],
            cross(chain[j + 1], chain[j], c_end),
        ]
    )


def _dedupe(p: Array, tol: float) -> Array:
    """Drop consecutive (cyclic) vertices closer than ``tol``."""
    keep = np.hypot(*(np.roll(p, -1, axis=0) - p).T) > tol
    return p[keep]


def _compensate(
    vertices: Array, k: int, shift: float, c_plus: float, c_minus: float
) -> tuple[Array, Array]:
    """The compensated upper and lower outline pieces in the fold frame.

    Upper runs from the +x bridge to the -x bridge, lower from -x to +x (CCW).
    """
    mirror = np.array([1.0, -1.0])
    off_axis = np.abs(vertices[1:k, 1]).tolist() + np.abs(vertices[k + 1 :, 1]).tolist()
    limit = shift + max(c_plus, c_minus)
    if min(off_axis) <= limit:
        raise InvalidParameterError(
            "thickness",
            "the thickness-compensated outline is invalid: a sheet corner lies "
            f"{min(off_axis):.6g} from the fold line, inside a bend zone (BD/2 + BA/2 = "
            f"{limit:.6g}); reduce thickness or bend_radius, or move the corner",
        )
    upper = vertices[: k + 1] - np.array([0.0, shift])
    lower = np.vstack([vertices[k:], vertices[:1]]) * mirror - np.array([0.0, shift])
    return _clip_chain(upper, c_plus, c_minus), _clip_chain(lower, c_minus, c_plus) * mirror


def _ruling_segments(ends: Array, shift: float, c: float, hole_r: float) -> Array:
    """Ruling segments (fold frame) moved with their side, clipped to the
    flat flanges (|y| >= c) and outside the hole (|p| >= hole_r)."""
    out = []
    for e in ends:
        s = 1.0 if e[1] > 0.0 else -1.0
        p0, p1 = np.array([0.0, -s * shift]), e - np.array([0.0, s * shift])
        d = p1 - p0
        lo = 0.0
        if c > 0.0 or shift > 0.0:
            lo = (c - s * p0[1]) / (s * d[1])
        if hole_r > 0.0:  # |p0 + u d| >= hole_r
            a, b, cc = d @ d, 2.0 * (p0 @ d), p0 @ p0 - hole_r**2
            disc = b * b - 4.0 * a * cc
            if disc > 0.0:
                lo = max(lo, (-b + math.sqrt(disc)) / (2.0 * a))
        if lo < 1.0 - 1e-9:
            out.append([p0 + max(lo, 0.0) * d, p1])
    return np.array(out, dtype=float).reshape(-1, 2, 2)


def _require_simple(polygon: Array, param: str, what: str) -> None:
    """InvalidParameterError naming ``param`` unless ``polygon`` is simple."""
    try:
        _check_simple(polygon, param)
    except InvalidSheetError as exc:
        raise InvalidParameterError(param, f"{what} ({exc})") from None


def flat_pattern(design: Design, folded: FoldedSheet) -> FlatPattern:
    """Compute the flat pattern of ``design`` from its fold.

    Args:
        design: the design (sheet, material, units, name).
        folded: ``build_design(design)`` (fold angles and bend directions).

    Raises:
        InvalidParameterError: 'folded' not from this design's sheet;
            'thickness' when the compensated outline becomes invalid;
            'relief_hole' when the hole does not fit in the compensated
            outline; 'kerf' when the kerf is too large for the sheet or hole.
    """
    if folded.sheet is not design.sheet:
        raise InvalidParameterError("folded", "must be build_design(design) of this design")
    sheet, mat = design.sheet, design.material
    v = np.asarray(sheet.vertices, dtype=float)
    k = sheet.minus_x_index
    tol = 1e-12 * sheet.size
    t = mat.thickness
    values = [bend_values(c.fold_angle_deg, mat) for c in folded.crease]
    if t > 0.0:
        ba = [b.allowance for b in values]
        bd = [b.deduction for b in values]
    else:
        ba, bd = [0.0, 0.0], [0.0, 0.0]
    shift = (bd[0] + bd[1]) / 4.0
    residual = abs(bd[0] - bd[1]) / 2.0
    c_plus, c_minus = ba[0] / 2.0, ba[1] / 2.0

    if t > 0.0:
        up, lo = _compensate(v, k, shift, c_plus, c_minus)
        outline = _dedupe(np.vstack([up, lo]), tol)
        up_first, up_last, lo_first, lo_last = up[0], up[-1], lo[0], lo[-1]
        end_plus = np.array([(up_first[0] + lo_last[0]) / 2.0, 0.0])
        end_minus = np.array([(up_last[0] + lo_first[0]) / 2.0, 0.0])
        zones = [
            np.array([[[0.0, c_plus], up_first], [[0.0, -c_plus], lo_last]]),
            np.array([[[0.0, c_minus], up_last], [[0.0, -c_minus], lo_first]]),
        ]
        if not (min(up_first[0], lo_last[0]) > 0.0 > max(up_last[0], lo_first[0])):
            raise InvalidParameterError(
                "thickness",
                "the thickness-compensated outline is invalid: a bend zone's edge no longer "
                "reaches past H; reduce thickness or bend_radius",
            )
        _require_simple(outline, "thickness", "the thickness-compensated outline is invalid")
    else:
        outline = v.copy()
        end_plus, end_minus = v[0].copy(), v[k].copy()
        zones = [np.zeros((0, 2, 2)), np.zeros((0, 2, 2))]
    zones = [z if z.size and abs(z[0, 0, 1]) > tol else np.zeros((0, 2, 2)) for z in zones]

    origin = np.zeros(2)
    inner = boundary_distance(outline, origin)
    hole = relief_hole_diameter(design, folded)
    if hole > 0.0 and hole / 2.0 >= inner:
        raise InvalidParameterError(
            "relief_hole",
            f"diameter must be < {2.0 * inner:.6g} (twice the distance from H to the nearest "
            f"edge of the flat pattern), got {hole:g}",
        )
    kerf = mat.kerf
    if kerf > 0.0 and kerf / 2.0 >= inner:
        raise InvalidParameterError(
            "kerf", f"must be < {2.0 * inner:.6g} (the flat pattern's inradius about H x 2)"
        )
    if hole > 0.0 and kerf >= hole:
        raise InvalidParameterError(
            "kerf", f"must be < the relief hole's diameter {hole:g}, got {kerf:g}"
        )
    place = sheet.to_sheet
    outline_s = place.apply(outline)
    if kerf > 0.0:
        from ezdxf.math import offset_vertices_2d  # ezdxf only when a kerf is cut

        cut = np.array([(p.x, p.y) for p in offset_vertices_2d(outline_s, -kerf / 2.0, True)])
        _require_simple(cut, "kerf", "the kerf offset self-intersects")
    else:
        cut = outline_s.copy()

    halves = []
    for crease, end, b, a, d, z in zip(
        folded.crease, (end_plus, end_minus), values, ba, bd, zones, strict=True
    ):
        zone = place.apply(z.reshape(-1, 2)).reshape(-1, 2, 2)
        halves.append(
            FoldHalf(
                crease.name,
                place.apply(origin),
                place.apply(end),
                b.angle_deg,
                crease.bend,
                a,
                d,
                zone,
            )
        )
    ends = folded.rulings_flat[:, 1]
    ends = ends[np.abs(ends[:, 1]) > 1e-9 * sheet.size]
    rul = _ruling_segments(ends, shift, max(c_plus, c_minus), max(hole - kerf, 0.0) / 2.0)
    pattern = FlatPattern(
        name=design.name,
        units=design.units,
        outline=outline_s,
        cut_outline=cut,
        apex=place.apply(origin),
        hole_diameter=hole,
        cut_hole_diameter=hole - kerf if hole > 0.0 else 0.0,
        halves=(halves[0], halves[1]),
        rulings=place.apply(rul.reshape(-1, 2)).reshape(-1, 2, 2),
        fold_direction=place.apply_direction(np.array([1.0, 0.0])),
        shift=shift,
        residual=residual,
        kerf=kerf,
        thickness=t,
        notes=(),
    )
    return _with_notes(pattern, design)


def _with_notes(p: FlatPattern, design: Design) -> FlatPattern:
    """``p`` with its NOTES text lines filled in."""
    from dataclasses import replace

    mat, u = design.material, design.units.value
    w, h = p.size
    lines = [
        f"ONE-FOLD FLAT PATTERN: {design.name}",
        f"units: {u}",
        f"material: {mat.name or 'unspecified'}",
        f"thickness t = {mat.thickness:g} {u}, bend radius r = {mat.bend_radius:g} {u}, "
        f"K-factor = {mat.k_factor:g}, reference surface {mat.sheet_surface.value}",
    ]
    for half in p.halves:
        side = "+x" if half.name == "plus_x" else "-x"
        extra = f", BA {half.allowance:.4f}, BD {half.deduction:.4f} {u}" if p.thickness else ""
        lines.append(f"fold half {side}: {half.label} (layer {half.layer}){extra}")
    if p.thickness > 0.0:
        lines.append(
            f"thickness compensation: each side moved {p.shift:.4f} {u} towards the fold line "
            f"(mean BD/2); residual |BD+ - BD-|/2 = {p.residual:.4f} {u}"
        )
    else:
        lines.append("thickness compensation: none (t = 0, sharp crease)")
    lines.append(f"kerf: {p.kerf:g} {u} (cut contours offset by kerf/2)")
    if p.hole_diameter > 0.0:
        lines.append(f"relief hole: diameter {p.hole_diameter:g} {u} at the apex mark")
    lines.append(f"flat size: {w:.3f} x {h:.3f} {u}, area {p.area:.3f} sq {u}")
    mass = design_mass(design, p.area)  # the one mass formula (kg or lb, density kg/m^3)
    if mass is not None:
        lines.append(f"mass: {mass}")
    return replace(p, notes=tuple(lines))
