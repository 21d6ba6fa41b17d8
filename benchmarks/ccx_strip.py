"""The strip check of the CalculiX forming benchmark (``calculix_forming.py
strip``): a wide plate bent to a cylinder by driving every node along the
isometric cylinders, released on three centre-line nodes in the same ccx run,
its springback against Gardiner's in plane strain."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from ccx_deck import Array, Deck, displacements, form_and_release, quadratic, support_321


def gardiner(x: float) -> float:
    """R_formed / R_released for a rectangular section in uniaxial bending,
    elastic-perfectly plastic (Gardiner 1957), x = R sigma_y / (E t)."""
    return 4.0 * x**3 - 3.0 * x + 1.0


def _circle_radius(p: Array) -> float:
    """Least-squares circle through points ``(k, 2)`` (Kasa's fit)."""
    a = np.column_stack([2 * p[:, 0], 2 * p[:, 1], np.ones(len(p))])
    b = (p**2).sum(axis=1)
    cx, cy, c = np.linalg.lstsq(a, b, rcond=None)[0]
    return float(math.sqrt(c + cx * cx + cy * cy))


def strip(x: float, *, direct: bool, layers: int, workdir: Path, t: float = 1e-3) -> dict[str, Any]:
    """A wide strip (E 200 GPa, nu 0.3, t 1 mm, width 0.2 m, R = 1 m, so
    width^2 / (R t) = 40: a plate in cylindrical bending; sigma_y = x E t / R)
    bent through 30 degrees to radius R with every node driven along the
    isometric cylinders of curvature s / R, released on three centre-line
    nodes; the radii fitted to the centre line's nodes of its central half.
    Gardiner's ratio for plane strain lies between the values with
    E' = E / (1 - nu^2) and sigma_y / sqrt(1 - nu + nu^2) (first yield) or
    2 sigma_y / sqrt(3) (fully plastic) in place of sigma_y."""
    E, nu, R, b = 200e9, 0.3, 1.0, 0.2
    sy = x * E * t / R
    L = math.pi / 6.0 * R
    nx, ny = 20, 4
    xs = np.linspace(-0.5 * L, 0.5 * L, nx + 1)
    ys = np.linspace(-0.5 * b, 0.5 * b, ny + 1)
    grid = np.array([[xx, yy] for yy in ys for xx in xs])
    tris = []
    for r in range(ny):
        for c in range(nx):
            a0, a1 = r * (nx + 1) + c, r * (nx + 1) + c + 1
            b0, b1 = a0 + nx + 1, a1 + nx + 1
            tris += [[a0, a1, b1], [a0, b1, b0]]
    flat, tri6 = quadratic(grid, np.array(tris))
    driven = np.arange(len(flat))
    s = np.linspace(0.05, 1.0, 20)
    X = flat[:, 0]
    u = np.zeros((len(s), len(driven), 3))
    for k, sk in enumerate(s):
        kap = sk / R
        u[k, :, 0] = np.sin(kap * X) / kap - X
        u[k, :, 2] = (1 - np.cos(kap * X)) / kap
    x0 = np.column_stack([flat, np.zeros(len(flat))])
    centre = np.flatnonzero(np.abs(flat[:, 1]) < 1e-12 * b)
    centre = centre[np.argsort(flat[centre, 0])]
    a, c, bb = centre[len(centre) // 2], centre[len(centre) // 4], centre[-1]
    support = support_321(x0 + u[-1], [int(a), int(bb), int(c)])
    deck = Deck(x0, tri6, s, u, driven, t, E, nu, sy, layers, support=support, direct=direct)
    deck.form_inc = 0.05
    name = f"strip_x{x:g}" + ("_direct" if direct else "")
    res = form_and_release(deck, workdir, name, release=True)
    xf = x0 + displacements(res["form"], 1.0, len(x0))
    xr = x0 + displacements(res["release"], 2.0, len(x0))
    # the central half: the ends' boundary layer (M = 0 at a free end after
    # the release) bends back differently; the whole length beside it
    mid = centre[np.abs(flat[centre, 0]) <= 0.25 * L + 1e-12]
    r_form = _circle_radius(xf[mid][:, [0, 2]])
    r_rel = _circle_radius(xr[mid][:, [0, 2]])
    full = _circle_radius(xf[centre][:, [0, 2]]) / _circle_radius(xr[centre][:, [0, 2]])
    e_plate = E / (1 - nu * nu)
    lo = gardiner(R * sy / math.sqrt(1 - nu + nu * nu) / (e_plate * t))
    hi = gardiner(R * 2 * sy / math.sqrt(3) / (e_plate * t))
    ratio = r_form / r_rel
    return {
        "x": x,
        "direct": direct,
        "R_m": R,
        "R_formed_m": r_form,
        "R_released_m": r_rel,
        "ratio": ratio,
        "ratio_whole_length": full,
        "gardiner_uniaxial": gardiner(x),
        "gardiner_plane_strain": sorted([lo, hi]),
        "within": min(lo, hi) <= ratio <= max(lo, hi),
        "wall_s": res["wall_form_s"] + res["wall_release_s"],
    }
