"""A simulation's form as binary glTF 2.0: the standing (or released) sheet.

:func:`write_simulation_glb` writes the simulation's triangle mesh
(:class:`onefold_cad.mechanics.results.Simulation`: ``faces`` on
``standing_positions`` or ``released_positions``) with trimesh, in the
conventions of NAME.glb (:mod:`onefold_cad.export.glb`): metres, y up (the
design's z-up frame turned -90 deg about x: glTF ``(x, y, z)`` is the
design's ``(x, z, -y)``), the ground at y = 0 and the form standing on it.
The turn is applied to the vertices (no node transform), so a reader sees
the coordinates as stored.

- 'standing': each vertex coloured by its node's deviation from the designed
  form (``COLOR_0``, linear light as glTF requires, from the sRGB scale of
  :mod:`onefold_cad.export.simulation.colour_scale`: the deviation picture's colours);
- 'released': the form after springback, placed as the standing stage sets
  it down, in NAME.glb's steel grey (no per-node deviation is known).

One double-sided material (a zero-thickness sheet shows from both sides). The
scene's ``extras`` say what was written: the form, the unit the deviation
scale is in and its ends (0 and the largest deviation, design unit), the
colour stops. No normals are written (glTF viewers then shade each triangle
flat: the crease stays sharp). The same simulation gives the same bytes.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import trimesh
from trimesh.visual.material import PBRMaterial
from trimesh.visual.texture import TextureVisuals

from onefold_cad.choices import Units
from onefold_cad.errors import ExportError, InvalidParameterError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.export.simulation.colour_scale import (
    DEVIATION_STOPS,
    STEEL_GREY,
    deviation_label,
    deviation_range,
    ramp,
    srgb_to_linear,
    to_uint8,
)
from onefold_cad.geometry.numeric import Array
from onefold_cad.mechanics.results import Simulation

__all__ = ["FORMS", "gltf_vertices", "write_simulation_glb"]

#: The forms :func:`write_simulation_glb` can write.
FORMS = ("standing", "released")


def gltf_vertices(points: Array, unit: str) -> Array:
    """``(n, 3)`` points in the design's ``unit`` (z up) as glTF vertices:
    metres, y up (``(x, y, z)`` -> ``(x, z, -y)``)."""
    p = np.asarray(points, dtype=float) * (Units(unit).mm / 1000.0)
    return np.stack([p[:, 0], p[:, 2], -p[:, 1]], axis=1)


def _form(sim: Simulation, which: str) -> Array:
    if which not in FORMS:
        raise InvalidParameterError("which", f"must be one of {', '.join(FORMS)}, got {which!r}")
    if sim.faces is None:
        raise ExportError("the simulation carries no mesh to write")
    points = sim.standing_positions if which == "standing" else sim.released_positions
    if points is None:
        why = (
            f"it found no standing equilibrium ({sim.standing.reason})"
            if which == "standing"
            else "the simulation took the designed form as its reference (reference 'designed')"
        )
        raise ExportError(f"no {which} form to write: {why}")
    return np.asarray(points, dtype=float)


def _colours(sim: Simulation, which: str, n: int) -> tuple[Array, dict[str, object]]:
    """``(n, 4)`` RGBA bytes (linear light) and the scale's description."""
    if which == "standing" and sim.deviation is not None:
        dev = np.asarray(sim.deviation, dtype=float)
        lo, hi = deviation_range(dev)
        rgb = srgb_to_linear(ramp(dev, lo, hi))
        scale: dict[str, object] = {
            "quantity": deviation_label(sim.unit),
            "unit": sim.unit,
            "min": lo,
            "max": hi,
            "stops_srgb": list(DEVIATION_STOPS),
        }
    else:
        rgb = np.tile(srgb_to_linear(np.array(STEEL_GREY)), (n, 1))
        scale = {"quantity": None}
    return np.column_stack([to_uint8(rgb), np.full(n, 255, np.uint8)]), scale


def write_simulation_glb(
    sim: Simulation, path: str | os.PathLike[str], which: str = "standing"
) -> Path:
    """Write the simulation's standing (or released) form as binary glTF.

    Args:
        sim: the simulation (:func:`~onefold_cad.mechanics.simulate.simulate`).
        path: the ``.glb`` file to write (atomically).
        which: 'standing' (coloured by deviation from the design) or
            'released' (after springback, uniform steel grey).

    Returns:
        The path written.

    Raises:
        InvalidParameterError: ``which`` is not one of :data:`FORMS`.
        ExportError: the simulation has no such form (no standing
            equilibrium; reference 'designed' has no released form) or the
            file could not be written.
    """
    points = _form(sim, which)
    faces = np.asarray(sim.faces, dtype=np.int64)
    mesh = trimesh.Trimesh(gltf_vertices(points, sim.unit), faces, process=False)
    rgba, scale = _colours(sim, which, len(points))
    material = PBRMaterial(
        name=f"{which} form",
        baseColorFactor=[255, 255, 255, 255],
        metallicFactor=0.0,
        roughnessFactor=0.6,
        doubleSided=True,
    )
    mesh.visual = TextureVisuals(material=material)
    mesh.visual.vertex_attributes["color"] = rgba
    scene = trimesh.Scene()
    scene.add_geometry(mesh, node_name=which, geom_name=which)
    scene.metadata["onefold"] = {
        "form": which,
        "units": "m",
        "design_unit": sim.unit,
        "supports": sim.supports,
        "reference": sim.reference,
        "colour_scale": scale,
    }
    data = trimesh.exchange.gltf.export_glb(scene, include_normals=False)
    with atomic_output(path) as tmp:
        tmp.write_bytes(data)
    return Path(path)
