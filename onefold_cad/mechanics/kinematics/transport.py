"""Directors transported along their edges: a director's position as a function of
its edge vector and its angle, with gradient and Hessian.

Each edge carries a director, a unit vector normal to it: the reference director
``r0`` parallel-transported from the reference edge direction ``t0`` to the
current one, then turned about the edge by its angle. Vectorised over edges;
tests/mechanics/kinematics/test_transport.py checks every derivative against finite
differences.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["transported_director"]

F = NDArray[np.float64]


def _cross3(a: F, b: F) -> F:
    """``a x b`` of (3, k) arrays (components first)."""
    return np.stack(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


def _skew3(v: F) -> F:
    """(3, 3, k) cross-product matrices of (3, k) vectors (components first)."""
    z = np.zeros_like(v[0])
    return np.array([[z, -v[2], v[1]], [v[2], z, -v[0]], [-v[1], v[0], z]])


def _dot3(a: F, b: F) -> F:
    """(k,) dot products of (3, k) arrays."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def transported_director(
    t0: F, r0: F, e: F, theta: F, order: int = 2
) -> tuple[F, F | None, F | None]:
    """Directors ``d = cos(theta) r + sin(theta) t x r``, ``r`` the reference director ``r0``
    parallel-transported from the reference edge direction ``t0`` to ``t = e / |e|``.

    Args:
        t0, r0: (k, 3) unit reference edge directions and directors (``r0 . t0 = 0``).
        e: (k, 3) current edge vectors; theta: (k,) angles (rad) about ``t``.
        order: 0, 1 or 2.

    Returns:
        d: (k, 3); dd: (k, 3, 4) in ``(e, theta)``; d2d: (k, 3, 4, 4).

    The transport is ``r = r0 - alpha (t0 + t)``, ``alpha = (r0 . t) / (1 + t0 . t)``.
    Its derivatives in ``t`` (``a = d alpha / dt``, ``A = da / dt``) collapse to
    ``dd/dt = -alpha cos I - sin [alpha t + r]x - g a^T`` and
    ``d2d_i/dt2 = m_i a^T + a m_i^T - g_i A`` with ``g = cos (t0 + t) + sin t x t0`` and
    ``m_i`` the rows of ``-cos I + sin [t0]x``; ``t = e / |e|`` adds the projector
    ``P = I - t t^T`` on each side, ``/ |e|`` per derivative, and ``dd/dt`` times
    ``d2t/de2 = -(delta_ij t_k + delta_ik t_j + delta_jk t_i - 3 t_i t_j t_k) / |e|^2``.
    Computed components first, the edges along the fast axis (about half the time
    of forming the (k, 3, 3, 3) tensors of the plain chain rule).
    """
    k = len(e)
    ec = e.T
    length = np.sqrt(_dot3(ec, ec))
    t = ec / length
    t0c, r0c = t0.T, r0.T
    c = _dot3(t0c, t)
    # An edge turned back on its reference direction has no transport: NaN there.
    w = np.where(c > -1 + 1e-9, 1.0, np.nan) / np.maximum(1.0 + c, 1e-300)
    s = _dot3(r0c, t)
    alpha = s * w
    plus = t0c + t
    r = r0c - alpha * plus
    q = _cross3(t, r)
    cos, sin = np.cos(theta), np.sin(theta)
    d = cos * r + sin * q
    if order == 0:
        return d.T.copy(), None, None
    inv = 1 / length
    a = w * r0c - (s * w**2) * t0c  # d alpha / dt
    t_t0 = _cross3(t, t0c)
    g = cos * plus + sin * t_t0
    spin = alpha * t + r
    d_t = _skew3(-sin * spin)  # dd / dt
    d_t -= g[:, None] * a[None]
    d_t_theta = _skew3(-cos * spin)  # its derivative in theta
    d_t_theta -= (cos * t_t0 - sin * plus)[:, None] * a[None]
    for i in range(3):
        d_t[i, i] -= alpha * cos
        d_t_theta[i, i] += alpha * sin
    u = np.einsum("ijk,jk->ik", d_t, t)  # dd/dt t
    dd = np.empty((k, 3, 4))
    dd[:, :, :3] = ((d_t - u[:, None] * t[None]) * inv).transpose(2, 0, 1)
    dd[:, :, 3] = (cos * q - sin * r).T
    if order == 1:
        return d.T.copy(), dd, None
    mat = _skew3(sin * t0c)
    for i in range(3):
        mat[i, i] -= cos
    mp = mat - np.einsum("ijk,jk->ik", mat, t)[:, None] * t[None]  # m_i^T P
    rho, tau = r0c - s * t, t0c - c * t  # P r0, P t0
    pa = w * rho - (s * w**2) * tau  # P a
    pap = -(w**2) * (rho[:, None] * tau[None] + tau[:, None] * rho[None])  # P A P
    pap += (2 * s * w**3) * (tau[:, None] * tau[None])
    # P m_i a^T P + its transpose, and dd/dt d2t's -(d_t[i, j] t_l + t_j d_t[i, l])
    half = mp[:, :, None] * pa[None, None] - d_t[:, :, None] * t[None, None]
    hess = half + half.transpose(0, 2, 1, 3)
    hess -= g[:, None, None] * pap[None]
    hess += u[:, None, None] * (3 * (t[:, None] * t[None]))[None]  # and -u_i delta_jl:
    for j in range(3):
        hess[:, j, j] -= u
    hess *= inv**2
    d2d = np.empty((k, 3, 4, 4))
    d2d[:, :, :3, :3] = hess.transpose(3, 0, 1, 2)
    mixed = (d_t_theta - np.einsum("ijk,jk->ik", d_t_theta, t)[:, None] * t[None]) * inv
    d2d[:, :, :3, 3] = mixed.transpose(2, 0, 1)
    d2d[:, :, 3, :3] = d2d[:, :, :3, 3]
    d2d[:, :, 3, 3] = -d.T
    return d.T.copy(), dd, d2d
