"""NAME.glb read back with trimesh: binary glTF 2.0 in metres, y-up, standing
on the ground as the design's resting placement puts it (or in the fold frame),
every vertex on the folded surface, the area the sheet's."""

from __future__ import annotations

import json
import math
import struct

import numpy as np
import pytest
import trimesh

from onefold_cad import (
    Design,
    ExportError,
    FabricationError,
    FrameCurve,
    Material,
    Sheet,
    fold_design,
)
from onefold_cad.export.glb import ANGULAR_DEFLECTION, LINEAR_DEFLECTION, write_glb
from onefold_cad.export.measure import measure
from onefold_cad.export.part import build_part
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.fabrication.rules import resting_placement, solid_bend_problem

FLOAT32 = float(np.finfo(np.float32).eps)


def _glb_json(path) -> dict:
    """The JSON chunk of a binary glTF file (spec: 12-byte header, then chunks)."""
    raw = path.read_bytes()
    magic, version, length = struct.unpack("<4sII", raw[:12])
    assert magic == b"glTF" and version == 2 and length == len(raw)
    size, kind = struct.unpack("<I4s", raw[12:20])
    assert kind == b"JSON"
    return json.loads(raw[20 : 20 + size])


def _mesh(path) -> trimesh.Trimesh:
    """Every mesh of the file with its node transforms applied (metres, y-up)."""
    return trimesh.load(path, force="mesh")


def _z_up(design: Design, vertices_m: np.ndarray) -> np.ndarray:
    """glTF (metres, y-up) -> the design's unit, z-up."""
    x, y, z = vertices_m.T
    return np.stack([x, -z, y], axis=1) * (1000.0 / design.units.mm)  # turned back about x


def _to_design_frame(design: Design, folded, vertices_m: np.ndarray) -> np.ndarray:
    """glTF (metres, y-up) -> the design's unit, z-up -> the fold frame (the
    design's resting placement of its default body undone)."""
    rest = resting_placement(design, folded)
    return (_z_up(design, vertices_m) - rest.translation) @ rest.rotation  # inverse of R p + t


@pytest.fixture(scope="module")
def shell(tmp_path_factory):
    """A zero-thickness design in inches: the part is the sewn shell."""
    design = Design("shell", FrameCurve(40, 40), Sheet.quadrilateral(30, 30, 20, 20), units="in")
    folded = fold_design(design)
    path = write_glb(design, folded, tmp_path_factory.mktemp("glb") / "shell.glb")
    return design, folded, path


@pytest.fixture(scope="module")
def solid(tmp_path_factory):
    """A 2 mm sheet: the part is the solid (built once, standing, passed in)."""
    design = Design(
        "solid",
        FrameCurve(50, 45),
        Sheet.quadrilateral(100, 100, 100, 100),
        material=Material(thickness=2.0),
    )
    folded = fold_design(design)
    part = build_part(design, folded)
    path = write_glb(design, folded, tmp_path_factory.mktemp("glb") / "solid.glb", part=part)
    return design, folded, part, path


def test_file_is_binary_gltf_2_with_a_double_sided_material(shell):
    doc = _glb_json(shell[2])
    assert doc["asset"]["version"] == "2.0"
    assert doc["materials"] and all(m["doubleSided"] for m in doc["materials"])
    assert len(_mesh(shell[2]).faces) > 0


def test_every_vertex_lies_on_the_folded_surface_in_metres_y_up(shell):
    """Read back as metres with y up, undone the resting placement, every
    vertex is on the exact cone (distance along its normal, and inside the
    flat sheet), to float32 rounding of its coordinates."""
    design, folded, path = shell
    v = _mesh(path).vertices
    p = _to_design_frame(design, folded, v)
    flat, off = folded.unfold(p)
    scale = float(np.abs(v).max()) * 1000.0 / design.units.mm
    assert off.max() <= 8 * FLOAT32 * scale
    # the flat point of every vertex is on the sheet: its distance from H is
    # within that ray's reach
    psi = np.arctan2(flat[:, 1], flat[:, 0])
    reach = design.sheet.ray_lengths(psi)
    assert np.all(np.hypot(flat[:, 0], flat[:, 1]) <= reach + 8 * FLOAT32 * scale)
    # and the file spans the folded sheet: its corners are vertices
    corners = folded.map_points(design.sheet.vertices)
    gap = np.min(np.linalg.norm(corners[:, None] - p[None], axis=2), axis=1)
    assert gap.max() <= 8 * FLOAT32 * scale


def test_ground_is_y_zero_and_the_form_stands_on_it(shell):
    """Mesh vertices lie on the surface, which rests on y = 0; the lowest
    vertex is no higher than the tessellation's deflection above the lowest
    point (a chord's lower end is at most the deflection above the curve)."""
    design, _, path = shell
    y = _mesh(path).vertices[:, 1]
    metre = design.units.mm / 1000.0
    assert y.min() >= -1e-9 * design.sheet.size * metre - 8 * FLOAT32 * float(np.abs(y).max())
    assert y.min() <= LINEAR_DEFLECTION * design.sheet.size * metre


def test_mesh_area_is_the_sheets_to_the_tessellation_tolerance(shell):
    """The folded sheet keeps its flat area: the mesh's (in square metres, in
    the design's unit again) matches it within ANGULAR_DEFLECTION^2 / 6."""
    design, folded, path = shell
    area = _mesh(path).area * (1000.0 / design.units.mm) ** 2
    hole = relief_hole_diameter(design, folded)
    expected = design.sheet.area - math.pi * hole**2 / 4.0
    assert area == pytest.approx(expected, rel=ANGULAR_DEFLECTION**2 / 6.0)


def test_solid_bounding_box_is_the_parts_in_metres(solid):
    """The mesh, in mm and z up again, fills the given (standing) part's
    bounding box: inside it, and reaching each side within the deflection."""
    design, folded, part, path = solid
    p = _z_up(design, _mesh(path).vertices)
    box = part.bounding_box(optimal=True)
    lo = np.array([box.min.X, box.min.Y, box.min.Z])
    hi = np.array([box.max.X, box.max.Y, box.max.Z])
    slack = 8 * FLOAT32 * float(np.abs(p).max()) + 1e-6 * design.sheet.size
    deflection = LINEAR_DEFLECTION * design.sheet.size
    assert np.all(p.min(axis=0) >= lo - slack) and np.all(p.max(axis=0) <= hi + slack)
    assert np.all(p.min(axis=0) <= lo + deflection) and np.all(p.max(axis=0) >= hi - deflection)


def test_solid_mesh_area_is_the_parts(solid):
    """Within ANGULAR_DEFLECTION^2 / 2 of the part's area: the solid's faces that taper
    to a point at the crease get thin triangles, tilted by up to the angular deflection
    a against the surface under them (larger by up to 1 / cos(a) - 1)."""
    design, _, part, path = solid
    area = _mesh(path).area * 1e6
    assert area == pytest.approx(measure(part, "area"), rel=ANGULAR_DEFLECTION**2 / 2.0)
    # and it is the solid's: both faces of the sheet and its edges
    assert area > 1.9 * design.sheet.area


def test_given_part_is_the_one_written(tmp_path, solid):
    design, folded, _, _ = solid
    shell = build_part(design, folded, body="shell")
    path = write_glb(design, folded, tmp_path / "s.glb", part=shell)
    area = _mesh(path).area * 1e6
    assert area == pytest.approx(measure(shell, "area"), rel=ANGULAR_DEFLECTION**2 / 6.0)


def test_same_design_gives_the_same_bytes(tmp_path, shell):
    design, folded, path = shell
    again = write_glb(design, folded, tmp_path / "again.glb")
    assert again.read_bytes() == path.read_bytes()


def test_write_failure_raises_export_error_and_leaves_nothing(tmp_path, shell):
    design, folded, _ = shell
    with pytest.raises(ExportError):
        write_glb(design, folded, tmp_path / "missing" / "x.glb")
    assert list(tmp_path.iterdir()) == []


def test_the_fold_frame_part_is_written_in_the_fold_frame(tmp_path, shell):
    """placement='frame': no placement to undo, every vertex lies on the cone in the
    fold frame (the apex above H), and the file differs from the standing one."""
    design, folded, standing = shell
    path = write_glb(design, folded, tmp_path / "frame.glb", placement="frame")
    v = _mesh(path).vertices
    _, off = folded.unfold(_z_up(design, v))
    scale = float(np.abs(v).max()) * 1000.0 / design.units.mm
    assert off.max() <= 8 * FLOAT32 * scale
    assert path.read_bytes() != standing.read_bytes()


def test_a_solid_past_the_bend_limits_is_refused_as_the_step_refuses_it(tmp_path):
    """The GLB holds the STEP's part: past the bend model's limits the solid is refused
    with the same error (nothing written) unless compensation is 'none'."""
    design = Design("corner", FrameCurve(60, 70), Sheet.rectangle(40, 100, 0.5),
                    material=Material(thickness=3.57, bend_radius=6.0))  # fmt: skip
    folded = fold_design(design)
    expected = solid_bend_problem(design, folded)
    assert expected is not None
    with pytest.raises(FabricationError) as err:
        write_glb(design, folded, tmp_path / "corner.glb")
    assert str(err.value) == str(expected)
    assert list(tmp_path.iterdir()) == []
    path = write_glb(design, folded, tmp_path / "corner.glb", compensation="none")
    assert len(_mesh(path).faces) > 0
