"""NAME.vtu, a simulation's stages for ParaView: read back with meshio (the
mesh, the displacement of each stage, the stress) against the simulation's
own arrays, in metres; the same bytes for the same simulation."""

from __future__ import annotations

import meshio
import numpy as np
import pytest

from onefold_cad.design import fold_design
from onefold_cad.export.simulation_vtu import write_simulation_vtu
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import load_template


@pytest.fixture(scope="module")
def sim():
    design = load_template("patkau-one-fold")
    return simulate(design, fold_design(design), level="coarse", convergence=False, law="j2")


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


def _vm(v):
    """The von Mises norm of plane (11, 22, 12) resultants."""
    return np.sqrt(v[:, 0] ** 2 - v[:, 0] * v[:, 1] + v[:, 1] ** 2 + 3 * v[:, 2] ** 2)


def test_each_stage_has_its_surfaces_and_resultants_within_the_yield_bounds(sim, tmp_path):
    """The J2 fields of every stage: the surface stresses never above the flow
    stress (patkau's 304 hardens isotropically: sigma_y + H alpha), plastic
    strains that only grow from stage to stage, and resultants inside the
    bounds von Mises puts on any section whose points are at most at the
    largest flow stress (independent of the law's integration):
    |N|_vm <= sigma t and |M|_vm <= sigma t^2 / 4."""
    mesh = meshio.read(write_simulation_vtu(sim, tmp_path / "p.vtu"))
    cd = {k: v[0] for k, v in mesh.cell_data.items()}
    assert sim.kinematic_hardening == 0
    h = sim.hardening_modulus_MPa
    peeq_max = max(
        cd[f"{s}_plastic_strain_{side}"].max()
        for s in ("formed", "released", "standing")
        for side in ("bottom", "top")
    )
    sy, t = sim.yield_stress_MPa + h * peeq_max, sim.thickness / 1000  # MPa, m
    last = np.zeros((sim.triangles, 2))
    for stage in ("formed", "released", "standing"):
        stress = np.column_stack(
            [cd[f"{stage}_von_mises_bottom_MPa"], cd[f"{stage}_von_mises_top_MPa"]]
        )
        peeq = np.column_stack(
            [cd[f"{stage}_plastic_strain_bottom"], cd[f"{stage}_plastic_strain_top"]]
        )
        assert np.all(stress <= (sim.yield_stress_MPa + h * peeq) * (1 + 1e-9))
        assert np.all(peeq >= last - 1e-15)
        last = peeq
        assert _vm(cd[f"{stage}_membrane_force_N_per_m"]).max() <= sy * 1e6 * t * (1 + 1e-9)
        assert _vm(cd[f"{stage}_bending_moment_N_per_m"]).max() <= sy * 1e6 * t**2 / 4 * (1 + 1e-9)
    # the formed sheet's largest surface plastic strain is the report's
    formed = np.maximum(cd["formed_plastic_strain_bottom"], cd["formed_plastic_strain_top"])
    assert formed.max() == pytest.approx(sim.formed.max_plastic_strain, rel=1e-12)
    # and the cells' own frame: unit vectors along each triangle's first edge
    axis = cd["resultant_axis_1"]
    assert np.allclose(np.linalg.norm(axis, axis=1), 1.0)


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
    "cell_arrays": sorted(cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())),
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
    for stage in ("formed", "released", "standing"):
        for field in ("von_mises_top_MPa", "plastic_strain_bottom", "bending_moment_N_per_m"):
            assert f"{stage}_{field}" in got["cell_arrays"]
    stress = np.asarray(sim.face_stress_MPa)
    assert got["stress_range"] == pytest.approx([stress.min(), stress.max()], rel=1e-12)
    designed = np.asarray(sim.designed_positions) / 1000
    lo, hi = designed.min(axis=0), designed.max(axis=0)
    expected = [lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]]
    assert got["bounds"] == pytest.approx(expected, abs=1e-9)
