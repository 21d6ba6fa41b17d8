"""The folded form's side Breps as another module (a Hops server) gets them:
one valid one-face Brep per side with its render mesh and user strings,
standing as it rests or in the fold frame, the refusals of the writers."""

from __future__ import annotations

import numpy as np
import pytest
import rhino3dm

from onefold_cad import (
    Design,
    FabricationError,
    FrameCurve,
    InvalidParameterError,
    Material,
    Sheet,
    fold_design,
)
from onefold_cad.export.rhino_sides import side_breps
from onefold_cad.export.rhino_strings import KEY_NUMBERS
from onefold_cad.fabrication.rules import resting_placement


@pytest.fixture(scope="module")
def case():
    sheet = Sheet.polygon([[90, 0], [40, 70], [-80, 50], [-100, 0], [-30, -60], [70, -40]])
    design = Design("sides", FrameCurve(40, 30), sheet, material=Material(thickness=1.0))
    return design, fold_design(design)


def _points(brep, n: int = 7) -> np.ndarray:
    s = brep.Surfaces[0]
    u, v = s.Domain(0), s.Domain(1)
    return np.array(
        [
            [(p := s.PointAt(a, b)).X, p.Y, p.Z]
            for a in np.linspace(u.T0, u.T1, n)
            for b in np.linspace(v.T0, v.T1, 3)
        ]
    )


def test_one_valid_brep_per_side_with_its_mesh_and_strings(case):
    design, folded = case
    got = side_breps(design, folded, placement="frame")
    assert [name for name, _ in got] == ["upper", "lower"]
    for name, brep in got:
        assert isinstance(brep, rhino3dm.Brep) and len(brep.Faces) == 1
        assert brep.IsValid and brep.IsValidWithLog[0]
        mesh = brep.Faces[0].GetMesh(rhino3dm.MeshType.Render)
        assert mesh is not None and len(mesh.Faces) > 0
        strings = dict(brep.GetUserStrings())
        assert strings["side"] == name and strings["rhino.placement"] == "frame"
        assert {f"report.{k}" for k in KEY_NUMBERS} <= strings.keys()
        assert float(strings["frame.alpha"]) == 40.0
        # in the fold frame the upper side is the +y one: its flat points have y >= 0
        flat, off = folded.unfold(_points(brep))
        assert off.max() <= 1e-6 * design.sheet.size
        sign = 1.0 if name == "upper" else -1.0
        assert (sign * flat[:, 1]).min() >= -1e-9 * design.sheet.size


def test_resting_breps_are_the_frames_moved_by_the_resting_placement(case):
    design, folded = case
    frame = dict(side_breps(design, folded, placement="frame"))
    rest = dict(side_breps(design, folded))  # the default: as it rests
    placement = resting_placement(design, folded)
    for name, brep in rest.items():
        want = placement.apply(_points(frame[name]))
        assert np.abs(_points(brep) - want).max() <= 1e-9 * design.sheet.size
        assert brep.GetUserString("rhino.placement") == "rest"


def test_a_bad_placement_and_a_hole_too_big_are_refused(case):
    design, folded = case
    with pytest.raises(InvalidParameterError, match="placement: must be one of rest, frame"):
        side_breps(design, folded, placement="upside-down")
    big = design.with_changes(material=design.material.with_changes(relief_hole=150.0))
    with pytest.raises(FabricationError):
        side_breps(big, fold_design(big))
