"""Small geometric functions of a triangle, an edge or a director, with gradients
and Hessians.

Vectorised over elements. A face's 9 local variables are its vertices'
coordinates ``(x0, x1, x2)`` (3 each, in that order); an edge's 12 are
``(a, b, c, d)``: the edge ``a -> b`` as it runs in its first face ``T0 = (a, b, c)``,
and ``d`` the vertex opposite it in ``T1 = (b, a, d)``; a director's 4 are its
edge vector and its angle. Derivations are in docs/mechanics.md;
tests/mechanics/kinematics/test_triangles.py checks every derivative against finite
differences.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "METRIC_HESSIAN",
    "SlopeTerms",
    "area_hessian",
    "area_jacobian",
    "dihedral",
    "director_slopes",
    "face_heights",
    "face_metric",
    "skew",
]

F = NDArray[np.float64]
_I3 = np.eye(3)


def skew(v: F) -> F:
    """Cross-product matrices: ``skew(v) @ w == cross(v, w)``; (..., 3) -> (..., 3, 3)."""
    out = np.zeros(v.shape[:-1] + (3, 3))
    x, y, w = v[..., 0], v[..., 1], v[..., 2]
    out[..., 0, 2], out[..., 1, 0], out[..., 2, 1] = y, w, x
    np.negative(w, out=out[..., 0, 1])
    np.negative(x, out=out[..., 1, 2])
    np.negative(y, out=out[..., 2, 0])
    return out


def _metric_hessian() -> F:
    """(3, 9, 9): Hessians of ``(e1.e1, e1.e2, e2.e2)``, ``e1 = x1 - x0``, ``e2 = x2 - x0``."""
    s1 = np.zeros((3, 9))
    s2 = np.zeros((3, 9))
    s1[:, 0:3], s1[:, 3:6] = -_I3, _I3
    s2[:, 0:3], s2[:, 6:9] = -_I3, _I3
    return np.stack([2 * s1.T @ s1, s1.T @ s2 + s2.T @ s1, 2 * s2.T @ s2])


#: Constant Hessians of the metric components with respect to the 9 coordinates.
METRIC_HESSIAN = _metric_hessian()


def _slope_patterns() -> tuple[F, F, F]:
    """Constant pieces of the Hessians in ``director_slopes`` over ``(x0, x1, x2, d_i)``:
    ``A = d_i . (x_i - x_{i+1})`` has Hessians ``d2A_i`` coupling the coordinates
    with ``d_i`` only, (3, 9, 3) those blocks; ``B = d_i . N`` has ``d2B_i = sum_c
    d_ic P1[c] + sum_(v, c) E_vc P2[v, c]`` (E_v the edge vectors): P1's blocks
    over the coordinates (3, 81), P2's coupling them with ``d_i`` (9, 27). Every
    block that couples the coordinates with ``d_i`` has its mirror image."""
    d2a = np.zeros((3, 9, 3))
    for i in range(3):
        for v, sign in ((i, 1.0), ((i + 1) % 3, -1.0)):
            d2a[i, 3 * v : 3 * v + 3] += sign * _I3
    basis = skew(_I3)  # [e_c]x
    p1 = np.zeros((3, 9, 9))
    p2 = np.zeros((3, 3, 9, 3))
    for v in range(3):
        nxt, prv = 3 * ((v + 2) % 3), 3 * ((v + 1) % 3)
        p1[:, 3 * v : 3 * v + 3, nxt : nxt + 3] += basis
        p1[:, 3 * v : 3 * v + 3, prv : prv + 3] -= basis
        p2[v, :, 3 * v : 3 * v + 3] -= basis
    return d2a, p1.reshape(3, 81), p2.reshape(9, 27)


_SLOPE_PATTERNS = _slope_patterns()


def face_metric(x: F) -> tuple[F, F]:
    """The metric ``(a11, a12, a22)`` of ``x(u, v) = x0 + u e1 + v e2`` and its gradient.

    Args:
        x: (m, 3, 3) vertex positions.

    Returns:
        a: (m, 3); da: (m, 3, 9). The Hessian is ``METRIC_HESSIAN`` (constant).
    """
    e1, e2 = x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]
    a = np.stack(
        [
            np.einsum("ij,ij->i", e1, e1),
            np.einsum("ij,ij->i", e1, e2),
            np.einsum("ij,ij->i", e2, e2),
        ],
        axis=1,
    )
    da = np.zeros((len(x), 3, 9))
    da[:, 0, 0:3], da[:, 0, 3:6] = -2 * e1, 2 * e1
    da[:, 1, 0:3], da[:, 1, 3:6], da[:, 1, 6:9] = -(e1 + e2), e2, e1
    da[:, 2, 0:3], da[:, 2, 6:9] = -2 * e2, 2 * e2
    return a, da


def area_jacobian(edge: F) -> F:
    """``(m, 3, 9)`` ``dN / dx_i = [E_i]x``: the area vector ``N = (x1 - x0) x (x2 - x0)``
    by the vertices, from the edges ``(m, 3, 3)`` (edge i opposite vertex i)."""
    return skew(edge).transpose(0, 2, 1, 3).reshape(len(edge), 3, 9)


def _area_blocks(dn: F, normal: F) -> F:
    """``(m, 9, 9)`` ``dN^T dN + sum_k N_k d2N_k``: ``dN`` :func:`area_jacobian`,
    ``d2N``'s constant pattern P1 of ``_slope_patterns``."""
    return dn.transpose(0, 2, 1) @ dn + (normal @ _SLOPE_PATTERNS[1]).reshape(len(dn), 9, 9)


def area_hessian(dn: F, normal: F, nn: F, df: F, weight: F) -> F:
    """``(m, 9, 9)`` ``weight`` ``(m,)`` times the Hessian of ``M = |N|`` (``dn`` from
    :func:`area_jacobian`, ``nn = |N|^2``, ``df`` ``(m, 9)`` the gradient of ``ln M``):
    ``M (d2F + dF dF^T) = (dN^T dN + sum_k N_k d2N_k) / M - M dF dF^T``."""
    c = weight * np.sqrt(nn)
    out = _area_blocks(dn, normal) * (c / nn)[:, None, None]
    out -= (c[:, None] * df)[:, :, None] * df[:, None, :]
    return out


def face_heights(x: F, order: int = 2) -> tuple[F, F | None, F | None]:
    """Heights ``h_i = 2 A / l_i`` of the vertices over the opposite edges.

    Args:
        x: (m, 3, 3) vertex positions.
        order: 0 (values), 1 (and gradients) or 2 (and Hessians).

    Returns:
        h: (m, 3); dh: (m, 3, 9); d2h: (m, 3, 9, 9).
    """
    m = len(x)
    edge = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], axis=1)
    normal = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    nn = np.einsum("ij,ij->i", normal, normal)
    ll = np.einsum("ijk,ijk->ij", edge, edge)
    h = np.sqrt(nn[:, None] / ll)
    if order == 0:
        return h, None, None
    # F = ln|N|, G_i = ln l_i; h_i = exp(F - G_i).
    dfx = np.cross(normal[:, None, :], edge) / nn[:, None, None]  # (m, 3 vertices, 3)
    df = dfx.reshape(m, 9)
    dg = np.zeros((m, 3, 9))
    for i in range(3):
        j, k = (i + 2) % 3, (i + 1) % 3
        dg[:, i, 3 * j : 3 * j + 3] = edge[:, i] / ll[:, i, None]
        dg[:, i, 3 * k : 3 * k + 3] = -edge[:, i] / ll[:, i, None]
    dlog = df[:, None, :] - dg
    dh = h[:, :, None] * dlog
    if order == 1:
        return h, dh, None
    d2f = _area_blocks(area_jacobian(edge), normal) / nn[:, None, None]
    d2f -= 2 * df[:, :, None] * df[:, None, :]
    d2h = np.broadcast_to(d2f[:, None], (m, 3, 9, 9)).copy()
    d2h += dlog[:, :, :, None] * dlog[:, :, None, :]
    unit = edge / np.sqrt(ll)[:, :, None]
    mm = (_I3 - 2 * unit[:, :, :, None] * unit[:, :, None, :]) / ll[:, :, None, None]
    for i in range(3):
        j, k = 3 * ((i + 2) % 3), 3 * ((i + 1) % 3)
        d2h[:, i, j : j + 3, j : j + 3] -= mm[:, i]
        d2h[:, i, k : k + 3, k : k + 3] -= mm[:, i]
        d2h[:, i, j : j + 3, k : k + 3] += mm[:, i]
        d2h[:, i, k : k + 3, j : j + 3] += mm[:, i]
    d2h *= h[:, :, None, None]
    return h, dh, d2h


def dihedral(x: F, order: int = 2) -> tuple[F, F | None, F | None]:
    """The signed bending angle of edges: 0 flat, > 0 where the two faces form a bowl
    (concave towards their normals).

    Args:
        x: (k, 4, 3) the positions of ``(a, b, c, d)``.
        order: 0, 1 or 2.

    Returns:
        psi: (k,) rad in (-pi, pi); dpsi: (k, 12); d2psi: (k, 12, 12).
    """
    a, b, c, d = x[:, 0], x[:, 1], x[:, 2], x[:, 3]
    e = b - a
    n0 = np.cross(e, c - a)  # T0 = (a, b, c)
    n1 = np.cross(a - b, d - b)  # T1 = (b, a, d)
    ee = np.einsum("ij,ij->i", e, e)
    le = np.sqrt(ee)
    sin = np.einsum("ij,ij->i", np.cross(n1, n0), e) / le
    psi = np.arctan2(sin, np.einsum("ij,ij->i", n0, n1))
    if order == 0:
        return psi, None, None
    k = len(x)
    nn0 = np.einsum("ij,ij->i", n0, n0)
    nn1 = np.einsum("ij,ij->i", n1, n1)
    v0 = le[:, None] * n0 / nn0[:, None]  # n0 / h0
    v1 = le[:, None] * n1 / nn1[:, None]
    s0 = np.einsum("ij,ij->i", c - a, e) / ee  # foot of c on a -> b
    s1 = np.einsum("ij,ij->i", d - a, e) / ee
    grad = np.zeros((k, 4, 3))
    grad[:, 0] = -(1 - s0)[:, None] * v0 - (1 - s1)[:, None] * v1
    grad[:, 1] = -s0[:, None] * v0 - s1[:, None] * v1
    grad[:, 2] = v0
    grad[:, 3] = v1
    dpsi = grad.reshape(k, 12)
    if order == 1:
        return psi, dpsi, None
    unit = e / le[:, None]
    dv0 = _dv(le, n0, nn0, unit, [(0, skew(c - b)), (1, skew(a - c)), (2, skew(e))])
    dv1 = _dv(le, n1, nn1, unit, [(1, skew(d - a)), (0, skew(b - d)), (3, skew(a - b))])
    ds0 = _ds(e, ee, c - a, s0, 2)
    ds1 = _ds(e, ee, d - a, s1, 3)
    hess = np.zeros((k, 4, 3, 12))
    hess[:, 2] = dv0
    hess[:, 3] = dv1
    hess[:, 0] = (
        -(1 - s0)[:, None, None] * dv0
        + v0[:, :, None] * ds0[:, None, :]
        - (1 - s1)[:, None, None] * dv1
        + v1[:, :, None] * ds1[:, None, :]
    )
    hess[:, 1] = (
        -s0[:, None, None] * dv0
        - v0[:, :, None] * ds0[:, None, :]
        - s1[:, None, None] * dv1
        - v1[:, :, None] * ds1[:, None, :]
    )
    d2psi = hess.reshape(k, 12, 12)
    return psi, dpsi, 0.5 * (d2psi + d2psi.transpose(0, 2, 1))


def _dv(le: F, n: F, nn: F, unit: F, dn_blocks: list[tuple[int, F]]) -> F:
    """(k, 3, 12) Jacobian of ``v = |e| N / |N|^2`` (``e = b - a``)."""
    k = len(n)
    nhat = n / np.sqrt(nn)[:, None]
    proj = (_I3 - 2 * nhat[:, :, None] * nhat[:, None, :]) * (le / nn)[:, None, None]
    out = np.zeros((k, 3, 12))
    for slot, block in dn_blocks:
        out[:, :, 3 * slot : 3 * slot + 3] += proj @ block
    pe = (n / nn[:, None])[:, :, None] * unit[:, None, :]
    out[:, :, 0:3] -= pe
    out[:, :, 3:6] += pe
    return out


def _ds(e: F, ee: F, f: F, s: F, slot: int) -> F:
    """(k, 12) gradient of ``s = f.e / |e|^2`` with ``f = (vertex at slot) - a``."""
    out = np.zeros((len(e), 12))
    out[:, 0:3] = (-e - f + 2 * s[:, None] * e) / ee[:, None]
    out[:, 3:6] = (f - 2 * s[:, None] * e) / ee[:, None]
    out[:, 3 * slot : 3 * slot + 3] = e / ee[:, None]
    return out


def director_slopes(x: F, d: F, order: int = 2) -> tuple[F, F | None, F | None]:
    """``u_i = h_i tan(phi_i) = |N| (d_i . (x_i - x_{i+1})) / (d_i . N)``: a face's
    height over edge i times the slope of its director ``d_i`` there.

    Args:
        x: (m, 3, 3) vertex positions; d: (m, 3, 3) the directors of edges 0, 1, 2
            (each normal to its edge).

    Returns:
        u: (m, 3); du: (m, 3, 12) and d2u: (m, 3, 12, 12) in ``(x0, x1, x2, d_i)``.
        (:class:`SlopeTerms` gives ``sum_i w_i d2u_i`` without the (m, 3, 12, 12).)
    """
    if order == 0:
        return _slope_values(x, d)[-1], None, None
    terms = SlopeTerms(x, d)
    if order == 1:
        return terms.u, terms.du, None
    m = len(x)
    d2u = np.zeros((m, 3, 12, 12))
    _, hxd, hdd = terms.hessian(np.ones((m, 3)))
    for i in range(3):
        d2u[:, i, :9, :9] = terms.hessian(np.eye(3)[i][None, :].repeat(m, 0))[0]
    d2u[:, :, :9, 9:] = hxd
    d2u[:, :, 9:, :9] = hxd.transpose(0, 1, 3, 2)
    d2u[:, :, 9:, 9:] = hdd
    return terms.u, terms.du, d2u


def _slope_values(x: F, d: F) -> tuple[F, F, F, F, F, F, F, F]:
    """``director_slopes``' values: edges, normal, ``|N|^2``, ``|N|``, ``x_i -
    x_{i+1}``, ``A_i``, ``B_i`` and ``u``."""
    edge = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], axis=1)
    normal = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    nn = np.einsum("ij,ij->i", normal, normal)
    norm = np.sqrt(nn)
    f = x - x[:, [1, 2, 0]]  # x_i - x_{i+1}
    num = np.einsum("mij,mij->mi", d, f)
    den = np.einsum("mij,mj->mi", d, normal)
    return edge, normal, nn, norm, f, num, den, norm[:, None] * num / den


class SlopeTerms:
    """:func:`director_slopes` to first order, and its Hessians contracted
    with weights per edge (:meth:`hessian`) without the (m, 3, 12, 12) blocks.

    Args:
        x: (m, 3, 3) vertex positions; d: (m, 3, 3) the edges' directors.

    Attributes:
        u: (m, 3); du: (m, 3, 12) in ``(x0, x1, x2, d_i)``.
    """

    def __init__(self, x: F, d: F) -> None:
        m = len(x)
        edge, normal, nn, norm, f, num, den, u = _slope_values(x, d)
        # |N| = M: dM = M dF (F = ln|N|), d2M = M (d2F + dF dF^T).
        dn = area_jacobian(edge)
        df = (normal[:, None, :] @ dn)[:, 0] / nn[:, None]  # N^T dN / |N|^2
        dm = norm[:, None] * df
        da = np.zeros((m, 3, 12))
        db = np.zeros((m, 3, 12))
        for i in range(3):
            j = (i + 1) % 3
            da[:, i, 3 * i : 3 * i + 3] += d[:, i]
            da[:, i, 3 * j : 3 * j + 3] -= d[:, i]
            da[:, i, 9:] = f[:, i]
        db[:, :, :9] = d @ dn  # d_i x E_j over vertex j
        db[:, :, 9:] = normal[:, None, :]
        g = norm[:, None] / den  # G = M / B
        dg = -(norm[:, None] / den**2)[:, :, None] * db
        dg[:, :, :9] += dm[:, None, :] / den[:, :, None]
        self.u: F = u
        self.du: F = g[:, :, None] * da + num[:, :, None] * dg
        self._x = (edge, normal, nn, norm, num, den, d, df, dn)
        self._v = (da, dg, dm, db, g)

    def hessian(self, w: F) -> tuple[F, F, F]:
        """``sum_i w_i d2u_i`` ((m, 3) weights) in blocks: over the coordinates
        (m, 9, 9) (summed), coordinates by ``d_i`` (m, 3, 9, 3) and ``d_i`` by
        ``d_i`` (m, 3, 3, 3) (each edge's own, times ``w_i``)."""
        edge, normal, nn, norm, num, den, d, df, dn = self._x
        da, dg, dm, db, g = self._v
        m = len(w)
        # u = A G, G = M / B: d2u = G d2A - (A M / B^2) d2B + (A / B) d2M
        #   + dA dG^T + dG dA^T - (A / B^2)(dM dB^T + dB dM^T) + (2 A M / B^3) dB dB^T.
        ab2 = num / den**2
        # The dense part as V^T C V, V = (dA, dG, dM, dB), weighted per edge.
        v = np.zeros((m, 3, 4, 12))
        v[:, :, 0], v[:, :, 1], v[:, :, 3] = da, dg, db
        v[:, :, 2, :9] = dm[:, None, :]
        c = np.zeros((m, 3, 4, 4))
        c[:, :, 0, 1] = c[:, :, 1, 0] = w
        c[:, :, 2, 3] = c[:, :, 3, 2] = -w * ab2
        c[:, :, 3, 3] = 2 * w * ab2 * norm[:, None] / den
        cv = c @ v  # (m, 3, 4, 12)
        vx = v[..., :9]
        hxx = vx.reshape(m, 12, 9).transpose(0, 2, 1) @ cv[..., :9].reshape(m, 12, 9)
        hxd = vx.transpose(0, 1, 3, 2) @ cv[..., 9:]
        hdd = v[..., 9:].transpose(0, 1, 3, 2) @ cv[..., 9:]
        # + (A / B) d2M over the coordinates
        hxx += area_hessian(dn, normal, nn, df, np.einsum("mi,mi->m", w, num / den))
        # The constant-pattern parts: G d2A - (A M / B^2) d2B; d2A and the d_i part of
        # d2B couple the coordinates with d_i, d2B's x part the coordinates alone.
        d2a, p1, p2 = _SLOPE_PATTERNS
        coef = w * ab2 * norm[:, None]
        hxx -= ((coef[:, None, :] @ d)[:, 0] @ p1).reshape(m, 9, 9)
        p2e = (edge.reshape(m, 9) @ p2).reshape(m, 1, 9, 3)
        hxd += (w * g)[:, :, None, None] * d2a - coef[:, :, None, None] * p2e
        return hxx, hxd, hdd
