"""The simulation's GLB read back with trimesh: metres, y up, standing on y = 0,
one vertex per node, coloured by deviation (one coarse simulation per module)."""

from __future__ import annotations

import json
import struct
from dataclasses import replace

import numpy as np
import pytest
import trimesh

from onefold_cad.design import fold_design
from onefold_cad.errors import ExportError, InvalidParameterError
from onefold_cad.export.colour_scale import (
    DEVIATION_STOPS,
    deviation_range,
    ramp,
    srgb_to_linear,
    to_uint8,
)
from onefold_cad.export.simulation_glb import write_simulation_glb
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import load_template
from tests.export.simulations import stalled_copy

FLOAT32 = float(np.finfo(np.float32).eps)


@pytest.fixture(scope="module")
def sim():
    design = load_template("patkau-one-fold")
    return simulate(design, fold_design(design), level="coarse", convergence=False)


@pytest.fixture(scope="module")
def standing(sim, tmp_path_factory):
    return write_simulation_glb(sim, tmp_path_factory.mktemp("glb") / "p-standing.glb")


def _mesh(path) -> trimesh.Trimesh:
    """The file's mesh with its node transform applied (metres, y up)."""
    return trimesh.load(path, force="mesh", process=False)


def _colours(path) -> np.ndarray:
    """``(n, 4)`` the file's vertex colours (bytes), as stored."""
    (geometry,) = trimesh.load(path, process=False).geometry.values()
    return geometry.visual.vertex_attributes["color"]


def _json(path) -> dict:
    raw = path.read_bytes()
    magic, version, length = struct.unpack("<4sII", raw[:12])
    assert magic == b"glTF" and version == 2 and length == len(raw)
    size, kind = struct.unpack("<I4s", raw[12:20])
    assert kind == b"JSON"
    return json.loads(raw[20 : 20 + size])


def test_every_node_is_a_vertex_in_metres_y_up(sim, standing):
    mesh = _mesh(standing)
    assert len(mesh.vertices) == sim.nodes and len(mesh.faces) == sim.triangles
    np.testing.assert_array_equal(mesh.faces, sim.faces)
    x, y, z = sim.standing_positions.T / 1000.0  # mm -> m
    size = float(np.ptp(sim.standing_positions, axis=0).max()) / 1000.0
    np.testing.assert_allclose(mesh.vertices, np.stack([x, z, -y], 1), atol=4 * FLOAT32 * size)
    # bounds: the standing form's extent, its height along y
    assert mesh.bounds[1, 1] == pytest.approx(sim.standing.height / 1000.0, rel=1e-6)
    assert np.ptp(mesh.vertices[:, 0]) == pytest.approx(sim.standing.span / 1000.0, rel=1e-6)


def test_the_ground_is_y_zero_and_the_form_stands_on_it(sim, standing):
    y = _mesh(standing).vertices[:, 1]
    size = float(np.abs(_mesh(standing).vertices).max())
    assert abs(y.min()) <= 4 * FLOAT32 * size
    # the nodes touching the ground are the standing contacts
    on_ground = np.abs(sim.standing_positions[:, 2]) <= 1e-6 * size * 1000.0
    assert np.all(np.abs(y[on_ground]) <= 4 * FLOAT32 * size)


def test_vertex_colours_are_the_deviation_scale_in_linear_light(sim, standing):
    colours = _colours(standing)
    expected = to_uint8(srgb_to_linear(ramp(sim.deviation, *deviation_range(sim.deviation))))
    np.testing.assert_array_equal(colours[:, :3], expected)
    assert np.all(colours[:, 3] == 255)
    top = to_uint8(srgb_to_linear(ramp(np.array([1.0]), 0.0, 1.0)))[0]
    np.testing.assert_array_equal(colours[int(np.argmax(sim.deviation)), :3], top)
    doc = _json(standing)
    assert doc["materials"][0]["doubleSided"] is True
    scale = doc["scenes"][0]["extras"]["onefold"]["colour_scale"]
    assert scale["quantity"] == "deviation from the design (mm)"
    assert scale["max"] == pytest.approx(sim.standing.max_deviation)
    assert scale["stops_srgb"] == list(DEVIATION_STOPS)
    assert "normals" not in doc["meshes"][0]["primitives"][0]["attributes"]


def test_the_released_form_is_written_grey_on_the_ground(sim, tmp_path):
    path = write_simulation_glb(sim, tmp_path / "r.glb", which="released")
    mesh = _mesh(path)
    assert len(mesh.vertices) == sim.nodes
    assert abs(mesh.vertices[:, 1].min()) <= 4 * FLOAT32 * float(np.abs(mesh.vertices).max())
    assert len(np.unique(_colours(path), axis=0)) == 1
    assert _json(path)["scenes"][0]["extras"]["onefold"]["form"] == "released"


def test_the_same_simulation_gives_the_same_bytes(sim, standing, tmp_path):
    assert write_simulation_glb(sim, tmp_path / "again.glb").read_bytes() == standing.read_bytes()


def test_a_missing_form_is_an_export_error_naming_why(sim, tmp_path):
    none = stalled_copy(sim)
    with pytest.raises(ExportError, match="no standing form to write: it found no standing"):
        write_simulation_glb(none, tmp_path / "x.glb")
    assert len(_mesh(write_simulation_glb(none, tmp_path / "r.glb", "released")).vertices)
    designed = replace(sim, reference="designed", released_positions=None)
    with pytest.raises(ExportError, match="no released form to write"):
        write_simulation_glb(designed, tmp_path / "y.glb", which="released")
    with pytest.raises(InvalidParameterError, match="which: must be one of standing, released"):
        write_simulation_glb(sim, tmp_path / "z.glb", which="formed")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.glb"]


def test_a_failed_write_raises_export_error_and_leaves_nothing(sim, tmp_path):
    with pytest.raises(ExportError):
        write_simulation_glb(sim, tmp_path / "missing" / "x.glb")
    assert list(tmp_path.iterdir()) == []
