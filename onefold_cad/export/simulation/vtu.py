"""A simulation's results for ParaView and other VTK readers: NAME.vtu.

:func:`write_simulation_vtu` writes the simulation's triangle mesh
(:class:`onefold_cad.mechanics.results.Simulation`) with meshio as one
unstructured grid (VTK XML, binary, compressed), in metres, on the designed
form as it stands (the resting frame: z up, the ground at z = 0). Its fields
(ParaView's *Warp By Vector* on a displacement shows that stage):

- point data ``displacement_standing`` (m): the standing sheet from the
  designed form, when there is a standing equilibrium;
  ``displacement_released`` (m): the sheet after springback, as the standing
  stage set it down, from the designed form (reference ``flat``);
  ``deviation_standing`` (m): each node's distance from the designed form as
  it stands; ``flat_position`` (m): the node on the flat sheet (fold frame);
- cell data ``von_mises_MPa``: the larger von Mises stress of the sheet's two
  surfaces in each triangle, standing (the stress picture's).

Only the fields the simulation has are written. The same simulation gives
the same bytes.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import meshio
import numpy as np

from onefold_cad.choices import Units
from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output

__all__ = ["simulation_mesh", "write_simulation_vtu"]


def simulation_mesh(sim: Any) -> meshio.Mesh:
    """The simulation as a meshio mesh (see the module docstring)."""
    if sim.designed_positions is None or sim.faces is None:
        raise ExportError("a simulation without its mesh cannot be written as NAME.vtu")
    scale = Units.parse(sim.unit).mm / 1000.0
    designed = np.asarray(sim.designed_positions, dtype=float) * scale
    points: dict[str, np.ndarray] = {}
    if sim.standing_positions is not None:
        points["displacement_standing"] = np.asarray(sim.standing_positions) * scale - designed
    if sim.released_positions is not None:
        points["displacement_released"] = np.asarray(sim.released_positions) * scale - designed
    if sim.deviation is not None:
        points["deviation_standing"] = np.asarray(sim.deviation, dtype=float) * scale
    flat = np.asarray(sim.flat, dtype=float) * scale
    points["flat_position"] = np.column_stack([flat, np.zeros(len(flat))])
    cells: dict[str, list[np.ndarray]] = {}
    if sim.face_stress_MPa is not None:
        cells["von_mises_MPa"] = [np.asarray(sim.face_stress_MPa, dtype=float)]
    return meshio.Mesh(
        designed,
        [("triangle", np.asarray(sim.faces, dtype=np.int64))],
        point_data=points,
        cell_data=cells,
    )


def write_simulation_vtu(sim: Any, path: str | Path) -> Path:
    """Write NAME.vtu (``path``) for the simulation ``sim``, whole or not at all."""
    p = Path(path)
    mesh = simulation_mesh(sim)
    with atomic_output(p) as tmp:
        meshio.write(tmp, mesh, file_format="vtu", binary=True, compression="zlib")
    return p
