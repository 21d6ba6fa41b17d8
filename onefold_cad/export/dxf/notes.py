"""The text of the DXF's NOTES layer: what the shop needs beside the drawing
(material, bend directions, compensation, the bend table, how the cones are
formed, kerf, hole, size and mass), one line each, from the flat pattern alone (the fabrication
rules' numbers; nothing is derived here).
"""

from __future__ import annotations

from onefold_cad.fabrication.bend_table import bend_table
from onefold_cad.fabrication.flat_pattern import FlatPattern
from onefold_cad.fabrication.mass import part_mass

__all__ = ["flat_pattern_notes"]


def flat_pattern_notes(p: FlatPattern) -> tuple[str, ...]:
    """The NOTES text lines of the flat pattern ``p``."""
    mat, u = p.material, p.units.value
    w, h = p.size
    lines = [
        f"ONE-FOLD FLAT PATTERN: {p.name}",
        f"units: {u}",
        f"material: {mat.name or 'unspecified'}",
        f"thickness t = {mat.thickness:g} {u}, bend radius r = {mat.bend_radius:g} {u}, "
        f"K-factor = {mat.k_factor:g}, reference surface {mat.sheet_surface.value}",
        "UP = the flat sheet's top face (the face this drawing shows) ends inside the bend: "
        "the sides rise towards you; DOWN = the bottom face ends inside: they drop away",
    ]
    for half in p.halves:
        side = "+x" if half.name == "plus_x" else "-x"
        lines.append(f"fold half {side}: {half.label} (layer {half.layer})")
    if p.fold_rulings:
        lines.append(
            f"ruling folds: {len(p.fold_rulings)} rulings of the paper model's fan are folds "
            "(planar triangles meeting at an angle), drawn on BEND_UP/BEND_DOWN and listed in "
            "the bend sheet; the blank does not compensate them (width error 2 x shift each)"
        )
    if p.thickness <= 0.0:
        lines.append("thickness compensation: none (t = 0, sharp crease)")
    elif p.compensation == "none":
        e = p.move.errors
        lines.append(
            "thickness compensation: NONE (asked for): this blank is the designed outline; "
            f"across each half it is 2 x shift wider than the bend model asks ({e[0]:.4f}, "
            f"{e[1]:.4f} {u} for +x, -x)"
        )
        lines += [f"limit passed: {q.message}" for q in p.problems]
    else:
        shown = [round(x, 9) + 0.0 for x in p.move.errors]  # no '-0.0000'
        lines.append(
            f"thickness compensation: each side moved {p.shift:.4f} {u} towards the fold line "
            "(the mean of the halves' shifts SB - BA/2); blank width error across +x, -x: "
            f"{shown[0]:.4f}, {shown[1]:.4f} {u}"
        )
    lines += bend_table(p).splitlines()
    if mat.cones_compensated:
        lines.append(
            "cones: formed past their springback at every point, each station to the radius "
            f"in {p.name}-cones.csv (tighter than the cone's, which the steel springs back to)"
        )
    lines.append(f"kerf: {p.kerf:g} {u} (cut contours offset by kerf/2)")
    if p.hole_diameter > 0.0:
        lines.append(f"relief hole: diameter {p.hole_diameter:g} {u} at the apex mark")
    lines.append(f"flat size: {w:.3f} x {h:.3f} {u}, area {p.area:.3f} sq {u}")
    mass = part_mass(p.material, p.units, p.area)  # the one mass formula (kg, lb; kg/m^3)
    if mass is not None:
        lines.append(f"mass: {mass}")
    return tuple(lines)
