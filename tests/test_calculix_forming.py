"""The CalculiX forming benchmark's pure-numpy parts (benchmarks/ccx_path.py,
ccx_deck.py, calculix_forming.py): the driven path's ramp strain, the rigid
motion taken out of it, the graded steps, the crease hinge and the one-run
release deck. No ccx needed; expected values in closed form."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import calculix_forming as cf  # noqa: E402
import ccx_deck as cd  # noqa: E402
import ccx_path as cp  # noqa: E402


def _rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _square_mesh(nx: int = 4, ny: int = 4) -> tuple[np.ndarray, np.ndarray]:
    """Linear triangles of the square [-1, 1]^2 (the crease y = 0 a grid line)."""
    xs = np.linspace(-1.0, 1.0, nx + 1)
    ys = np.linspace(-1.0, 1.0, ny + 1)
    pts = np.array([[x, y] for y in ys for x in xs])
    tris = []
    for r in range(ny):
        for c in range(nx):
            a0, a1 = r * (nx + 1) + c, r * (nx + 1) + c + 1
            b0, b1 = a0 + nx + 1, a1 + nx + 1
            tris += [[a0, a1, b1], [a0, b1, b0]]
    return pts, np.array(tris)


def test_ramp_strain_of_a_turned_chord_is_one_minus_cos_of_half_the_turn():
    """A chord of unchanged length turned by phi: at the ramp's midpoint it is
    cos(phi / 2) of its length; a translation strains nothing."""
    a = np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    edges = np.array([[0, 1]])
    for phi in (0.01, 0.2, 1.0):
        b = a @ _rot_z(phi).T
        assert cp.ramp_strain(a, b, edges)[0] == pytest.approx(math.cos(phi / 2) - 1, rel=1e-12)
    assert cp.ramp_strain(a, a + [3.0, -1.0, 2.0], edges)[0] == pytest.approx(0.0, abs=1e-15)


def test_ramp_strain_leaves_out_the_forms_own_length_change():
    """A chord stretched along itself (no turn) has no ramp strain: the ramp
    measures the shortening that the linear path adds, not the forms' error."""
    a = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    b = np.array([[0.0, 0.0, 0.0], [1.01, 0.0, 0.0]])
    assert cp.ramp_strain(a, b, np.array([[0, 1]]))[0] == pytest.approx(0.0, abs=1e-15)


def test_half_edges_of_one_s6_are_its_six_corner_to_midpoint_chords():
    tri6 = np.array([[0, 1, 2, 3, 4, 5]])
    got = {tuple(e) for e in cp.half_edges(tri6)}
    assert got == {(0, 3), (1, 3), (1, 4), (2, 4), (2, 5), (0, 5)}


def test_align_chain_takes_a_rigid_turn_out_of_each_step():
    rng = np.random.default_rng(3)
    flat = np.column_stack([rng.random((30, 2)), np.zeros(30)])
    moved = [flat @ _rot_z(0.3 * k).T + [k, 2.0 * k, -k] for k in (1, 2, 3)]
    aligned = cp.align_chain(flat, moved, np.ones(30))
    for f in aligned:
        np.testing.assert_allclose(f, flat, atol=1e-12)


def test_graded_steps_halve_a_rigid_turn_until_the_ramp_strain_is_below_the_bound():
    """A square turned through 1 rad as s goes 0..1, unaligned: a step of
    turn d has ramp strain 1 - cos(d / 2), so halving from one step stops at
    2^k steps, k the least with 1 - cos(1 / 2^(k + 1)) <= bound; aligned,
    the turn is rigid motion and one step suffices."""
    pts, tris = _square_mesh(2, 2)
    flat, tri6 = cd.quadratic(pts, tris)
    x0 = np.column_stack([flat, np.zeros(len(flat))])
    edges = cp.half_edges(tri6)
    bound = 1e-4
    k = next(k for k in range(20) if 1 - math.cos(1.0 / 2 ** (k + 1)) <= bound)
    path = cp.graded_steps(
        lambda s: x0 @ _rot_z(s).T, x0, edges, np.ones(len(x0)), bound=bound, start=1, align=False
    )
    assert len(path.s) == 2**k
    assert path.worst.max() == pytest.approx(1 - math.cos(1.0 / 2 ** (k + 1)), rel=1e-9)
    aligned = cp.graded_steps(
        lambda s: x0 @ _rot_z(s).T, x0, edges, np.ones(len(x0)), bound=bound, start=1
    )
    assert len(aligned.s) == 1 and aligned.worst.max() < 1e-12


def test_graded_steps_refine_only_where_the_ramp_strains():
    """A turn theta(s) = s^2 (fast at s = 1, slow near 0), four steps to start:
    the first turns 1/16 rad (ramp strain 1 - cos(1/32) = 4.9e-4, below the
    bound 1e-3) and stays; the last turns 7/16 rad and is halved."""
    pts, tris = _square_mesh(2, 2)
    flat, tri6 = cd.quadratic(pts, tris)
    x0 = np.column_stack([flat, np.zeros(len(flat))])
    path = cp.graded_steps(
        lambda s: x0 @ _rot_z(s * s).T,
        x0,
        cp.half_edges(tri6),
        np.ones(len(x0)),
        bound=1e-3,
        start=4,
        align=False,
    )
    assert path.s[0] == pytest.approx(0.25)
    assert path.worst[0] == pytest.approx(1 - math.cos(1 / 32), rel=1e-9)
    assert np.diff(path.s)[-1] < 0.25 / 2
    assert path.worst.max() <= 1e-3


def test_split_crease_gives_the_lower_side_its_own_crease_nodes():
    """Outside the hole, every node on y = 0 used by a lower element gets a
    twin at the same place; no element then uses a node and a twin, the upper
    elements keep theirs, and the lower ones touch no upper crease node."""
    pts, tris = _square_mesh(4, 4)
    flat1, tri1 = cd.quadratic(pts, tris)
    hole_r = 0.3
    flat, tri6, partner = cd.split_crease(flat1, tri1, hole_r)
    n1 = len(flat1)
    on = np.flatnonzero((np.abs(flat1[:, 1]) < 1e-12) & (np.abs(flat1[:, 0]) >= hole_r))
    # the crease line's nodes (corners and midpoints) lie at x = k / 4,
    # k = -4..4; |x| >= 0.3 keeps k = +-2, +-3, +-4
    assert len(partner) == len(on) == 6
    np.testing.assert_array_equal(np.sort(partner), on)
    np.testing.assert_allclose(flat[n1:], flat1[partner])
    below = flat[tri6[:, :3], 1].mean(axis=1) < 0
    np.testing.assert_array_equal(tri6[~below], tri1[~below])
    assert not np.isin(tri6[below], on).any()
    assert np.isin(tri6[below], np.arange(n1, len(flat))).any()


def _deck_of_split_square(loads=None):
    pts, tris = _square_mesh(2, 2)
    flat1, tri1 = cd.quadratic(pts, tris)
    flat, tri6, partner = cd.split_crease(flat1, tri1, 0.0)
    n1, n = len(flat1), len(flat)
    x0 = np.column_stack([flat, np.zeros(n)])
    u = np.zeros((2, n1, 3))
    u[1, :, 2] = 0.1
    support = cd.support_321(x0 + u[-1, np.r_[np.arange(n1), partner]], [0, 2, 8])
    deck = cd.Deck(x0, tri6, np.array([0.5, 1.0]), u, np.arange(n1), 1e-3, 2e11, 0.3, 2e8)
    deck.twins, deck.support, deck.loads = partner, support, loads
    return deck, n1, n, partner


def test_deck_ties_each_twin_to_its_partners_driver_and_releases_in_the_same_run(tmp_path):
    loads = None
    deck, n1, n, partner = _deck_of_split_square(loads)
    deck.loads = np.arange(3.0 * n1).reshape(n1, 3) + 1.0
    cd.write_deck(deck, tmp_path / "d.inp")
    text = (tmp_path / "d.inp").read_text()
    for k, p in enumerate(partner):
        twin, driver = n1 + k + 1, n + 1 + int(p)
        for d in (1, 2, 3):
            assert f"\n{twin},{d},1.,{driver},{d},-1.\n" in text
    steps = text.split("*STEP")
    assert len(steps) == 1 + 2 + 1  # two forming steps, one release
    release = steps[-1]
    assert "*BOUNDARY,OP=NEW" in release and "*CLOAD,OP=NEW,AMPLITUDE=DOWN" in release
    fixed = sum(len(v) for v in deck.support.values())
    bc = release.split("*BOUNDARY,OP=NEW\n")[1].split("*CLOAD")[0].strip().splitlines()
    assert len(bc) == fixed == 6
    cl = release.split("AMPLITUDE=DOWN\n")[1].split("*NODE PRINT")[0].strip().splitlines()
    assert len(cl) == 3 * n1 - 6
    assert all(int(line.split(",")[0]) > n for line in cl)  # on the drivers
    assert "RF" not in release  # the reactions come from the forming-only run
    cd.write_deck(_deck_of_split_square(None)[0], tmp_path / "f.inp")
    form = (tmp_path / "f.inp").read_text()
    assert form.count("*STEP") == 2 and "\nRF\n" in form


def test_driver_loads_sum_a_twin_s_reaction_into_its_partners_driver():
    deck, n1, n, partner = _deck_of_split_square()
    rf = np.column_stack([np.arange(1, n + 1), np.ones((n, 3))])
    loads = cd.driver_loads(deck, rf)
    expect = np.ones((n1, 3))
    np.add.at(expect, partner, 1.0)
    np.testing.assert_allclose(loads, expect)
    assert loads.sum() == pytest.approx(3.0 * n)


def test_richardson_recovers_the_limit_of_a_second_order_sequence():
    h = [0.4, 0.28, 0.196]
    v = [2.0 + 5.0 * x**2 for x in h]
    val, p = cf.richardson(h, v)
    assert val == pytest.approx(2.0, rel=1e-9)
    assert p == pytest.approx(2.0, rel=1e-9)


def _one_s6(L: float) -> tuple[np.ndarray, np.ndarray]:
    corners = np.array([[0.0, 0.0], [L, 0.0], [0.0, L]])
    mids = 0.5 * (corners + corners[[1, 2, 0]])
    return np.concatenate([corners, mids]), np.array([[0, 1, 2, 3, 4, 5]])


def test_s6_membrane_strain_is_exact_for_a_stretch_and_zero_for_a_rigid_turn():
    flat, tri6 = _one_s6(0.3)
    lam = 1.01
    stretched = np.column_stack([lam * flat[:, 0], flat[:, 1], np.zeros(6)])
    assert cp.s6_membrane_strain(flat, stretched, tri6)[0] == pytest.approx(
        0.5 * (lam**2 - 1), rel=1e-12
    )
    turned = np.column_stack([flat, np.zeros(6)]) @ _rot_z(0.7).T + 5.0
    assert cp.s6_membrane_strain(flat, turned, tri6)[0] == pytest.approx(0.0, abs=1e-14)


def test_s6_nodes_on_a_cylinder_strain_the_element_by_kappa_h_squared():
    """Every node put on the cylinder of radius R the flat element rolls onto
    (an isometry): the quadratic element is strained nonetheless, and the
    strain falls as the square of its size (the ratio 4 to 2 %)."""
    R = 1.0

    def rolled(flat):
        X, Y = flat[:, 0], flat[:, 1]
        return np.column_stack([R * np.sin(X / R), Y, R * (1 - np.cos(X / R))])

    big = cp.s6_membrane_strain(*(lambda f, t: (f, rolled(f), t))(*_one_s6(0.4)))[0]
    small = cp.s6_membrane_strain(*(lambda f, t: (f, rolled(f), t))(*_one_s6(0.2)))[0]
    assert big > 1e-3  # above a stainless steel's yield strain at kappa h = 0.4
    assert big / small == pytest.approx(4.0, rel=0.02)


def test_reuse_reads_a_finished_forming_and_runs_no_ccx(tmp_path, monkeypatch):
    deck, n1, n, _ = _deck_of_split_square()

    def no_ccx(*args, **kwargs):
        raise AssertionError("ccx must not run")

    monkeypatch.setattr(cd, "run_ccx", no_ccx)
    rows = "\n".join(f"{i} 0.0 0.0 {0.1 * i:.6E}" for i in range(1, n + 1))
    (tmp_path / "job_form.dat").write_text(
        f"\n displacements (vx,vy,vz) for set SH and time  0.1000000E+01\n\n{rows}\n"
    )
    res = cd.form_and_release(deck, tmp_path, "job", release=False, reuse=True)
    assert res["wall_form_s"] is None
    np.testing.assert_allclose(
        cd.displacements(res["form"], 1.0, n)[:, 2], 0.1 * np.arange(1, n + 1)
    )


def test_graded_sheet_grows_its_elements_with_the_distance_from_h():
    """A 2 x 2 square with a hole of radius 0.05 graded at 0.5 r (capped at
    0.3): the crease meets the outline at x = +-1 (nodes there), the elements
    near the hole follow 0.5 r, those far from it the cap, and the crease is
    kept as edges (nodes on y = 0 from the hole to the outline)."""
    import ccx_mesh as cm

    square = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
    assert cm.axis_crossings(square) == (1.0, -1.0)
    pts, tris, info = cm.graded_sheet(square, 0.1, 0.3, 0.5)
    np.testing.assert_allclose(pts[info["crease_ends"]], [[1.0, 0.0], [-1.0, 0.0]], atol=1e-12)
    np.testing.assert_allclose(pts[info["vertices"]], square, atol=1e-12)
    edge = np.linalg.norm(pts[tris] - pts[np.roll(tris, -1, axis=1)], axis=2).max(axis=1)
    r = np.hypot(*pts[tris].mean(axis=1).T)
    # the target 0.5 r is at most 0.05 within r < 0.1; beyond r = 0.6 it is capped at 0.3
    assert np.median(edge[r < 0.1]) < 0.05
    assert 0.15 < np.median(edge[r > 0.8]) < 0.45
    on = np.abs(pts[:, 1]) < 1e-12
    assert np.sum(on & (pts[:, 0] > 0.5)) >= 2  # the crease's nodes, not only its ends


def test_deck_writes_the_template_s_linear_hardening(tmp_path):
    """The deck's law is simulate --law j2's: sigma_y at no plastic strain
    and sigma_y + H at a plastic strain of 1 (ccx interpolates linearly);
    without hardening, one row (perfectly plastic)."""

    def plastic_rows(deck):
        cd.write_deck(deck, tmp_path / "d.inp")
        lines = (tmp_path / "d.inp").read_text().splitlines()
        i = lines.index("*PLASTIC") + 1
        rows = []
        while not lines[i].startswith("*"):
            rows.append([float(v) for v in lines[i].split(",")])
            i += 1
        return rows

    deck, *_ = _deck_of_split_square()
    assert plastic_rows(deck) == [[2e8, 0.0]]
    deck.hardening = 507e6
    assert plastic_rows(deck) == [[2e8, 0.0], [2e8 + 507e6, 1.0]]


def test_free_edge_midpoints_are_the_outline_s_and_the_hinge_s_upper_side():
    """Driven with ``--drive edges``: the midpoints of the square's outline and
    of the crease's edges on the upper side (the lower side's are twins, tied
    to those), none inside."""
    pts, tris = _square_mesh(4, 4)
    flat1, tri1 = cd.quadratic(pts, tris)
    flat, tri6, partner = cd.split_crease(flat1, tri1, 0.0)
    n1 = len(flat1)
    got = cf.free_edge_midpoints(tri6, n1)
    mids = np.arange(len(pts), n1)
    p = flat1[mids]
    outline = np.isclose(np.abs(p).max(axis=1), 1.0)
    crease = np.isclose(p[:, 1], 0.0)
    np.testing.assert_array_equal(got, mids[outline | crease])
    assert len(got) == 16 + 4  # 4 per side of the square, 4 on the crease
