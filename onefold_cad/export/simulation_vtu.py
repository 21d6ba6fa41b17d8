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
  surfaces in each triangle, standing (the stress picture's);
- with the J2 law, per stage ``S`` (``formed``, ``released``, ``standing``):
  ``S_von_mises_bottom_MPa`` and ``S_von_mises_top_MPa`` (the surfaces
  ``z = -t/2`` and ``+t/2`` along the shell's director), ``S_plastic_strain_bottom``
  and ``S_plastic_strain_top`` (equivalent plastic strain),
  ``S_membrane_force_N_per_m`` ``(N11, N22, N12)`` and
  ``S_bending_moment_N_per_m`` ``(M11, M22, M12)`` (N m / m), the resultants
  through the thickness on each triangle's own frame: axis 1 along its first
  edge (cell vector ``resultant_axis_1``, the designed form's), axis 2 in its
  plane. The formed stage is the designed form itself (no displacement).

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
    faces = np.asarray(sim.faces, dtype=np.int64)
    for stage, f in (getattr(sim, "fields", None) or {}).items():
        cells[f"{stage}_von_mises_bottom_MPa"] = [np.asarray(f.stress[:, 0]) / 1e6]
        cells[f"{stage}_von_mises_top_MPa"] = [np.asarray(f.stress[:, 1]) / 1e6]
        cells[f"{stage}_plastic_strain_bottom"] = [np.asarray(f.plastic_strain[:, 0])]
        cells[f"{stage}_plastic_strain_top"] = [np.asarray(f.plastic_strain[:, 1])]
        cells[f"{stage}_membrane_force_N_per_m"] = [np.asarray(f.force, dtype=float)]
        cells[f"{stage}_bending_moment_N_per_m"] = [np.asarray(f.moment, dtype=float)]
    if getattr(sim, "fields", None):
        edge = designed[faces[:, 1]] - designed[faces[:, 0]]
        cells["resultant_axis_1"] = [edge / np.linalg.norm(edge, axis=1)[:, None]]
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
