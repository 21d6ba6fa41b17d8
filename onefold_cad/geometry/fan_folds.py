"""The paper model's ruling folds: the signed fold angle along each ruling of a fan.

The paper model's surface is a fan of planar triangles about the apex, one
per division of the frame curve. Two neighbouring triangles meet along a
division ray at a dihedral angle: that ruling is a real fold, like the
crease, only a small one. A ruling through a polygon vertex that is not a
division ray runs inside one planar triangle and is no fold. The exact
model's cone is smooth: it bends along its rulings without folding, so it
has no ruling folds.

One source for every writer: the DXF and the bend sheet draw and list the
ruling folds from :func:`ruling_folds`; the FOLD file assigns its edges with
:func:`signed_fold_angles` and :func:`on_division_rays`. Numpy only. Angles
in degrees, valley (UP: the two sides turn towards the flat sheet's top,
+z) positive; points in the fold frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.geometry.fan import PaperFan
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.numeric import Array

__all__ = ["RulingFold", "on_division_rays", "ring_angles", "ruling_folds", "signed_fold_angles"]

#: Rays closer than this (radians) are one ruling (as in folding.fold's merge).
SAME_RAY = 1e-12


@dataclass(frozen=True)
class RulingFold:
    """One ruling of the paper model's fan that is a fold between two planar triangles.

    Attributes:
        name: '+y ruling k' (the k-th ruling fold counter-clockwise from the
            +x crease half) or '-y ruling k' (the k-th counter-clockwise from
            the -x crease half), k = 1, 2, ...
        end_flat: ``(2,)`` the ruling's end on the flat sheet's outline (fold
            frame; the ruling runs from H to it).
        angle_deg: the fold angle from flat (deg, >= 0): the angle between the
            two triangles' top normals.
        bend: 'UP' (the triangles turn towards the top face: a valley seen
            from +z) or 'DOWN'.
    """

    name: str
    end_flat: Array
    angle_deg: float
    bend: str


def signed_fold_angles(apex: Array, ring: Array) -> Array:
    """Fold angle (deg, valley positive) along each ruling apex -> ring[i] of
    the closed fan of triangles (apex, ring[i], ring[i + 1]).

    The triangle (apex, ring[i], ring[i + 1]) lies left of the ruling i, seen
    from its top side, and (apex, ring[i - 1], ring[i]) right of it; a valley
    turns their top normals towards each other, so (n_left x n_right) points
    against the ruling's direction.

    Args:
        apex: ``(3,)`` the fan's apex.
        ring: ``(n, 3)`` the rulings' far ends, counter-clockwise seen from
            the top side.
    """
    rel = ring - apex
    normals = np.cross(rel, np.roll(rel, -1, axis=0))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    left, right = normals, np.roll(normals, 1, axis=0)
    axis = rel / np.linalg.norm(rel, axis=1, keepdims=True)
    sin = -np.einsum("ij,ij->i", np.cross(left, right), axis)
    cos = np.einsum("ij,ij->i", left, right)
    return np.degrees(np.arctan2(sin, cos))


def ring_angles(fan: FoldedSheet) -> tuple[Array, int]:
    """The flat angles theta (radians) of a paper fan's ruling ends in the
    order of :attr:`FoldedSheet.boundary_3d` (counter-clockwise from the +x
    crease end: the +y side's, then the -y side's back) and the ring index of
    the -x crease end."""
    up, lo = fan.ruling_angles
    return np.concatenate((up, lo[-2:0:-1])), len(up) - 1


def on_division_rays(theta: Array, fan: FoldedSheet) -> NDArray[np.bool_]:
    """Whether each ruling angle ``theta`` (radians) is one of the paper fan's
    division rays (a fold between two planar triangles) rather than a ray
    inside one triangle."""
    surface = fan.solution.surface
    if not isinstance(surface, PaperFan) or surface.thetas is None:
        raise TypeError("on_division_rays needs a paper-model fold")
    divisions = np.minimum(surface.thetas, math.pi)
    k = np.clip(divisions.searchsorted(theta), 1, len(divisions) - 1)
    near = np.minimum(np.abs(divisions[k] - theta), np.abs(divisions[k - 1] - theta))
    return near <= SAME_RAY


def ruling_folds(folded: FoldedSheet) -> tuple[RulingFold, ...]:
    """The ruling folds of a paper-model fold (empty for the exact model),
    counter-clockwise from the +x crease half; the two crease halves are not
    among them (see :attr:`FoldedSheet.crease`)."""
    if not isinstance(folded.solution.surface, PaperFan):
        return ()
    theta, minus_x = ring_angles(folded)
    angle = signed_fold_angles(folded.apex, folded.boundary_3d)
    fold = on_division_rays(theta, folded)
    fold &= angle != 0.0  # two coplanar triangles: no fold
    fold[0] = fold[minus_x] = False  # the crease halves
    ends = folded.boundary_flat
    out = []
    counts = {"+y": 0, "-y": 0}
    for i in np.flatnonzero(fold):
        side = "+y" if i < minus_x else "-y"
        counts[side] += 1
        a = float(angle[i])
        out.append(RulingFold(f"{side} ruling {counts[side]}", ends[i].copy(), abs(a),
                              "UP" if a > 0.0 else "DOWN"))  # fmt: skip
    return tuple(out)
