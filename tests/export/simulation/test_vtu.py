"""NAME.vtu, a simulation's stages for ParaView: read back with meshio (the
mesh, the displacement of each stage, the stress) against the simulation's
own arrays, in metres; the same bytes for the same simulation."""

from __future__ import annotations

import meshio
import numpy as np
import pytest

from onefold_cad.design import build_design
from onefold_cad.export.simulation.vtu import write_simulation_vtu
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import load_template


@pytest.fixture(scope="module")
def sim():
    design = load_template("patkau-one-fold")
    return simulate(design, build_design(design), level="coarse", convergence=False)


def test_read_back_it_is_the_simulation_in_metres(sim, tmp_path):
    mesh = meshio.read(write_simulation_vtu(sim, tmp_path / "p.vtu"))
    designed = np.asarray(sim.designed_positions) / 1000  # mm -> m
    assert np.allclose(mesh.points, designed, rtol=0, atol=1e-12)
    (block,) = mesh.cells
    assert block.type == "triangle" and np.array_equal(block.data, sim.faces)
    standing = mesh.points + mesh.point_data["displacement_standing"]
    assert np.allclose(standing, np.asarray(sim.standing_positions) / 1000, atol=1e-12)
    released = mesh.points + mesh.point_data["displacement_released"]
    assert np.allclose(released, np.asarray(sim.released_positions) / 1000, atol=1e-12)
    assert np.allclose(mesh.point_data["deviation_standing"], np.asarray(sim.deviation) / 1000)
    flat = mesh.point_data["flat_position"]
    assert np.allclose(flat[:, :2], np.asarray(sim.flat) / 1000) and not flat[:, 2].any()
    (stress,) = mesh.cell_data["von_mises_MPa"]
    assert np.array_equal(stress, sim.face_stress_MPa)
    # the largest movement of the standing stage is the report's
    moved = np.linalg.norm(mesh.point_data["displacement_standing"], axis=1)
    assert 1000 * moved.max() == pytest.approx(
        np.linalg.norm(np.asarray(sim.standing_positions) - designed * 1000, axis=1).max()
    )


def test_the_same_simulation_gives_the_same_bytes(sim, tmp_path):
    a = write_simulation_vtu(sim, tmp_path / "a.vtu").read_bytes()
    b = write_simulation_vtu(sim, tmp_path / "b.vtu").read_bytes()
    assert a == b and a.startswith(b"<?xml")


PARAVIEW_READ = """
import json, sys
from paraview.simple import XMLUnstructuredGridReader, servermanager
reader = XMLUnstructuredGridReader(FileName=[sys.argv[1]])
reader.UpdatePipeline()
grid = servermanager.Fetch(reader)
pd, cd = grid.GetPointData(), grid.GetCellData()
print(json.dumps({
    "points": grid.GetNumberOfPoints(),
    "cells": grid.GetNumberOfCells(),
    "point_arrays": sorted(pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())),
    "stress_range": list(cd.GetArray("von_mises_MPa").GetRange()),
    "bounds": list(grid.GetBounds()),
}))
"""


def test_paraview_reads_it(sim, tmp_path):
    """ParaView's own reader (Debian's python3-paraview: make test installs it)."""
    import json
    import shutil
    import subprocess

    pvpython = shutil.which("pvpython")
    assert pvpython is not None, "ParaView is not installed: make test installs python3-paraview"
    path = write_simulation_vtu(sim, tmp_path / "p.vtu")
    script = tmp_path / "read.py"
    script.write_text(PARAVIEW_READ)
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    proc = subprocess.run([pvpython, str(script), str(path)], capture_output=True, text=True,
                          timeout=300, env=env)  # fmt: skip
    assert proc.returncode == 0, proc.stderr[-2000:]
    got = json.loads(proc.stdout.strip().splitlines()[-1])
    assert got["points"] == sim.nodes and got["cells"] == sim.triangles
    assert got["point_arrays"] == sorted(
        ["displacement_standing", "displacement_released", "deviation_standing", "flat_position"]
    )
    stress = np.asarray(sim.face_stress_MPa)
    assert got["stress_range"] == pytest.approx([stress.min(), stress.max()], rel=1e-12)
    designed = np.asarray(sim.designed_positions) / 1000
    lo, hi = designed.min(axis=0), designed.max(axis=0)
    expected = [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]
    assert got["bounds"] == pytest.approx(expected, abs=1e-9)
