"""The bending part of CalculiX's formed stresses, with its membrane part
taken out (pure numpy; SI units: m, Pa).

An isometric forming bends the sheet and stretches none of it, so the
stress at height z of a face is the bending stress alone, linear in z while
it is elastic. CalculiX's S6 following the cones stretches its own
mid-plane a little (the quadratic element's interpolation error,
``ccx_path.s6_membrane_strain``), and that membrane stress adds to the
bending stress at the surfaces: it widens the yielded area on a coarse mesh.

Here the two are told apart at each in-plane point from the levels that
are still elastic (no plastic strain): there the stress is the membrane
stress plus z times its slope, ``sigma(z) = a + z b``, fitted by least
squares over those levels (exact where they are elastic, as long as the
forming loaded them monotonically). ``b z`` is the stress of the
curvature alone, and ``a`` the membrane stress; where fewer than two levels
are elastic the point has yielded through most of its thickness and counts
as yielded.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from ccx_deck import GAUSS, level_fields, mises
from numpy.typing import NDArray

Array = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


def level_heights(t: float, layers: int) -> Array:
    """The ``2 layers`` Gauss heights (m) of a composite section of equal
    layers, bottom up (two points a layer at +-1/sqrt(3) of its half)."""
    h = t / layers
    return np.array(
        [-0.5 * t + h * (j + 0.5 + s * 0.5 * GAUSS) for j in range(layers) for s in (-1.0, 1.0)]
    )


@dataclass(frozen=True)
class Split:
    """Per element and in-plane point ``(m, 3)``: the membrane stress ``a``
    and the bending slope ``b`` (``(m, 3, 6)``: Pa and Pa/m, components xx,
    yy, zz, xy, xz, yz) of the elastic levels' fit ``a + z b``, and whether
    the point had two elastic levels to fit."""

    membrane: Array
    slope: Array
    fitted: BoolArray

    def bending_yielded(self, height: float, sy: float) -> BoolArray:
        """The points where the curvature alone would have yielded at
        ``height`` (m): von Mises of ``b height`` at or above ``sy`` (Pa);
        a point without a fit (yielded through its thickness) counts."""
        return ~self.fitted | (mises(self.slope * height) >= sy)

    def trial_yielded(self, height: float, sy: float) -> BoolArray:
        """As :meth:`bending_yielded` with the membrane stress added: the
        elastic trial stress ``a +- b height`` at either face."""
        up = mises(self.membrane + self.slope * height)
        down = mises(self.membrane - self.slope * height)
        return ~self.fitted | (np.maximum(up, down) >= sy)

    def membrane_at_edge(self, t: float, sy: float, band: float = 0.1) -> float:
        """The median von Mises membrane stress (Pa) at the points where the
        bending alone is within ``band`` of the yield stress at the surface
        (the edge of the yielded zone); NaN if there are none."""
        r = mises(self.slope * 0.5 * t) / sy
        at = self.fitted & (np.abs(r - 1.0) <= band)
        return float(np.median(mises(self.membrane)[at])) if at.any() else float("nan")


def split(sig: Array, peeq: Array, t: float) -> Split:
    """The fit of ``sig`` ``(m, levels, 3, 6)`` (levels bottom up, as
    ``ccx_deck.surface_state`` reads them) over the levels whose ``peeq``
    ``(m, levels, 3)`` is zero, at :func:`level_heights` of thickness ``t``."""
    levels = sig.shape[1]
    z = level_heights(t, levels // 2)[None, :, None]
    w = (peeq == 0).astype(float)  # (m, levels, 3)
    s0, s1, s2 = w.sum(1), (w * z).sum(1), (w * z * z).sum(1)
    t0 = (w[..., None] * sig).sum(1)
    t1 = (w[..., None] * z[..., None] * sig).sum(1)
    det = s0 * s2 - s1 * s1
    fitted = s0 >= 2  # two levels at two heights: det > 0
    safe = np.where(fitted, det, 1.0)[..., None]
    a = np.where(fitted[..., None], (s2[..., None] * t0 - s1[..., None] * t1) / safe, 0.0)
    b = np.where(fitted[..., None], (s0[..., None] * t1 - s1[..., None] * t0) / safe, 0.0)
    return Split(a, b, fitted)


def formed_split(blocks: dict, when: float, layers: int, t: float, n_elem: int) -> Split:
    """:func:`split` of the stresses and plastic strains ``ccx_deck.read_dat``
    read at total time ``when``."""
    sig, peeq = level_fields(blocks, when, layers, n_elem)
    return split(sig, peeq, t)
