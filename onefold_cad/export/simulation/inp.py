"""The structural check as a CalculiX / Abaqus input file: NAME.inp.

:func:`write_structural_inp` writes the designed form as it stands (the
simulation's mesh, :class:`onefold_cad.mechanics.results.Simulation`) as a
shell model an engineer re-runs in their own program (``ccx -i NAME``; the
keywords are Abaqus's too):

- ``*NODE``: the mesh's nodes on the designed form in the resting frame
  (first, in the simulation's order) and the nodes that make each facet
  four curved six-node triangles
  (:mod:`onefold_cad.export.simulation.inp_mesh`: on the simulation's flat
  facets CalculiX's S6 converge slowly, 10 % below ours on the normal mesh),
  in metres, each number in at most 20 characters (12 significant digits:
  ccx 2.20 reads no more of a field, and 15 digits moved nodes of the 6 mm
  elements by the relief hole enough to invert them, "nonpositive jacobian");
- ``*ELEMENT, TYPE=S6``: six-node shell triangles (four per facet of the
  sheet's mesh, corners counter-clockwise seen from the sheet's top), element
  set ``SHEET``; the two sides of the crease share its nodes (a welded
  crease, as the ``held`` crease model is);
- ``*MATERIAL``: ``*ELASTIC`` (Pa), ``*DENSITY`` (kg/m^3), ``*PLASTIC`` at the
  yield stress, perfectly plastic; ``*SHELL SECTION`` of the sheet's thickness;
- node sets ``FEET`` (the designed resting contacts), ``CREASE`` and
  ``EVERY``; supports as the simulation's: ``anchored`` holds each foot in x,
  y and z, ``frictionless`` in z only, plus x and y of the first foot and the
  horizontal direction across the first two at the second (no rigid motion
  in the ground's plane);
- one ``*STEP, NLGEOM`` with ``*STATIC`` and gravity (``*DLOAD ... GRAV``):
  the weight, the ``U`` and ``RF`` fields in the ``.frd`` and the feet's
  reactions and every node's displacement in the ``.dat``.

SI units (m, N, Pa, kg). The same simulation gives the same bytes.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.choices import Units
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.simulation.inp_mesh import shell_mesh

__all__ = ["GRAVITY", "structural_model", "write_structural_inp"]

#: Standard gravity (m/s^2).
GRAVITY = 9.80665


def structural_model(sim: Any) -> dict[str, Any]:
    """The shell model's arrays in metres: ``nodes`` ``(N, 3)`` (the
    simulation's corners first, then the nodes
    :func:`onefold_cad.export.simulation.inp_mesh.shell_mesh` adds),
    ``elements`` ``(4 m, 6)`` (0-based S6 connectivity), ``feet`` and
    ``crease`` (node ids)."""
    scale = Units.parse(sim.unit).mm / 1000.0
    flat, faces = np.asarray(sim.flat), np.asarray(sim.faces)
    placed = np.asarray(sim.designed_positions)
    mesh = shell_mesh(placed, faces, flat)
    size = float(np.ptp(placed, axis=0).max())
    feet = np.flatnonzero(placed[:, 2] <= placed[:, 2].min() + 1e-9 * size)
    on_crease = np.abs(mesh.flat[:, 1]) <= 1e-12 * float(np.ptp(flat, axis=0).max())
    return {
        "nodes": mesh.nodes * scale,
        "elements": mesh.elements,
        "feet": feet,
        "crease": np.flatnonzero(on_crease),
    }


def _num(value: float) -> str:
    """A number in at most 20 characters (12 significant digits)."""
    return f"{float(value):.12g}"


def _ids(values: np.ndarray) -> list[str]:
    """Node ids (1-based) 16 a line, as the keyword format wants."""
    ids = [str(int(v) + 1) for v in values]
    return [", ".join(ids[i : i + 16]) for i in range(0, len(ids), 16)]


def _supports(sim: Any, model: dict[str, Any]) -> list[str]:
    feet = model["feet"]
    if sim.supports == "anchored":
        return ["*BOUNDARY", "FEET, 1, 3"]
    x = model["nodes"]
    first, second = int(feet[0]), int(feet[np.argmax(np.linalg.norm(x[feet] - x[feet[0]], axis=1))])
    d = x[second] - x[first]
    across = 2 if abs(d[0]) >= abs(d[1]) else 1  # hold the one less along the line
    return ["*BOUNDARY", "FEET, 3, 3", f"{first + 1}, 1, 2", f"{second + 1}, {across}, {across}"]


def inp_text(sim: Any, name: str) -> str:
    """NAME.inp's text (see the module docstring)."""
    model = structural_model(sim)
    scale = Units.parse(sim.unit).mm / 1000.0
    t = sim.thickness * scale
    out = [
        "*HEADING",
        f"{name}: onefold simulate's structural check, the designed form standing under its "
        f"weight on {sim.supports} feet (SI units: m, N, Pa, kg)",
        "*NODE, NSET=EVERY",
    ]
    out += [f"{i + 1}, {_num(p[0])}, {_num(p[1])}, {_num(p[2])}"
            for i, p in enumerate(model["nodes"])]  # fmt: skip
    out.append("*ELEMENT, TYPE=S6, ELSET=SHEET")
    out += [f"{k + 1}, " + ", ".join(str(int(v) + 1) for v in e)
            for k, e in enumerate(model["elements"])]  # fmt: skip
    out += ["*NSET, NSET=FEET", *_ids(model["feet"])]
    out += ["*NSET, NSET=CREASE", *_ids(model["crease"])]
    out += [
        "*MATERIAL, NAME=SHEET_STEEL",
        "*ELASTIC",
        f"{_num(sim.youngs_modulus_GPa * 1e9)}, {_num(sim.poisson)}",
        "*DENSITY",
        _num(sim.density_kg_m3),
        "*PLASTIC",
        f"{_num(sim.yield_stress_MPa * 1e6)}, 0.",
        "*SHELL SECTION, ELSET=SHEET, MATERIAL=SHEET_STEEL",
        _num(t),
        *_supports(sim, model),
        "*STEP, NLGEOM",
        "*STATIC",
        "*DLOAD",
        f"SHEET, GRAV, {_num(GRAVITY)}, 0., 0., -1.",
        "*NODE FILE",
        "U, RF",
        "*EL FILE",
        "S",
        "*NODE PRINT, NSET=FEET",
        "RF",
        "*NODE PRINT, NSET=EVERY",
        "U",
        "*END STEP",
    ]
    return "\n".join(out) + "\n"


def write_structural_inp(sim: Any, path: str | Path) -> Path:
    """Write NAME.inp (``path``) for the simulation ``sim`` (written whole or
    not at all)."""
    p = Path(path)
    text = inp_text(sim, p.stem)
    with atomic_output(p) as tmp:
        Path(tmp).write_text(text, encoding="ascii")
    return p
