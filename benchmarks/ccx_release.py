"""The CalculiX peer of the springback from the formed state
(``calculix_release.py``): onefold's mesh of the designed sheet as solid
quadratic wedges (``C3D15``), the formed stress at every integration point
from onefold's J2 law, and the decks of the held and the released runs (SI
units: m, Pa, N).

* **Solid mesh** (:func:`solid_mesh`): each face of onefold's mesh a column of
  ``layers`` wedges, its mid-surface nodes the designed nodes, the edge
  midpoints lifted onto the curved surface (``inp_mesh.curved_midpoints``),
  every node moved ``h`` along the designed top normal at ``2 layers + 1``
  heights ``h`` from ``-t/2`` to ``t/2`` (the odd levels are the wedges'
  vertical midpoints). The crease is welded (:func:`node_moves`):
  its nodes are shared by both sides and moved along the mitre of the two
  sides' normals, the slant faded beside it, so the two sides keep their
  angle, as ``onefold simulate``'s ``held`` crease. (Shared mitre nodes
  alone turn wedges inside out near H, where onefold's faces are narrower
  than the slant ``tan(psi / 2) t / 2``; a ``*RIGID BODY`` per crease
  station kept even the elastic release from converging.)
* **Integration points** (:data:`GAUSS_WEDGE`, ccx's ``gauss3d8``): three in
  the plane times three through each layer at ``zeta = -sqrt(3/5), 0,
  sqrt(3/5)``; a point's height is ``h = (k + 1/2) t / L - t/2 + zeta t /
  (2 L)`` in layer ``k`` of ``L`` (the wedge is linear through its depth).
* **Formed stress** (:func:`formed_stress`): onefold's forming imposes, at
  every point of every face, the strain ``h`` times the face's designed
  curvature with no membrane strain, in ``FORMING_STEPS`` proportional return
  mappings of the J2 law (``onefold_cad.mechanics.j2``); the same law here at
  each integration point's height, the plane stress turned from the face's
  frame (first axis along its first edge) into the global frame
  (:func:`to_global`), ``s33 = 0``. onefold's section heights ``z`` run along
  the director, opposite the top normal: the strain at ``h`` is ``-h`` times
  onefold's curvature (the sign checked in tests/ against the offset surface).
* **The initial state as an initial strain** (:func:`initial_strain`): ccx
  2.20 adds an ``*INITIAL CONDITIONS, TYPE=STRESS`` twice into the stress of
  its finite-strain plasticity (``incplas.f``, the law ``NLGEOM`` uses: a
  held wedge given 100 MPa reads 200 MPa, and a plane stress inside the yield
  surface yields) and counts its hydrostatic part in the yield check; its
  small-strain plasticity reads it right. ``TYPE=PLASTIC STRAIN`` is
  subtracted from the strain before the law (an eigenstrain): the strain
  ``-C^-1 sigma`` gives the stress ``sigma`` at the formed, undisplaced state
  in both, and for a perfectly plastic law the stress is the whole state. So
  the perfectly plastic variant of a template is compared, on both sides.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: ccx's ``gauss3d8`` (src/gauss.f): the 9 points of a ``C3D15`` wedge as
#: ``(xi, eta, zeta)``, in ccx's order.
GAUSS_WEDGE = np.array(
    [
        (xi, eta, zeta)
        for zeta in (-math.sqrt(0.6), 0.0, math.sqrt(0.6))
        for xi, eta in ((1 / 6, 1 / 6), (2 / 3, 1 / 6), (1 / 6, 2 / 3))
    ]
)


def point_heights(thickness: float, layers: int) -> Array:
    """``(layers, 9)`` the height ``h`` (m, along the top normal from the
    mid-surface) of each ``C3D15`` integration point, layer by layer from
    the bottom (``h = -t/2``)."""
    d = thickness / layers
    mid = -0.5 * thickness + (np.arange(layers) + 0.5) * d
    return mid[:, None] + 0.5 * d * GAUSS_WEDGE[None, :, 2]


def face_frames(x: Array, triangles: IntArray) -> Array:
    """``(m, 3, 3)`` each face's orthonormal frame as rows ``(e1, e2, e3)``:
    ``e1`` along its first edge, ``e2`` in its plane towards its third
    corner, ``e3 = e1 x e2`` (the frame of onefold's J2 stresses)."""
    p = x[triangles]
    a1, a2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    e1 = a1 / np.linalg.norm(a1, axis=1)[:, None]
    e2 = a2 - np.einsum("mi,mi->m", a2, e1)[:, None] * e1
    e2 /= np.linalg.norm(e2, axis=1)[:, None]
    return np.stack([e1, e2, np.cross(e1, e2)], axis=1)


def to_global(plane: Array, frames: Array) -> Array:
    """``(m, k, 6)`` ccx's ``(s11, s22, s33, s12, s13, s23)`` of the plane
    stresses ``plane`` ``(m, k, 3)`` = ``(s11, s22, s12)`` on the faces'
    ``frames`` ``(m, 3, 3)`` (rows e1, e2, e3)."""
    e1, e2 = frames[:, None, 0], frames[:, None, 1]
    s11, s22, s12 = plane[..., 0:1], plane[..., 1:2], plane[..., 2:3]
    t = (
        s11[..., None] * e1[..., :, None] * e1[..., None, :]
        + s22[..., None] * e2[..., :, None] * e2[..., None, :]
        + s12[..., None]
        * (e1[..., :, None] * e2[..., None, :] + e2[..., :, None] * e1[..., None, :])
    )
    return np.stack(
        [t[..., 0, 0], t[..., 1, 1], t[..., 2, 2], t[..., 0, 1], t[..., 0, 2], t[..., 1, 2]],
        axis=-1,
    )


def tensor(stress: Array) -> Array:
    """``(..., 3, 3)`` the symmetric tensors of ccx's ``(..., 6)``
    ``(s11, s22, s33, s12, s13, s23)``."""
    t = np.empty(stress.shape[:-1] + (3, 3))
    for (i, j), c in {(0, 0): 0, (1, 1): 1, (2, 2): 2, (0, 1): 3, (0, 2): 4, (1, 2): 5}.items():
        t[..., i, j] = t[..., j, i] = stress[..., c]
    return t


def to_frame(stress: Array, frames: Array) -> Array:
    """The inverse of :func:`to_global` for stresses in the faces' planes:
    ``(m, k, 3)`` ``(s11, s22, s12)`` on ``frames`` of ccx's ``(m, k, 6)``."""
    s = stress
    t = tensor(s)
    e1, e2 = frames[:, None, 0], frames[:, None, 1]
    proj = lambda a, b: np.einsum("mki,mkij,mkj->mk", a, t, b)  # noqa: E731
    e1 = np.broadcast_to(e1, s.shape[:-1] + (3,))
    e2 = np.broadcast_to(e2, s.shape[:-1] + (3,))
    return np.stack([proj(e1, e1), proj(e2, e2), proj(e1, e2)], axis=-1)


def formed_stress(law, curvature: Array, heights: Array, steps: int) -> tuple[Array, Array]:
    """``(stress (m, k, 3), plastic (m, k) bool)``: the plane stress on each
    face's frame at heights ``heights`` ``(k,)`` (m, along the top normal)
    after onefold's imposed forming: the strain ``-h`` times the face's
    ``curvature`` ``(m, 3)`` (onefold's Cartesian ``(k11, k22, 2 k12)``, whose
    heights run along the director), reached in ``steps`` proportional
    return mappings of the J2 ``law`` (``mechanics.j2.law.update``) from the
    virgin state; ``plastic``: the points with plastic strain."""
    from onefold_cad.mechanics.j2.law import J2State, update

    strain = -np.asarray(heights)[None, :, None] * np.asarray(curvature)[:, None, :]
    state = J2State.virgin(strain.shape[:-1])
    resp = None
    for i in range(1, steps + 1):
        resp = update(law, strain * (i / steps), state)
        state = resp.state
    assert resp is not None
    return resp.stress, state.equivalent > 0


def initial_strain(stress: Array, youngs: float, poisson: float) -> Array:
    """``(..., 6)`` the strain ``-C^-1 sigma`` (ccx's order, tensor shears
    ``e12 = g12 / 2``) whose eigenstrain gives the stress ``stress``
    ``(..., 6)`` at zero displacement (isotropic ``E``, ``nu``)."""
    s = np.asarray(stress, dtype=float)
    trace = s[..., 0] + s[..., 1] + s[..., 2]
    eps = (1.0 + poisson) / youngs * s
    eps[..., :3] -= (poisson / youngs * trace)[..., None]
    return -eps


@dataclass(frozen=True)
class SolidMesh:
    """The designed sheet as ``C3D15`` columns (0-based ids).

    Attributes:
        nodes: ``(N, 3)`` positions (m): corner node ``i`` at level ``j``
            (``0 .. 2 layers``) is ``j n + i``; edge midpoint ``e`` at even
            level ``2 l`` is ``(2 layers + 1) n + l E + e``.
        elements: ``(m layers, 15)`` ccx's node order (corners bottom, top,
            edge midpoints bottom, top, vertical midpoints); face ``f``'s
            layer ``k`` is element ``f layers + k``.
        layers: wedges through the thickness.
        n_corners: ``n``, the designed nodes.
    """

    nodes: Array
    elements: IntArray
    layers: int
    n_corners: int

    def level(self, j: int) -> Array:
        """``(n, 3)`` the corner nodes at level ``j`` (``layers``: the mid-surface)."""
        return self.nodes[j * self.n_corners : (j + 1) * self.n_corners]


def solid_mesh(
    x: Array,
    triangles: IntArray,
    move: Array,
    mids: Array,
    mid_move: Array,
    face_edge: IntArray,
    thickness: float,
    layers: int,
) -> SolidMesh:
    """The columns of wedges over the faces ``triangles`` ``(m, 3)`` of the
    mid-surface nodes ``x`` ``(n, 3)``: nodes moved by ``h move`` (``move``
    ``(n, 3)``, :func:`offsets`), the edge midpoints ``mids`` ``(E, 3)`` by
    ``h mid_move``; ``face_edge`` ``(m, 3)``: the edge of face corners
    ``(0, 1), (1, 2), (2, 0)``. The faces must be counterclockwise about the
    top normal (a positive wedge)."""
    n, e_count = len(x), len(mids)
    h = np.linspace(-0.5 * thickness, 0.5 * thickness, 2 * layers + 1)
    corners = x[None] + h[:, None, None] * move[None]
    edge_h = h[::2]
    edge_nodes = mids[None] + edge_h[:, None, None] * mid_move[None]
    nodes = np.concatenate([corners.reshape(-1, 3), edge_nodes.reshape(-1, 3)])
    base = (2 * layers + 1) * n
    rows = []
    for k in range(layers):
        jb, jm, jt = 2 * k, 2 * k + 1, 2 * k + 2
        rows.append(
            np.column_stack(
                [
                    jb * n + triangles,
                    jt * n + triangles,
                    base + k * e_count + face_edge,
                    base + (k + 1) * e_count + face_edge,
                    jm * n + triangles,
                ]
            )
        )
    elements = np.stack(rows, axis=1).reshape(-1, 15)
    return SolidMesh(nodes, elements.astype(np.int64), layers, n)


def wedge_volumes(mesh: SolidMesh) -> Array:
    """``(elements,)`` each wedge's volume by ccx's 9-point rule (the
    Jacobian of the 15-node map; all > 0 for a valid mesh)."""
    vol = np.zeros(len(mesh.elements))
    weights = np.repeat([5 / 54, 8 / 54, 5 / 54], 3)  # gauss3d8's weights
    xl = mesh.nodes[mesh.elements]  # (e, 15, 3)
    for (xi, eta, ze), w in zip(GAUSS_WEDGE, weights, strict=True):
        vol += w * np.linalg.det(np.einsum("eki,kj->eij", xl, _shape15_derivatives(xi, eta, ze)))
    return vol


def _shape15_derivatives(xi: float, et: float, ze: float) -> Array:
    """``(15, 3)`` d N / d (xi, eta, zeta) of ccx's ``shape15w``."""
    a = 1.0 - xi - et
    d = np.zeros((15, 3))
    d[:, 0] = [
        0.5 * (1 - ze) * (4 * xi + 4 * et + ze - 2), 0.5 * (1 - ze) * (4 * xi - ze - 2), 0.0,
        0.5 * (1 + ze) * (4 * xi + 4 * et - ze - 2), 0.5 * (1 + ze) * (4 * xi + ze - 2), 0.0,
        2 * (1 - ze) * (1 - 2 * xi - et), 2 * et * (1 - ze), -2 * et * (1 - ze),
        2 * (1 + ze) * (1 - 2 * xi - et), 2 * et * (1 + ze), -2 * et * (1 + ze),
        -(1 - ze * ze), 1 - ze * ze, 0.0,
    ]  # fmt: skip
    d[:, 1] = [
        0.5 * (1 - ze) * (4 * xi + 4 * et + ze - 2), 0.0, 0.5 * (1 - ze) * (4 * et - ze - 2),
        0.5 * (1 + ze) * (4 * xi + 4 * et - ze - 2), 0.0, 0.5 * (1 + ze) * (4 * et + ze - 2),
        -2 * xi * (1 - ze), 2 * xi * (1 - ze), 2 * (1 - ze) * (1 - xi - 2 * et),
        -2 * xi * (1 + ze), 2 * xi * (1 + ze), 2 * (1 + ze) * (1 - xi - 2 * et),
        -(1 - ze * ze), 0.0, 1 - ze * ze,
    ]  # fmt: skip
    d[:, 2] = [
        a * (xi + et + ze - 0.5), xi * (-xi + ze + 0.5), et * (-et + ze + 0.5),
        a * (-xi - et + ze + 0.5), xi * (xi + ze - 0.5), et * (et + ze - 0.5),
        -2 * xi * a, -2 * xi * et, -2 * et * a,
        2 * xi * a, 2 * xi * et, 2 * et * a,
        -2 * a * ze, -2 * xi * ze, -2 * et * ze,
    ]  # fmt: skip
    return d


#: The mitred crease's slant fades over this many thicknesses from it.
MITRE_FADE = 3.0


def node_moves(folded, where: Array, scale: float, t: float) -> tuple[Array, NDArray[np.bool_]]:
    """``(move (N, 3), crease (N,) bool)``: the direction each node at flat
    ``where`` ``(N, 2)`` (m) moves per unit of height: the designed top
    normal of its side; on the crease (a ruling of both cones: each half's
    two normals constant along it) the mitre ``m = (n_a + n_b) / (1 + n_a .
    n_b)`` of its two sides' normals (a unit height from either side's
    plane); beside it the node's own normal plus the slant ``m - n_side`` of
    its crease half, fading to 0 at ``MITRE_FADE`` t (a face narrower than
    the slant is not turned inside out)."""
    size = float(np.ptp(where, axis=0).max())
    crease = np.abs(where[:, 1]) <= 1e-12 * size
    eps = np.array([0.0, 1e-7 * size])
    up, down = folded.normals((where + eps) / scale), folded.normals((where - eps) / scale)
    own = np.where((where[:, 1] > 0)[:, None], up, down)
    out = own.copy()
    w = np.clip(1.0 - np.abs(where[:, 1]) / (MITRE_FADE * t), 0.0, 1.0)
    for half in (where[:, 0] > 0, where[:, 0] < 0):
        c = np.flatnonzero(crease & half)
        if len(c) == 0:
            continue
        a, b = down[c].mean(axis=0), up[c].mean(axis=0)
        a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
        m = (a + b) / (1.0 + a @ b)
        slant = np.where((where[:, 1] > 0)[:, None], m - b, m - a)
        near = half & ~crease & (w > 0)
        out[near] = own[near] + w[near, None] * slant[near]
        out[c] = m
    return out, crease
