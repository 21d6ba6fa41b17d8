"""The bend model by hand, for the tests: from its definitions, never from
:mod:`onefold_cad.geometry.bend_model`.

Definitions used (docs/fabrication.md, material.py, folding.py):
- the reference surface ``INSIDE`` is the flat sheet's top face (the material
  lies below it), ``OUTSIDE`` its bottom face, ``MID`` the mid-surface;
- a crease half bent ``UP`` ends with the top face inside the bend, ``DOWN``
  with the bottom face inside.
"""

from __future__ import annotations

import math

import numpy as np

#: the faces' offsets from the reference surface along the top normal, per unit thickness
FACES = {"INSIDE": (-1.0, 0.0), "OUTSIDE": (0.0, 1.0), "MID": (-0.5, 0.5)}

#: s, the reference surface's distance from the bend's inside face in thicknesses, by
#: (reference surface, bend direction): INSIDE is the top face, which UP puts inside.
S_TABLE = {
    ("INSIDE", "UP"): 0.0,
    ("INSIDE", "DOWN"): 1.0,
    ("OUTSIDE", "UP"): 1.0,
    ("OUTSIDE", "DOWN"): 0.0,
    ("MID", "UP"): 0.5,
    ("MID", "DOWN"): 0.5,
}


def hand_bend(psi_deg: float, bend: str, surface: str, t: float, r: float, k: float) -> dict:
    """SB, BA, BD and the shift of one bend, from the textbook formulas."""
    psi = math.radians(psi_deg)
    s = S_TABLE[(surface, bend)]
    sb = (r + s * t) * math.tan(psi / 2.0)
    ba = psi * (r + k * t)
    return {"s": s, "sb": sb, "ba": ba, "bd": 2.0 * sb - ba, "shift": sb - ba / 2.0}


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def neutral_length(
    psi_deg: float, bend: str, surface: str, t: float, r: float, k: float, l1: float, l2: float
) -> float:
    """The neutral line's length across one bend, measured on a 2D cross-section.

    The cross-section is built as geometry, without any set-back formula: the
    reference surface's two flanges run from the sharp crease O along d1, d2
    (lengths l1, l2, included angle 180 - psi, bent towards the top face for
    UP); the sheet's faces are offset along each flange's top normal by
    FACES[surface] x t; the inside face is the one on the concave side; the
    inside arc (radius r) is tangent to both inside-face lines; the neutral
    line runs K t outside the inside face, as a flat piece from each flange's
    cut edge (perpendicular to the sheet at the reference flange's end) to its
    tangent point, and an arc of radius r + K t between the tangent points.
    """
    half = math.radians(psi_deg) / 2.0
    up = 1.0 if bend == "UP" else -1.0
    # flange 1 is the +y side, rotated by +psi/2 (UP: towards +w, the top side)
    d1 = np.array([math.cos(half), up * math.sin(half)])
    d2 = np.array([-math.cos(half), up * math.sin(half)])
    # top normals: the flat sheet's +w rotated with each flange
    n1 = np.array([-up * math.sin(half), math.cos(half)])
    n2 = np.array([up * math.sin(half), math.cos(half)])
    lo, hi = (f * t for f in FACES[surface])
    into = _unit(d1 + d2)  # the concave side of the V
    ends, tangents, normals_in, in_offsets = [], [], [], []
    centre_rows, centre_rhs = [], []
    for d, n, length in ((d1, n1, l1), (d2, n2, l2)):
        top_inside = float(n @ into) > 0.0
        off = hi if top_inside else lo  # the inside face's offset along n
        m = n if top_inside else -n  # unit normal towards the concave side
        base = off * n  # a point of the inside-face line
        centre_rows.append(m)  # m . (C - base) = r: the arc's centre r inside the line
        centre_rhs.append(r + float(m @ base))
        ends.append(length * d + off * n - k * t * m)  # the neutral line at the cut edge
        normals_in.append(m)
        in_offsets.append(base)
    centre = np.linalg.solve(np.array(centre_rows), np.array(centre_rhs))
    rho = r + k * t
    for m in normals_in:
        tangents.append(centre - rho * m)  # the neutral arc's tangent points
    flat = 0.0
    for end, tan, d in zip(ends, tangents, (d1, d2), strict=True):
        run = float((end - tan) @ d)
        assert run > 0.0, "the flange is shorter than the bend's set-back"
        flat += run
    a, b = tangents[0] - centre, tangents[1] - centre
    arc = math.atan2(abs(a[0] * b[1] - a[1] * b[0]), float(a @ b))
    return flat + rho * arc


def polygon_span_at(poly: np.ndarray, x: float) -> tuple[float, float]:
    """The lowest and highest y where the vertical line at ``x`` meets the
    closed polygon ``(n, 2)``'s edges."""
    a, b = poly, np.roll(poly, -1, axis=0)
    hit = (a[:, 0] - x) * (b[:, 0] - x) < 0.0
    u = (x - a[hit, 0]) / (b[hit, 0] - a[hit, 0])
    y = a[hit, 1] + u * (b[hit, 1] - a[hit, 1])
    return float(y.min()), float(y.max())


# -- the frame curve and the fold angles, from the paper's construction ------------------
def arc_point(alpha_deg: float, beta_deg: float, h_c: float, radius: float, phi: float):
    """The frame curve's point at arc angle ``phi`` (radians, -alpha at the f-line's +x
    end, 180 + alpha at its -x end): the circle of radius R about (-h_c, R sin alpha) in
    the plane through the x axis tilted by beta, (x, d cos beta, d sin beta)."""
    a, b = math.radians(alpha_deg), math.radians(beta_deg)
    d = radius * (math.sin(a) + math.sin(phi))
    return np.array([-h_c + radius * math.cos(phi), d * math.cos(b), d * math.sin(b)])


def arc_tangent(alpha_deg: float, beta_deg: float, radius: float, phi: float):
    """d(arc_point)/d(phi)."""
    b = math.radians(beta_deg)
    dd = radius * math.cos(phi)
    return np.array([-radius * math.sin(phi), dd * math.cos(b), dd * math.sin(b)])


def crease_angle(normal) -> float:
    """The fold angle (deg) between a +y side's top normal and its mirror image in the
    xz-plane (the -y side's): twice the normal's angle to that plane."""
    n = np.asarray(normal, dtype=float)
    return math.degrees(2.0 * math.atan2(abs(n[1]), math.hypot(n[0], n[2])))


def fan_folds(points, apex) -> list[tuple[float, str]]:
    """The paper fan's fold at each interior division ray k = 1 .. n-1 of the +y side:
    (angle in deg, 'UP' or 'DOWN'), from the triangles (A, P_k-1, P_k) and (A, P_k,
    P_k+1). A triangle's top normal is (P_k - A) x (P_k+1 - A) (the flat sheet's +x and
    +y give +z); the fold is UP (a valley seen from the top) when P_k+1 lies on the top
    side of the triangle before it."""
    u = [np.asarray(p, dtype=float) - apex for p in points]
    out = []
    for k in range(1, len(u) - 1):
        n0, n1 = np.cross(u[k - 1], u[k]), np.cross(u[k], u[k + 1])
        angle = math.degrees(math.atan2(float(np.linalg.norm(np.cross(n0, n1))), float(n0 @ n1)))
        out.append((angle, "UP" if float(u[k + 1] @ n0) > 0.0 else "DOWN"))
    return out
