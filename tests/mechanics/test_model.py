"""The sheet model of a design: the crease's set angle, with its overbend.

Expected angles come from the fold's own crease halves (``fold_design``), not
from the model; the simulated crease is measured on the mesh, as the angle
between the normals of the two triangles at each crease edge."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from onefold_cad.design import Design, fold_design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics.model import sheet_model
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import load_template


def _overbent(design: Design, degrees: float | None) -> Design:
    return design.with_changes(material=replace(design.material, crease_overbend=degrees))


@pytest.mark.parametrize("overbend", [None, 0.0, 7.5, -12.0])
def test_each_crease_edge_is_set_to_its_half_s_fold_angle_plus_the_overbend(overbend) -> None:
    design = _overbent(load_template("patkau-one-fold"), overbend)
    folded = fold_design(design)
    model = sheet_model(design, folded, level="coarse")
    mesh = model.mesh
    x = mesh.nodes[mesh.edges[mesh.crease_edges]].mean(axis=1)[:, 0]
    got = model.shell.crease_angle
    for half, where in zip(folded.crease, (x > 0.0, x <= 0.0), strict=True):
        sign = 1.0 if half.bend == "UP" else -1.0
        want = sign * math.radians(half.fold_angle_deg + (overbend or 0.0))
        assert where.any()
        np.testing.assert_allclose(got[where], want, rtol=0, atol=1e-12)


@pytest.mark.parametrize("overbend", [40.0, -45.0])
def test_a_set_angle_outside_0_to_180_degrees_is_refused_naming_the_overbend(overbend) -> None:
    base = load_template("patkau-one-fold")
    # alpha = beta = 60 deg folds each crease half to 150.3 deg; 10 deg to 24.6
    frame = base.frame.with_changes(alpha=60.0, beta=60.0) if overbend > 0 else (
        base.frame.with_changes(alpha=10.0, beta=10.0))  # fmt: skip
    design = _overbent(base.with_changes(frame=frame), overbend)
    with pytest.raises(InvalidParameterError, match="crease_overbend") as err:
        sheet_model(design, fold_design(design), level="coarse")
    assert "above 0 and below 180 deg" in str(err.value)


def test_an_overbend_out_of_its_range_is_refused_by_the_material() -> None:
    base = load_template("patkau-one-fold")
    with pytest.raises(InvalidParameterError, match=r"crease_overbend: must be in \[-45, 45\]"):
        _overbent(base, 46.0)


def _crease_dihedrals(flat: np.ndarray, faces: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The angle (deg) between the normals of the two triangles at each edge
    on the fold line (y = 0 on the flat sheet)."""
    on = np.abs(flat[:, 1]) <= 1e-9 * np.ptp(flat)
    at: dict[tuple[int, int], list[int]] = {}
    for f, tri in enumerate(faces):
        for a, b in zip(tri, np.roll(tri, -1), strict=True):
            if on[a] and on[b]:
                at.setdefault((min(a, b), max(a, b)), []).append(f)
    p = x[faces]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n /= np.linalg.norm(n, axis=1)[:, None]
    pairs = np.array([fs for fs in at.values() if len(fs) == 2])
    cos = np.einsum("ij,ij->i", n[pairs[:, 0]], n[pairs[:, 1]])
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


def test_a_held_crease_springs_back_to_about_its_overbent_set_angle() -> None:
    # the cones are formed as designed and the crease set 6 deg further: once
    # released, the held crease closes by most of it (the cones beside it
    # bend to meet it), where without an overbend it keeps the fold's angle
    base = load_template("patkau-one-fold")
    change = {}
    for overbend in (0.0, 6.0):
        design = _overbent(base, overbend)
        sim = simulate(design, fold_design(design), level="coarse", convergence=False,
                       reserve=False)  # fmt: skip
        assert sim.released_positions is not None and sim.designed_positions is not None
        before = _crease_dihedrals(sim.flat, sim.faces, sim.designed_positions)
        after = _crease_dihedrals(sim.flat, sim.faces, sim.released_positions)
        change[overbend] = float(np.mean(after - before))
    assert abs(change[0.0]) < 1.0
    assert 0.7 * 6.0 < change[6.0] - change[0.0] <= 6.0
