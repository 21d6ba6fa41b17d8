"""Where the thick sheet's sections change form along the arc: the kinks of
:mod:`~onefold_cad.geometry.body_mass`'s integrand.

A section of the exact model's solid at arc parameter phi (the ruling u, the
top normal n) is the slab r in [rho, r_out], s in [s0, s1], less what the
fold's plane of symmetry y = r u_y + s n_y = 0 cuts off. Its measure and
first moment are smooth in phi except where that cut's line passes a corner
of the slab (s = s0 or s1 at r = rho or r = r_out) or the sheet's edge
passes the hole (r_out = rho): there the closed forms change and the
integrand kinks, and a Gauss-Legendre panel across a kink converges only
algebraically (the rule of 16 points was off by up to 7e-10 of the volume on
the templates, all of it from the panel holding a kink). The rule's breaks
are put at the kinks instead: in the arc parameter for the exact model, in
the flat angle for the paper model's planar wedges (whose thick sheet the
same plane cuts). Angles in radians, lengths in the design unit.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.arc import ArcFrames
from onefold_cad.geometry.body import FoldedBody
from onefold_cad.geometry.cone import ExactCone
from onefold_cad.geometry.numeric import Array, cross3

__all__ = ["Section", "arc_section", "flat_section", "section_kinks"]

#: Points looked at inside a sector wider than 1/16 of its side's arc, so
#: that a kink inside a wide sector is bracketed (the graded sectors near the
#: crease ends are narrow enough without).
_LOOKS = 16


#: ``(t, lower) -> (u_y, n_y, r_out)`` at parameters ``t`` ``(k,)`` of the
#: +y side or the -y one: the ruling's and the top normal's y components and
#: the ray length there.
Section = Callable[[Array, NDArray[np.bool_]], tuple[Array, Array, Array]]


def arc_section(body: FoldedBody) -> Section:
    """The exact model's :data:`Section` in the arc parameter phi (the rule's
    own variable, :mod:`~onefold_cad.geometry.body_mass`)."""
    folded = body.folded
    cone = folded.solution.surface
    assert isinstance(cone, ExactCone)
    frames = ArcFrames(folded.solution.frame, folded.apex)

    def at(phi: Array, lower: NDArray[np.bool_]) -> tuple[Array, Array, Array]:
        theta = cone.theta_near(phi)
        u, _, n = frames.frames(phi)
        return u[:, 1], n[:, 1], folded.sheet.ray_lengths(np.where(lower, -theta, theta))

    return at


def flat_section(body: FoldedBody) -> Section:
    """Any surface's :data:`Section` in the flat angle theta (the paper
    model's planar wedges: their frames at theta)."""
    folded = body.folded
    surface = folded.solution.surface

    def at(theta: Array, lower: NDArray[np.bool_]) -> tuple[Array, Array, Array]:
        u, e = surface.frames(theta)
        n = cross3(u, e)
        return u[:, 1], n[:, 1], folded.sheet.ray_lengths(np.where(lower, -theta, theta))

    return at


def _corners(body: FoldedBody, section: Section, t: Array, lower: NDArray[np.bool_]) -> Array:
    """The five functions ``(5, k)`` whose zeros are the kinks, at parameters
    ``t`` of the +y side or the -y one (``lower``): rho u_y + s n_y and
    r_out u_y + s n_y for s = s0, s1 (the cut's line through a corner of
    the slab), and r_out - rho."""
    uy, ny, r_out = section(t, lower)
    s0, s1 = body.s_range
    rho = body.hole
    return np.stack(
        [rho * uy + s0 * ny, rho * uy + s1 * ny, r_out * uy + s0 * ny, r_out * uy + s1 * ny,
         r_out - rho]
    )  # fmt: skip


def _inverse_cubic(xs: Array, fs: Array) -> Array:
    """Per row, x at f = 0 of the cubic x(f) through four points ``(c, 4)``
    (Lagrange in f)."""
    out = np.zeros(len(xs))
    with np.errstate(divide="ignore", invalid="ignore"):
        for i in range(4):
            w = np.ones(len(xs))
            for j in range(4):
                if j != i:
                    w *= (0.0 - fs[:, j]) / (fs[:, i] - fs[:, j])
            out += w * xs[:, i]
    return out


def section_kinks(body: FoldedBody, section: Section, breaks: list[Array]) -> list[Array]:
    """Per side (+y, then -y), the parameters of ``section`` (:func:`arc_section`,
    :func:`flat_section`) strictly inside that side's
    sorted ``breaks`` ``(m,)`` at which the section's closed forms change
    (:func:`_corners`' zeros), to about 1e-12 of the arc; none for a sheet
    without thickness. A zero is found where one of the functions changes
    sign between neighbouring points looked at: the breaks, and
    :data:`_LOOKS` points inside each sector wider than 1/16 of its side.
    On the paper model a sign change across a division ray, where the
    wedges' normal jumps, is found too, within a refined step of the ray:
    one more break where the integrand is smooth on either side."""
    if body.s_range[1] <= body.s_range[0]:
        return [np.empty(0) for _ in breaks]
    looks, sides = [], []
    for side, b in enumerate(breaks):
        lo, hi = b[:-1], b[1:]
        wide = np.nonzero(hi - lo > (b[-1] - b[0]) / 16.0)[0]
        steps = np.arange(1, _LOOKS) / _LOOKS
        inner = (lo[wide, None] + (hi - lo)[wide, None] * steps).ravel()
        at = np.sort(np.concatenate([b, inner]))
        looks.append(at)
        sides.append(np.full(len(at), side == 1))
    phi, lower = np.concatenate(looks), np.concatenate(sides)
    values = _corners(body, section, phi, lower)
    # brackets: a sign change between neighbours of one side
    same = lower[1:] == lower[:-1]
    fun, left = np.nonzero((np.signbit(values[:, 1:]) != np.signbit(values[:, :-1])) & same)
    a, b = phi[left], phi[left + 1]
    side_of = lower[left]
    if not len(a):
        return [np.empty(0) for _ in breaks]
    # each bracket looked at again in _LOOKS steps (one evaluation for all):
    # the zero lies between two neighbours of that grid, and the inverse of
    # the cubic through the four grid points about it gives it to the
    # fourth power of the step (a step of 1e-3 of the arc: about 1e-13)
    t = np.linspace(0.0, 1.0, _LOOKS + 1)
    grid = a[:, None] + (b - a)[:, None] * t  # (c, _LOOKS + 1)
    k = np.arange(len(a))
    between = _corners(body, section, grid[:, 1:-1].ravel(), np.repeat(side_of, _LOOKS - 1))
    f = np.empty_like(grid)
    f[:, 0], f[:, -1] = values[fun, left], values[fun, left + 1]
    f[:, 1:-1] = between[np.repeat(fun, _LOOKS - 1), np.arange(between.shape[1])].reshape(
        len(a), _LOOKS - 1
    )
    change = np.argmax(np.signbit(f[:, 1:]) != np.signbit(f[:, :-1]), axis=1)
    first = np.clip(change - 1, 0, _LOOKS - 3)
    window = first[:, None] + np.arange(4)
    xs, fs = grid[k[:, None], window], f[k[:, None], window]
    roots = _inverse_cubic(xs, fs)
    lo_x, hi_x = grid[k, change], grid[k, change + 1]
    inside = (roots >= np.minimum(lo_x, hi_x)) & (roots <= np.maximum(lo_x, hi_x))
    # where the cubic leaves the grid step (F far from cubic there): its
    # secant
    f0, f1 = f[k, change], f[k, change + 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        secant = lo_x - f0 * (hi_x - lo_x) / (f1 - f0)
    roots = np.where(inside, roots, np.where(f1 != f0, secant, 0.5 * (lo_x + hi_x)))
    return [np.sort(roots[side_of == (side == 1)]) for side in range(len(breaks))]
