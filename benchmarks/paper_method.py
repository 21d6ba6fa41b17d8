"""The paper's method, implemented as the paper describes it: the baseline.

Plain Python (the ``math`` module only, no numpy), following sections 3.2 to
3.4 of the paper (/work/shared/reference/one-fold-paper.txt):

1. Direction-vectors: the frame curve (an arc of radius R and central angle
   180 + 2 alpha, chord on the x axis, H at ``h_c`` from the chord's
   midpoint, tilted by beta) is divided into ``divisions`` equal arcs. For an
   apex A = (0, 0, h), gamma_i is the angle between consecutive vectors
   P_i - A and S(h) = sum of gamma_i. The paper bisects for S(h) = 180 deg on
   the bracket [l, 2R], l = (R + R sin alpha) sin beta.
2. Final surface for a quadrilateral with vertices (X+, 0), (0, Y+), (-X-, 0),
   (0, -Y-): the rays from H at the cumulative angles theta_k = gamma_1 + ...
   + gamma_k meet the quadrilateral's sides at the distances
   f(gamma) = r s / (s cos gamma + r sin gamma), and the direction-vectors are
   scaled to those lengths (the -y side is the mirror image, its angles
   measured clockwise).

Stopping rule: bisect until the bracket is narrower than ``h_tol`` (a length,
default :data:`DEFAULT_H_TOL` = 1e-6 R), then return the bracket's midpoint. With R = 100 this
gives angle-condition errors of the order of the paper's Table 1 (1e-5 deg).
The bisection keeps the half whose ends straddle 180 deg under the usual
"S(mid) > 180 means the root lies above" rule; if the root is not in
[l, 2R] at all (e.g. alpha = beta = 85 deg, whose root is h ~ 242.5 > 2R), the
method silently converges to an end of the bracket, and its angle error shows it.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

__all__ = [
    "DEFAULT_H_TOL",
    "PaperResult",
    "frame_points",
    "angle_sum",
    "bisect_apex",
    "final_surface",
    "paper_method",
]

DEFAULT_H_TOL = 1e-6
"""Default bisection tolerance on h, as a fraction of R (length per length)."""

Vec = tuple[float, float, float]


@dataclass(frozen=True)
class PaperResult:
    """What the paper's method produces and how long it took.

    Attributes:
        apex_height: h (length).
        bracket: the initial bracket (l, 2R) (length).
        iterations: bisection steps.
        gammas_deg: the ``divisions`` apex angles of one side (deg).
        angle_sum_deg: 2 S(h), the sum around the apex (deg).
        angle_condition_error_deg: |2 S(h) - 360| (deg).
        rulings_upper: the +y side's rulings as (start, end) 3D points, from A.
        rulings_lower: the -y side's rulings (mirror directions, own lengths).
        time_direction_vectors: wall time of step 1 (s).
        time_final_surface: wall time of step 2 (s).
    """

    apex_height: float
    bracket: tuple[float, float]
    iterations: int
    gammas_deg: list[float]
    angle_sum_deg: float
    angle_condition_error_deg: float
    rulings_upper: list[tuple[Vec, Vec]]
    rulings_lower: list[tuple[Vec, Vec]]
    time_direction_vectors: float
    time_final_surface: float

    @property
    def time_total(self) -> float:
        """Both steps (s)."""
        return self.time_direction_vectors + self.time_final_surface


def frame_points(alpha: float, beta: float, h_c: float, radius: float, divisions: int) -> list[Vec]:
    """The ``divisions + 1`` division points of the +y frame curve.

    Args:
        alpha, beta: degrees; h_c, radius: lengths; divisions: >= 1.

    Returns:
        Points from the f-line's +x end (phi = -alpha) to its -x end
        (phi = 180 + alpha), equally spaced in the arc parameter phi.
    """
    a, b = math.radians(alpha), math.radians(beta)
    p0, p1 = -a, math.pi + a
    cb, sb, sa = math.cos(b), math.sin(b), math.sin(a)
    pts: list[Vec] = []
    for i in range(divisions + 1):
        phi = p0 + (p1 - p0) * i / divisions
        d = radius * sa + radius * math.sin(phi)
        pts.append((-h_c + radius * math.cos(phi), d * cb, d * sb))
    return pts


def _gammas(points: list[Vec], h: float) -> list[float]:
    """Apex angles (radians) between consecutive vectors P_i - A, A = (0, 0, h)."""
    out = []
    x0, y0, z0 = points[0]
    z0 -= h
    n0 = math.sqrt(x0 * x0 + y0 * y0 + z0 * z0)
    for x1, y1, z1 in points[1:]:
        z1 -= h
        n1 = math.sqrt(x1 * x1 + y1 * y1 + z1 * z1)
        c = (x0 * x1 + y0 * y1 + z0 * z1) / (n0 * n1)
        out.append(math.acos(max(-1.0, min(1.0, c))))
        x0, y0, z0, n0 = x1, y1, z1, n1
    return out


def angle_sum(points: list[Vec], h: float) -> float:
    """S(h): the sum of one side's apex angles (radians)."""
    return math.fsum(_gammas(points, h))


def bisect_apex(points: list[Vec], lo: float, hi: float, h_tol: float) -> tuple[float, int]:
    """Bisect S(h) = 180 deg on [lo, hi] until hi - lo < h_tol; return (mid, steps).

    S decreases through 180 deg past its maximum, so S(mid) > 180 deg moves
    the lower end up. No check that the bracket holds a root (the paper has none).
    """
    steps = 0
    while hi - lo >= h_tol:
        mid = 0.5 * (lo + hi)
        if angle_sum(points, mid) > math.pi:
            lo = mid
        else:
            hi = mid
        steps += 1
    return 0.5 * (lo + hi), steps


def _line_length(gamma: float, r: float, s: float) -> float:
    """f(gamma) = r s / (s cos gamma + r sin gamma): distance from the origin to
    the line x/r + y/s = 1 along the ray at angle gamma (radians)."""
    return r * s / (s * math.cos(gamma) + r * math.sin(gamma))


def final_surface(
    points: list[Vec],
    h: float,
    gammas: list[float],
    quad: tuple[float, float, float, float],
) -> tuple[list[tuple[Vec, Vec]], list[tuple[Vec, Vec]]]:
    """Scale the direction-vectors to the quadrilateral (paper section 3.4).

    Args:
        points: the frame-curve division points (+y side).
        h: the apex height.
        gammas: the apex angles (radians).
        quad: (X+, X-, Y+, Y-), the quadrilateral's axis crossings (lengths > 0).

    Returns:
        The rulings of the +y and the -y side as (A, end) pairs.
    """
    xp, xm, yp, ym = quad
    apex = (0.0, 0.0, h)
    theta = [0.0]
    for g in gammas:
        theta.append(theta[-1] + g)
    upper, lower = [], []
    for (x, y, z), t in zip(points, theta, strict=True):
        z -= h
        n = math.sqrt(x * x + y * y + z * z)
        ux, uy, uz = x / n, y / n, z / n
        r = xp if t <= 0.5 * math.pi else -xm
        lu = _line_length(t, r, yp)
        ll = _line_length(t, r, ym)
        upper.append((apex, (lu * ux, lu * uy, h + lu * uz)))
        lower.append((apex, (ll * ux, -ll * uy, h + ll * uz)))
    return upper, lower


def paper_method(
    alpha: float,
    beta: float,
    h_c: float,
    radius: float,
    divisions: int,
    quad: tuple[float, float, float, float],
    h_tol: float | None = None,
) -> PaperResult:
    """Run the whole method (direction-vectors, then final surface), timed.

    Args:
        alpha, beta: degrees; h_c, radius: lengths; divisions: triangles per side.
        quad: (X+, X-, Y+, Y-) of the quadrilateral sheet (lengths).
        h_tol: bisection stops when the bracket is narrower than this
            (length); default ``DEFAULT_H_TOL * radius``.
    """
    tol = DEFAULT_H_TOL * radius if h_tol is None else h_tol
    t0 = time.perf_counter()
    points = frame_points(alpha, beta, h_c, radius, divisions)
    lo = (radius + radius * math.sin(math.radians(alpha))) * math.sin(math.radians(beta))
    hi = 2.0 * radius
    h, steps = bisect_apex(points, lo, hi, tol)
    gammas = _gammas(points, h)
    t1 = time.perf_counter()
    upper, lower = final_surface(points, h, gammas, quad)
    t2 = time.perf_counter()
    total = 2.0 * math.degrees(math.fsum(gammas))
    return PaperResult(
        apex_height=h,
        bracket=(lo, hi),
        iterations=steps,
        gammas_deg=[math.degrees(g) for g in gammas],
        angle_sum_deg=total,
        angle_condition_error_deg=abs(total - 360.0),
        rulings_upper=upper,
        rulings_lower=lower,
        time_direction_vectors=t1 - t0,
        time_final_surface=t2 - t1,
    )
