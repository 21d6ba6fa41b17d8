"""The CalculiX release benchmark's pure-numpy parts (benchmarks/ccx_release.py):
the formed stress at an integration point against the closed forms of a
sheet bent with no strain across the bend, the frame rotation, the initial
strain that gives a stress, ccx's wedge rule and the solid columns. No ccx
needed; expected values in closed form."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import ccx_release as cr  # noqa: E402

from onefold_cad.mechanics.j2.law import J2Law, von_mises  # noqa: E402

E, NU, SY, T = 200e9, 0.3, 215e6, 0.004
LAW = J2Law(E, NU, SY)
EP = E / (1.0 - NU**2)


def _stress_at(strain: float, steps: int = 4) -> np.ndarray:
    """The formed stress of a face bent about its second axis (curvature
    ``(k, 0, 0)``) at the height where the strain along the first axis is
    ``strain`` (h = 1 mm)."""
    h = 1e-3
    kappa = np.array([[-strain / h, 0.0, 0.0]])  # the strain at h is -h kappa
    return cr.formed_stress(LAW, kappa, np.array([h]), steps)[0][0, 0]


def test_elastic_point_is_the_plane_stress_of_a_bend_with_no_cross_strain():
    e = 0.5 * SY / EP  # well below first yield
    s = _stress_at(e)
    assert s[0] == pytest.approx(EP * e, rel=1e-12)
    assert s[1] == pytest.approx(NU * EP * e, rel=1e-12)
    assert s[2] == pytest.approx(0.0, abs=1e-6)


def test_first_yield_where_the_closed_form_puts_it():
    """No strain across the bend: sigma_2 = nu sigma_1 until von Mises
    reaches sigma_y, at sigma_1 = sigma_y / sqrt(1 - nu + nu^2)."""
    e_y = SY / math.sqrt(1.0 - NU + NU**2) / EP
    below = cr.formed_stress(LAW, np.array([[-e_y / 1e-3 * (1 - 1e-6), 0, 0]]), np.array([1e-3]), 4)
    above = cr.formed_stress(LAW, np.array([[-e_y / 1e-3 * (1 + 1e-3), 0, 0]]), np.array([1e-3]), 4)
    assert not below[1][0, 0] and above[1][0, 0]


def test_deep_point_is_on_the_yield_surface_at_the_fully_plastic_ratio():
    """Far past yield the plastic flow takes no strain across the bend:
    sigma_2 = sigma_1 / 2, von Mises = sigma_y, so sigma_1 = 2 sigma_y / sqrt 3."""
    s = _stress_at(200 * SY / EP)
    assert von_mises(s) == pytest.approx(SY, rel=1e-9)
    assert s[1] / s[0] == pytest.approx(0.5, abs=2e-3)
    assert s[0] == pytest.approx(2 * SY / math.sqrt(3.0), rel=2e-3)


def test_the_stress_changes_sign_with_the_height():
    kappa = np.array([[3.0, -1.0, 0.5]])
    s = cr.formed_stress(LAW, kappa, np.array([-1e-4, 1e-4]), 4)[0][0]
    np.testing.assert_allclose(s[0], -s[1], rtol=1e-12)


def _rotation(rng: np.random.Generator) -> np.ndarray:
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    return q * np.sign(np.linalg.det(q))


def test_plane_stress_turned_into_the_global_frame_keeps_its_invariants():
    rng = np.random.default_rng(5)
    frames = np.stack([_rotation(rng) for _ in range(4)])  # rows e1, e2, e3
    plane = rng.normal(size=(4, 2, 3)) * 1e8
    g = cr.to_global(plane, frames)
    tensor = np.zeros((4, 2, 3, 3))
    for (i, j), c in {(0, 0): 0, (1, 1): 1, (2, 2): 2, (0, 1): 3, (0, 2): 4, (1, 2): 5}.items():
        tensor[..., i, j] = tensor[..., j, i] = g[..., c]
    # the normal e3 carries no traction; trace and von Mises as in the plane
    np.testing.assert_allclose(np.einsum("mkij,mj->mki", tensor, frames[:, 2]), 0.0, atol=1e-6)
    np.testing.assert_allclose(np.trace(tensor, axis1=2, axis2=3), plane[..., 0] + plane[..., 1])
    dev = tensor - np.trace(tensor, axis1=2, axis2=3)[..., None, None] * np.eye(3) / 3
    vm3 = np.sqrt(1.5 * np.einsum("mkij,mkij->mk", dev, dev))
    np.testing.assert_allclose(vm3, von_mises(plane), rtol=1e-12)
    np.testing.assert_allclose(cr.to_frame(g, frames), plane, rtol=1e-12, atol=1e-3)


def test_face_frame_is_onefolds_first_edge_frame():
    x = np.array([[0.0, 0.0, 0.0], [0.0, 2.0, 0.0], [-1.0, 1.0, 0.0]])
    f = cr.face_frames(x, np.array([[0, 1, 2]]))[0]
    np.testing.assert_allclose(f, [[0, 1, 0], [-1, 0, 0], [0, 0, 1]], atol=1e-15)


def test_initial_strain_gives_back_the_stress():
    """Hooke's law in Lame's form, tensor shears: sigma = lambda tr(e) I + 2 mu e."""
    rng = np.random.default_rng(2)
    s = rng.normal(size=(5, 6)) * 1e8
    e = -cr.initial_strain(s, E, NU)
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    back = 2 * mu * e
    back[:, :3] += lam * e[:, :3].sum(axis=1)[:, None]
    np.testing.assert_allclose(back, s, rtol=1e-12, atol=1e-3)


@pytest.mark.parametrize("layers", [1, 4])
def test_point_heights_integrate_the_bending_stiffness(layers):
    """ccx's 3 points per layer (weights 5/18, 8/18, 5/18) integrate z^2 over
    the thickness exactly: t^3 / 12."""
    h = cr.point_heights(T, layers)[:, ::3]  # one in-plane point's three heights per layer
    w = np.array([5, 8, 5]) / 18 * T / layers
    assert np.sum(w * h**2) == pytest.approx(T**3 / 12, rel=1e-12)
    assert h.min() > -T / 2 and h.max() < T / 2


def test_columns_of_a_flat_square_fill_its_volume():
    """Two triangles of the unit square, extruded along z: the wedges' volume
    (ccx's rule on the 15-node map) is the area times t, each layer's alike."""
    x = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    tri = np.array([[0, 1, 2], [0, 2, 3]])
    edges = np.array([[0, 1], [1, 2], [0, 2], [2, 3], [0, 3]])
    face_edge = np.array([[0, 1, 2], [2, 3, 4]])
    mids = 0.5 * (x[edges[:, 0]] + x[edges[:, 1]])
    up = np.tile([0.0, 0, 1], (4, 1))
    m = cr.solid_mesh(x, tri, up, mids, np.tile([0.0, 0, 1], (5, 1)), face_edge, T, 3)
    vol = cr.wedge_volumes(m)
    assert len(m.elements) == 6 and len(m.nodes) == 7 * 4 + 4 * 5
    np.testing.assert_allclose(vol, T / 3 * 0.5, rtol=1e-12)
    np.testing.assert_allclose(m.level(3)[:, 2], 0.0, atol=1e-15)  # the mid-surface


def test_onefolds_section_heights_run_against_the_top_normal():
    """The strain of the offset surface ``x + h n`` (n the designed top
    normal, linear over a face) is ``h sym(a_i . n_j)``: onefold's curvature
    is its negative (the formed stress at ``h`` is onefold's at ``z = -h``)."""
    from onefold_cad.design import fold_design
    from onefold_cad.mechanics.energy import second_fundamental_form
    from onefold_cad.mechanics.model import sheet_model
    from onefold_cad.mechanics.shell import director_angles, pack
    from onefold_cad.templates import find_template, load_template

    design = load_template(find_template("broken-vault"))
    folded = fold_design(design)
    model = sheet_model(design, folded, level="coarse")
    x, tri, flat = model.designed, model.mesh.triangles, model.mesh.nodes
    shell = model.shell
    q = pack(x, director_angles(shell, x, model.normals))
    ours = np.einsum("mij,mj->mi", shell.cartesian, second_fundamental_form(shell, q))
    centre = flat[tri].mean(axis=1)
    n = np.stack(
        [folded.normals((flat[tri[:, k]] + 1e-6 * (centre - flat[tri[:, k]])) / model.scale)
         for k in range(3)], axis=1,
    )  # fmt: skip
    a1, a2 = x[tri[:, 1]] - x[tri[:, 0]], x[tri[:, 2]] - x[tri[:, 0]]
    n1, n2 = n[:, 1] - n[:, 0], n[:, 2] - n[:, 0]
    dot = lambda u, v: np.einsum("mi,mi->m", u, v)  # noqa: E731
    cov = np.stack([dot(a1, n1), 0.5 * (dot(a1, n2) + dot(a2, n1)), dot(a2, n2)], axis=1)
    offset = np.einsum("mij,mj->mi", shell.cartesian, cov)
    ratio = np.sum(ours * offset, axis=1) / np.sum(offset * offset, axis=1)
    assert np.median(ratio) == pytest.approx(-1.0, abs=0.02)


class _Roof:
    """A fold along the x axis: the y > 0 side's top normal turned by ``a``
    about x one way, the y < 0 side's the other (``folded.normals``' shape)."""

    def __init__(self, a: float) -> None:
        self.up = np.array([0.0, -math.sin(a), math.cos(a)])
        self.down = np.array([0.0, math.sin(a), math.cos(a)])

    def normals(self, xy: np.ndarray) -> np.ndarray:
        return np.where((np.asarray(xy)[:, 1] > 0)[:, None], self.up, self.down)


def test_the_crease_moves_along_the_mitre_and_its_slant_fades():
    roof = _Roof(math.radians(41.4))
    where = np.array([[1.0, 0.0], [-1.0, 0.0], [1.0, 1.5 * T], [1.0, -4 * T], [2.0, 1e-9]])
    move, crease = cr.node_moves(roof, where, 1.0, T)
    assert crease.tolist() == [True, True, False, False, False]
    for m in move[:2]:  # a unit height from either side's plane
        assert m @ roof.up == pytest.approx(1.0) and m @ roof.down == pytest.approx(1.0)
    fade = 1.0 - 1.5 / cr.MITRE_FADE
    np.testing.assert_allclose(move[2], roof.up + fade * (move[0] - roof.up), atol=1e-12)
    np.testing.assert_allclose(move[3], roof.down, atol=1e-12)  # beyond the fade


def _state(linear: bool) -> dict:
    """A one-wedge model as ``calculix_release.setup`` returns it."""
    from types import SimpleNamespace

    x = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    mids = 0.5 * (x + x[[1, 2, 0]])
    up = np.tile([0.0, 0, 1], (3, 1))
    solid = cr.solid_mesh(x, np.array([[0, 1, 2]]), up, mids, up, np.array([[0, 1, 2]]), T, 1)
    stress = np.arange(54.0).reshape(1, 9, 6) * 1e6
    material = SimpleNamespace(youngs_modulus=E, poisson=NU, yield_stress=SY)
    return {
        "solid": solid,
        "model": SimpleNamespace(material=material),
        "stress": stress,
        "eigen": cr.initial_strain(stress, E, NU),
        "n": 3,
        "linear": linear,
    }


@pytest.mark.parametrize("linear", [False, True])
def test_held_deck_hands_over_the_stress_the_way_its_law_reads_it(tmp_path, linear):
    """With NLGEOM the eigenstrain (TYPE=PLASTIC STRAIN), without it the
    stress itself (TYPE=STRESS); point 2 of element 1 carries row 2."""
    import calculix_release as rel

    st = _state(linear)
    rel.write_held(st, tmp_path / "held.inp")
    lines = (tmp_path / "held.inp").read_text().splitlines()
    kind = "STRESS" if linear else "PLASTIC STRAIN"
    at = lines.index(f"*INITIAL CONDITIONS,TYPE={kind}")
    row = [float(v) for v in lines[at + 2].split(",")]
    expected = (st["stress"] if linear else st["eigen"])[0, 1]
    assert row[:2] == [1, 2]
    np.testing.assert_allclose(row[2:], expected, rtol=1e-9)
    assert ("*STEP" in lines) == linear and ("*STEP,NLGEOM" in lines) != linear
