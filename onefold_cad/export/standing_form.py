"""A simulated standing form as files: GLB (coloured by its deviation) and
STEP (its mid-surface as a shell of planar triangles).

The form is given as arrays (``points (n, 3)`` in the design's unit, resting
frame, z up; ``faces (m, 3)``), so any command's form can be written: the
compensated steel of ``onefold compensate`` among them. The GLB is written
by :func:`~onefold_cad.export.simulation.glb.write_simulation_glb` (its
conventions: metres, y up, ``COLOR_0`` by deviation); the STEP holds one
shell of the mesh's triangles in the design's unit (build123d), read back
before it is kept.
"""

from __future__ import annotations

import os
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.geometry.numeric import Array

__all__ = ["write_form_glb", "write_form_step"]


def write_form_glb(
    points: Array, faces: Array, unit: str, deviation: Array | None, path: str | os.PathLike[str]
) -> Path:
    """Write the form as binary glTF, each vertex coloured by ``deviation``
    ``(n,)`` (design unit; None: steel grey)."""
    from onefold_cad.export.simulation.glb import write_simulation_glb

    form = SimpleNamespace(
        faces=np.asarray(faces), standing_positions=np.asarray(points, dtype=float),
        released_positions=None, deviation=deviation, unit=unit, supports="anchored",
        reference="flat", standing=SimpleNamespace(reason=""),
    )  # fmt: skip
    return write_simulation_glb(form, path, "standing")  # type: ignore[arg-type]


def write_form_step(points: Array, faces: Array, unit: str, path: str | os.PathLike[str]) -> Path:
    """Write the form's mid-surface as STEP: one shell of planar triangles in
    the design's ``unit``.

    Raises:
        ExportError: the kernel refused the shell or the file does not read back
            with every triangle.
    """
    import build123d as bd

    from onefold_cad.choices import Units
    from onefold_cad.export.brep.step import STEP_TIMESTAMP

    p = np.asarray(points, dtype=float)
    tris = [bd.Face(bd.Wire.make_polygon([tuple(p[i]) for i in f], close=True)) for f in faces]
    shell = bd.Shell(tris)
    units = {Units.MM: bd.Unit.MM, Units.IN: bd.Unit.IN, Units.FT: bd.Unit.FT}[Units(unit)]
    with atomic_output(path) as tmp:
        if not bd.export_step(shell, tmp, unit=units, timestamp=STEP_TIMESTAMP):
            raise ExportError(f"{Path(path).name}: the STEP writer refused the standing form")
        back = bd.import_step(tmp)
        if len(back.faces()) != len(tris):
            raise ExportError(
                f"{Path(path).name}: read back {len(back.faces())} of {len(tris)} triangles"
            )
    return Path(path)
