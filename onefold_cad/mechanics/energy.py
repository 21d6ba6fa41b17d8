"""The total energy of a shell and its exact gradient and sparse Hessian.

``E = membrane + bending + crease + gravity`` (J), all vectorised over elements:

- membrane (CST, St Venant-Kirchhoff, plane stress):
  ``Abar E' t / 2 * Q(eps)``, ``eps = (a - abar) / 2``;
- bending (mid-edge directors): per face ``b = 2 [[u0 + u1, u0], [u0, u0 + u2]]``,
  ``u_i = h_i tan(phi_i)``, ``phi_i`` the angle of edge i's director from the face
  normal (``kinematics.triangles.director_slopes``); a director is its edge's reference
  director transported to the edge's current direction and turned by the
  director angle about it (``transport.transported_director``); energy
  ``Abar D / 2 Q(b - bbar)``, or with the faces' accumulated plastic curvature
  (``Shell.accumulated``) the elastic-plastic law's ``Abar W(sqrt(Q(b - bbar)))``
  (``plastic.moment``);
- crease hinges: ``k_c / 2 * lbar * (theta+ - theta- - psi_set)^2``, the angle
  between the two sides' directors;
- gravity: ``-sum m_i g . x_i``.

``Q(s) = s^T K s`` is the isotropic form of ``material.strain_form``. A face's
energy depends on its 9 coordinates and its 3 director angles only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics.assembly import pattern_of
from onefold_cad.mechanics.j2.section import SectionResponse
from onefold_cad.mechanics.kinematics.transport import transported_director
from onefold_cad.mechanics.kinematics.triangles import (
    METRIC_HESSIAN,
    SlopeTerms,
    director_slopes,
    face_metric,
)
from onefold_cad.mechanics.plastic import moment
from onefold_cad.mechanics.shell import Shell, unpack

__all__ = ["Evaluation", "evaluate", "second_fundamental_form", "section_response"]

F = NDArray[np.float64]
#: b = B u
_B = np.array([[2.0, 2.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 2.0]])


@dataclass(frozen=True)
class Evaluation:
    """The energy at one state.

    Attributes:
        energy: total (J).
        parts: the terms ``membrane``, ``bending``, ``crease``, ``gravity`` (J).
        gradient: (N,) dE/dq (N for coordinates, N m for director angles), or None.
        hessian: (N, N) CSC on the mesh's fixed pattern, or None.
    """

    energy: float
    parts: dict[str, float]
    gradient: F | None = None
    hessian: sp.csc_matrix | None = None


def _directors(shell: Shell, x: F, theta: F, order: int):
    """Every director (n_dir, 3) with its derivatives in ``(edge vector, angle)``."""
    mesh = shell.mesh
    edge = np.concatenate([np.arange(mesh.n_edges), mesh.crease_edges])
    t0, r0 = shell.edge_frames
    vec = x[mesh.edges[edge, 1]] - x[mesh.edges[edge, 0]]
    with np.errstate(divide="ignore", invalid="ignore"):
        return transported_director(t0[edge], r0[edge], vec, theta, order)


def second_fundamental_form(shell: Shell, q: F) -> F:
    """(m, 3) the faces' second fundamental forms ``(b11, b12, b22)`` at state ``q`` (m)."""
    mesh = shell.mesh
    x, theta = unpack(mesh, q)
    d = _directors(shell, x, theta, 0)[0]
    return director_slopes(x[mesh.triangles], d[mesh.face_directors], 0)[0] @ _B.T


def section_response(shell: Shell, q: F) -> SectionResponse:
    """The faces' J2 sections (``Shell.plasticity``) at state ``q``, from the
    state at the increment's start: stresses through the thickness and the
    internal variables after it (an increment's equilibrium moves them on)."""
    if shell.plasticity is None:
        raise InvalidParameterError("plasticity", "the shell has no J2 sections")
    mesh = shell.mesh
    x = unpack(mesh, q)[0]
    eps = (face_metric(x[mesh.triangles])[0] - shell.ref_metric) / 2
    r = second_fundamental_form(shell, q) - shell.rest_curvature
    lmap = shell.cartesian
    return shell.plasticity.respond(
        np.einsum("mij,mj->mi", lmap, eps), np.einsum("mij,mj->mi", lmap, r)
    )


#: Faces per chunk of the vectorised face terms: the (c, 12, 12) temporaries stay in
#: cache and their memory is reused (``benchmarks/bench_iteration.py --chunks``: 512
#: and 1024 the fastest on the coarse and normal meshes, 256 and 2048 up to 30 % slower).
CHUNK = 512


def _face_terms(shell: Shell, x: F, directors: tuple, faces: slice, order: int):
    """Membrane and bending of a run of faces: energies (J) and, with ``order``, the
    (c, 12) gradients and (c, 12, 12) Hessians over the faces' own unknowns."""
    mesh = shell.mesh
    d_all, dd_all, d2d_all = directors
    tri = mesh.triangles[faces]
    c = len(tri)
    xf = x[tri]
    area, kform = shell.ref_area[faces], shell.form[faces]
    a, da = face_metric(xf)
    eps = (a - shell.ref_metric[faces]) / 2
    fd = mesh.face_directors[faces]
    if order == 0:
        u = director_slopes(xf, d_all[fd], 0)[0]
    else:
        slopes = SlopeTerms(xf, d_all[fd])
        u = slopes.u
    b = u @ _B.T
    r = b - shell.rest_curvature[faces]
    if shell.plasticity is not None:
        law = _section_law(shell, faces, area, eps, r)
    else:
        law = _elastic_law(shell, faces, area, kform, eps, r)
    e_mem, e_bend, g_eps, g_r, h_blocks = law
    if order == 0:
        return e_mem, e_bend, None, None
    # u_i in the face's own variables y = (9 coordinates, 3 angles), via z = (9, d_i).
    du_z = slopes.du
    maps = shell.edge_maps[faces]
    dd_y = dd_all[fd] @ maps  # (c, 3, 3, 12): d d_i / d y
    du = (du_z[:, :, None, 9:] @ dd_y)[:, :, 0]
    du[:, :, :9] += du_z[:, :, :9]
    w_u = g_r @ _B  # dW/du
    g_face = np.einsum("mi,mij->mj", w_u, du)
    g_face[:, :9] += np.einsum("mi,mij->mj", g_eps / 2, da)  # d eps = da / 2
    if order == 1:
        return e_mem, e_bend, g_face, None
    h_ee, h_er, h_rr = h_blocks()
    jr = _B @ du  # d r / d y
    h_face = jr.transpose(0, 2, 1) @ h_rr @ jr
    h_face += _slope_curvature(slopes, w_u, du_z, dd_all[fd], d2d_all[fd], maps, dd_y)
    je = da / 2  # d eps / d x (c, 3, 9)
    h_face[:, :9, :9] += je.transpose(0, 2, 1) @ h_ee @ je + (
        (g_eps / 2) @ METRIC_HESSIAN.reshape(3, 81)
    ).reshape(c, 9, 9)
    if h_er is not None:
        cross = je.transpose(0, 2, 1) @ h_er @ jr  # (c, 9, 12)
        h_face[:, :9, :] += cross
        h_face[:, :, :9] += cross.transpose(0, 2, 1)
    return e_mem, e_bend, g_face, h_face


def _slope_curvature(slopes: SlopeTerms, w: F, du_z: F, dd: F, d2d: F, maps: F, dd_y: F) -> F:
    """``sum_i w_i d2u_i / dy2`` (c, 12, 12), ``u_i`` through ``z_i = (9
    coordinates, d_i)`` and ``d_i`` through its edge's (vector, angle)
    (``maps``): ``jz^T d2u_z jz`` with ``jz = [[I9, 0], [dd_y]]`` in blocks,
    plus ``sum_k du/dd_k d2(d_k)``, both over (vector, angle) before ``maps``."""
    c = len(w)
    hxx, hxd, hdd = slopes.hessian(w)
    out = np.zeros((c, 12, 12))
    out[:, :9, :9] = hxx
    # coordinates by d_i, carried to y: sum_i hxd_i dd_y_i
    cross = hxd.transpose(0, 2, 1, 3).reshape(c, 9, 9) @ dd_y.reshape(c, 9, 12)
    out[:, :9, :] += cross
    out[:, :, :9] += cross.transpose(0, 2, 1)
    # d_i by d_i and the directors' own curvature, per edge over (vector, angle)
    k = dd.transpose(0, 1, 3, 2) @ hdd @ dd  # (c, 3, 4, 4)
    wdu = (w[:, :, None] * du_z[:, :, 9:])[:, :, None, :]
    k += (wdu @ d2d.reshape(c, 3, 3, 16)).reshape(c, 3, 4, 4)
    out += maps.reshape(c, 12, 12).transpose(0, 2, 1) @ (k @ maps).reshape(c, 12, 12)
    return out


def _elastic_law(shell: Shell, faces: slice, area: F, kform: F, eps: F, r: F):
    """St Venant-Kirchhoff membrane and the bending law (elastic, or with the
    faces' accumulated plastic curvature ``plastic.moment``): the energies
    (J), their gradients in ``eps`` and ``r`` (c, 3) and a function of the
    Hessian blocks ``(d2/deps2, d2/deps dr or None, d2/dr2)``."""
    mat = shell.material
    keps = np.einsum("mij,mj->mi", kform, eps)
    cm = area * mat.membrane_stiffness / 2
    e_mem = float(np.sum(cm * np.einsum("mi,mi->m", eps, keps)))
    kr = np.einsum("mij,mj->mi", kform, r)
    stiff = area * mat.bending_stiffness / 2
    rkr = np.einsum("mi,mi->m", r, kr)
    e_face = stiff * rkr
    # dW/dr = coef K r; d2W/dr2 = coef K + extra (K r)(K r)^T (elastic: coef = Abar D, extra 0)
    coef = 2 * stiff
    extra = None
    if shell.accumulated is not None:
        s_tr = np.sqrt(np.maximum(rkr, 0.0))
        m_law, slope, work = moment(mat, s_tr, shell.accumulated[faces])
        with np.errstate(divide="ignore", invalid="ignore"):
            phi = np.where(s_tr > 0, m_law / s_tr, mat.bending_stiffness)
            psi = np.where(s_tr > 0, (slope - phi) / np.maximum(s_tr, 1e-300) ** 2, 0.0)
        e_face = area * work
        coef = area * phi
        extra = area * psi

    def blocks():
        h_rr = coef[:, None, None] * kform
        if extra is not None:
            h_rr = h_rr + extra[:, None, None] * np.einsum("mi,mj->mij", kr, kr)
        return 2 * cm[:, None, None] * kform, None, h_rr

    return e_mem, float(np.sum(e_face)), 2 * cm[:, None] * keps, coef[:, None] * kr, blocks


def _section_law(shell: Shell, faces: slice, area: F, eps: F, r: F):
    """Membrane and bending together as J2 sections (``Shell.plasticity``):
    the energies (J; the membrane's share ``N . eps_m / 2``, the rest
    bending), the gradients in ``eps`` and ``r`` (c, 3) and a function of the
    Hessian blocks, each ``L^T (section tangent) L`` times the face's area."""
    assert shell.plasticity is not None
    lmap = shell.cartesian[faces]
    em = np.einsum("mij,mj->mi", lmap, eps)
    kc = np.einsum("mij,mj->mi", lmap, r)
    resp = shell.plasticity.respond(em, kc, faces)
    total = area * resp.energy
    e_mem = float(np.sum(area * np.einsum("mi,mi->m", resp.force, em) / 2))
    g_eps = area[:, None] * np.einsum("mji,mj->mi", lmap, resp.force)
    g_r = area[:, None] * np.einsum("mji,mj->mi", lmap, resp.moment)

    def blocks():
        t = resp.tangent
        lt = lmap.transpose(0, 2, 1)
        scale = area[:, None, None]
        return (
            scale * (lt @ t[:, :3, :3] @ lmap),
            scale * (lt @ t[:, :3, 3:] @ lmap),
            scale * (lt @ t[:, 3:, 3:] @ lmap),
        )

    return e_mem, float(np.sum(total)) - e_mem, g_eps, g_r, blocks


def evaluate(shell: Shell, q: F, order: int = 2) -> Evaluation:
    """The energy (order 0), its gradient (1) and Hessian (2) at state ``q`` ((N,))."""
    mesh = shell.mesh
    x, theta = unpack(mesh, q)
    m = mesh.n_faces
    directors = _directors(shell, x, theta, order)
    e_mem = e_bend = 0.0
    g_face = np.empty((m, 12)) if order >= 1 else None
    h_face = np.empty((m, 12, 12)) if order >= 2 else None
    for start in range(0, m, CHUNK):
        run = slice(start, min(start + CHUNK, m))
        em, eb, g, h = _face_terms(shell, x, directors, run, order)
        e_mem, e_bend = e_mem + em, e_bend + eb
        if g_face is not None:
            g_face[run] = g
        if h_face is not None:
            h_face[run] = h

    # Crease hinges: the angle between the two sides' directors.
    kc = len(mesh.crease_edges)
    delta = theta[mesh.crease_edges] - theta[mesh.n_edges :] - shell.crease_angle
    ck = shell.crease_stiffness * shell.crease_length
    e_crease = float(np.sum(ck * delta**2 / 2))

    # Gravity.
    weight = -shell.node_mass[:, None] * shell.gravity[None, :]  # dE/dx, (n, 3)
    e_grav = float(np.sum(weight * x))
    e_load = 0.0 if shell.load is None else -float(shell.load @ q)
    parts = {"membrane": e_mem, "bending": e_bend, "crease": e_crease, "gravity": e_grav}
    if shell.load is not None:
        parts["load"] = e_load
    total = e_mem + e_bend + e_crease + e_grav + e_load
    if order == 0:
        return Evaluation(total, parts)
    assert g_face is not None
    pattern = pattern_of(mesh)
    g_crease = np.zeros((kc, 2))
    g_crease[:, 0], g_crease[:, 1] = ck * delta, -ck * delta
    gradient = pattern.vector(g_face, g_crease)
    gradient[: 3 * mesh.n_nodes] += weight.ravel()
    if shell.load is not None:
        gradient -= shell.load
    if order == 1:
        return Evaluation(total, parts, gradient)
    assert h_face is not None
    h_crease = ck[:, None, None] * np.array([[1.0, -1.0], [-1.0, 1.0]])
    return Evaluation(total, parts, gradient, pattern.matrix(h_face, h_crease))
