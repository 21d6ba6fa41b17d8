#!/usr/bin/env python3
"""Fuzz onefold_cad: seeded random designs through the public API, checked
against invariants that do not trust our own solver, plus bad command lines.

Every design runs in a worker process with a time limit, so one design can
never stop the run. Each ends in one class:

- ``ok``: every stage ran and every check below held;
- ``refused``: a OneFoldError whose message names a parameter;
- ``crash``: any other exception, a OneFoldError naming no parameter, a
  numpy/Python warning (a line the user would see), a non-finite number in
  the report, or a worker that died;
- ``hang``: the design ran past its time limit;
- ``wrong``: an independent check failed (docs/reliability.md lists them).

Run (from the repository root)::

    .venv/bin/python scripts/fuzz.py                 # 10 000 designs, seed 1, 2 workers
    .venv/bin/python scripts/fuzz.py -n 500 --seed 7 --step-fraction 0
    .venv/bin/python scripts/fuzz.py --write-docs    # also update docs/reliability.md

Its functions are imported by tests/test_fuzz.py (a fast slice).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import multiprocessing as mp
import multiprocessing.connection as mpc
import os
import re
import shlex
import sys
import tempfile
import time
import traceback
import warnings
from collections import Counter, defaultdict
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.geometry.developability import developability

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs" / "reliability.md"
BEGIN, END = "<!-- fuzz-results:begin -->", "<!-- fuzz-results:end -->"
CLASSES = ("ok", "refused", "crash", "hang", "wrong")

#: Parameter names a refusal may name (API and CLI spellings).
PARAMETERS = (
    "alpha",
    "beta",
    "h_c",
    "hc",
    "radius",
    "divisions",
    "x_plus",
    "x_minus",
    "y_plus",
    "y_minus",
    "x-plus",
    "x-minus",
    "y-plus",
    "y-minus",
    "polygon",
    "rectangle",
    "width",
    "height",
    "apex_fraction",
    "apex-fraction",
    "thickness",
    "bend_radius",
    "bend-radius",
    "k_factor",
    "k-factor",
    "kerf",
    "relief_hole",
    "relief-hole",
    "density",
    "model",
    "units",
    "sheet_surface",
    "sheet-surface",
    "body",
    "name",
    "outdir",
)
_PARAM_RE = re.compile(
    r"(?<![A-Za-z_])(" + "|".join(map(re.escape, PARAMETERS)) + r")(?![A-Za-z_])"
)

#: Spec tolerances: the angle condition (deg) and lengths relative to the sheet.
ANGLE_TOL_DEG = 1e-9
LENGTH_TOL = 1e-7


# -- random designs ---------------------------------------------------------
def _log_uniform(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(10.0 ** rng.uniform(math.log10(lo), math.log10(hi)))


def _angle(rng: np.random.Generator) -> float:
    """alpha or beta: log-spaced towards both ends of (0, 90), 1e-4 .. 89.99 deg."""
    if rng.random() < 0.5:
        return _log_uniform(rng, 1e-4, 45.0)
    return 90.0 - _log_uniform(rng, 1e-2, 45.0)


def _near_one(rng: np.random.Generator) -> float:
    """A fraction in (0, 1), often within 1e-9 .. 1e-1 of 0 or 1."""
    u = rng.random()
    if u < 0.2:
        return _log_uniform(rng, 1e-9, 0.1)
    if u < 0.4:
        return 1.0 - _log_uniform(rng, 1e-9, 0.1)
    return float(rng.uniform(0.0, 1.0))


def _side(rng: np.random.Generator) -> float:
    """A side relative to the sheet's size: a sliver (1e-9 .. 1) now and then."""
    return _log_uniform(rng, 1e-9, 1.0) if rng.random() < 0.15 else float(rng.uniform(0.2, 1))


def _star_polygon(rng: np.random.Generator, size: float) -> list[list[float]]:
    """A polygon around H: usually strictly star-shaped, with slivers, vertices
    near H and many vertices now and then; sometimes deliberately invalid."""
    u = rng.random()
    n = int(round(_log_uniform(rng, 3, 60))) if u < 0.95 else int(rng.integers(60, 2001))
    gaps = rng.dirichlet(np.full(n, 2.0 if rng.random() < 0.7 else 0.3))
    if rng.random() < 0.1:  # a few angular slivers
        k = rng.integers(0, n, size=max(1, n // 4))
        gaps[k] = [_log_uniform(rng, 1e-9, 1e-3) for _ in k]
    gaps = gaps / gaps.sum() * 2.0 * math.pi
    if np.any(gaps >= math.pi) and rng.random() < 0.9:
        gaps = np.minimum(gaps, 0.9 * math.pi)
        gaps = gaps / gaps.sum() * 2.0 * math.pi
    ang = rng.uniform(0.0, 2.0 * math.pi) + np.concatenate([[0.0], np.cumsum(gaps)[:-1]])
    radii = size * rng.uniform(0.05, 1.0, n)
    if rng.random() < 0.1:  # vertices near H
        k = rng.integers(0, n, size=max(1, n // 5))
        radii[k] = size * np.array([_log_uniform(rng, 1e-9, 1e-2) for _ in k])
    radii[int(np.argmax(radii))] = size
    pts = np.stack([radii * np.cos(ang), radii * np.sin(ang)], axis=-1)
    bad = rng.random()
    if bad < 0.01 and n > 3:  # swap two vertices: usually self-intersecting
        i, j = rng.choice(n, 2, replace=False)
        pts[[i, j]] = pts[[j, i]]
    elif bad < 0.02:  # H outside or on the boundary
        pts = pts - pts[0] * (1.0 if rng.random() < 0.5 else 1.5)
    return pts.tolist()


def random_design(rng: np.random.Generator, step_fraction: float = 0.02) -> dict[str, Any]:
    """One random design as plain data (see :func:`make_design`)."""
    model = "paper" if rng.random() < 0.5 else "exact"
    alpha, beta = _angle(rng), _angle(rng)
    radius = _log_uniform(rng, 1e-2, 1e5)
    u = rng.random()
    if u < 0.6:
        ratio = _log_uniform(rng, 0.3, 30.0)
    elif u < 0.97:
        ratio = _log_uniform(rng, 1e-6, 1e6)  # tiny and huge sheets relative to R
    else:
        ratio = _log_uniform(rng, 1e-9, 1e9)  # partly out of bounds: must be refused
    if rng.random() < 0.02:
        radius = _log_uniform(rng, 1e-32, 1e32)  # absolute extremes, partly out of bounds
    size = ratio * radius
    half = radius * math.cos(math.radians(alpha))
    v = rng.random()
    frac = 0.0 if v < 0.1 else (2.0 * _near_one(rng) - 1.0 if v < 0.5 else rng.uniform(-1, 1))
    frac = min(max(frac, -(1.0 - 1e-15)), 1.0 - 1e-15)
    p: dict[str, Any] = {
        "model": model,
        "alpha": alpha,
        "beta": beta,
        "h_c": frac * half,
        "radius": radius,
        "divisions": int(round(_log_uniform(rng, 3, 2000))),
    }
    k = rng.random()
    if k < 0.4:
        d = [size * _side(rng) for _ in range(4)]
        p["sheet"] = {
            "quadrilateral": dict(zip(("x_plus", "x_minus", "y_plus", "y_minus"), d, strict=True))
        }
    elif k < 0.6:
        w = size * rng.uniform(0.2, 1.0)
        h = size * _side(rng)
        p["sheet"] = {"rectangle": {"width": w, "height": h, "apex_fraction": _near_one(rng)}}
    else:
        p["sheet"] = {"polygon": _star_polygon(rng, size)}
    t = 0.0 if rng.random() < 0.5 else size * _log_uniform(rng, 1e-5, 3e-2)
    p["thickness"] = t
    p["bend_radius"] = 0.0 if t == 0.0 or rng.random() < 0.5 else t * rng.uniform(0.5, 3.0)
    p["step"] = bool(rng.random() < step_fraction)
    p["reread_dxf"] = bool(rng.random() < 0.1)  # re-read and audit a tenth of the DXFs
    return p


def make_design(p: dict[str, Any]) -> Any:
    """The :class:`onefold_cad.Design` of random-design data."""
    from onefold_cad import Design, FrameCurve, Material, Sheet

    frame = FrameCurve(p["alpha"], p["beta"], p["h_c"], p["radius"], p["divisions"])
    kind, args = next(iter(p["sheet"].items()))
    if kind == "polygon":
        sheet = Sheet.polygon(args)
    elif kind == "quadrilateral":
        sheet = Sheet.quadrilateral(**args)
    else:
        sheet = Sheet.rectangle(**args)
    mat = Material(thickness=p["thickness"], bend_radius=p["bend_radius"])
    return Design("fuzz", frame, sheet, model=p["model"], material=mat)


def command_line(p: dict[str, Any], build: bool = False) -> str:
    """The ``onefold`` command that reproduces design ``p`` (exact float reprs;
    the default template supplies k-factor 0.44, kerf 0 and the MID surface,
    as :class:`Material` does)."""
    args = ["onefold", "build" if build else "solve", "--model", p["model"]]
    for flag, key in (("--alpha", "alpha"), ("--beta", "beta"), ("--hc", "h_c")):
        args += [flag, repr(float(p[key]))]
    args += ["--radius", repr(float(p["radius"])), "--divisions", str(p["divisions"])]
    kind, s = next(iter(p["sheet"].items()))
    if kind == "polygon":
        args += ["--polygon", ";".join(f"{x!r},{y!r}" for x, y in s)]
    elif kind == "quadrilateral":
        for key in ("x_plus", "x_minus", "y_plus", "y_minus"):
            args += ["--" + key.replace("_", "-"), repr(float(s[key]))]
    else:
        args += ["--rectangle", f"{s['width']!r}x{s['height']!r}"]
        args += ["--apex-fraction", repr(float(s["apex_fraction"]))]
    args += ["--thickness", repr(float(p["thickness"]))]
    args += ["--bend-radius", repr(float(p["bend_radius"]))]
    args += ["-o", "/tmp/onefold-repro"] if build else ["--json"]
    return " ".join(shlex.quote(a) for a in args)


# -- independent geometry (numpy/scipy/mpmath; nothing from onefold_cad) -----
def frame_point(p: dict[str, Any], phi: np.ndarray) -> np.ndarray:
    """Frame-curve points ``(k, 3)`` at arc angles ``phi`` (paper section 3.2)."""
    r, a, b = p["radius"], math.radians(p["alpha"]), math.radians(p["beta"])
    d = r * math.sin(a) + r * np.sin(phi)
    return np.stack([-p["h_c"] + r * np.cos(phi), d * math.cos(b), d * math.sin(b)], axis=-1)


def _arc_ends(p: dict[str, Any]) -> tuple[float, float]:
    a = math.radians(p["alpha"])
    return -a, math.pi + a


def fan_points(p: dict[str, Any]) -> np.ndarray:
    """The paper model's ``divisions + 1`` division points, equally spaced on the arc."""
    p0, p1 = _arc_ends(p)
    return frame_point(p, p0 + (p1 - p0) * np.arange(p["divisions"] + 1) / p["divisions"])


def fan_gammas(p: dict[str, Any], h: float) -> np.ndarray:
    """The fan's apex angles (radians) for the apex at height h."""
    v = fan_points(p) - np.array([0.0, 0.0, h])
    a, b = v[:-1], v[1:]
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))


def _speed_function(p: dict[str, Any], h: float) -> Callable[[float], float]:
    """|du/dphi| of the unit vector u from the apex (0, 0, h) to the arc point
    P(phi): |P' x (P - A)| / |P - A|^2, in plain floats (for scipy's quad)."""
    r, a, b, hc = p["radius"], math.radians(p["alpha"]), math.radians(p["beta"]), p["h_c"]
    rsa, cb, sb = r * math.sin(a), math.cos(math.radians(p["beta"])), math.sin(b)

    def speed(phi: float) -> float:
        c, s = math.cos(phi), math.sin(phi)
        d = rsa + r * s
        v0, v1, v2 = -hc + r * c, d * cb, d * sb - h
        d0, d1, d2 = -r * s, r * c * cb, r * c * sb
        c0, c1, c2 = d1 * v2 - d2 * v1, d2 * v0 - d0 * v2, d0 * v1 - d1 * v0
        return math.sqrt(c0 * c0 + c1 * c1 + c2 * c2) / (v0 * v0 + v1 * v1 + v2 * v2)

    return speed


def placement_error(p: dict[str, Any], h: float) -> float:
    """A bound on what the frame points' own rounding does to the double S(h)
    (radians): each point is computed from h_c and R cos(phi) to about
    4 eps (|h_c| + R) per coordinate, which turns the direction from the apex
    by that over |P - A|. Near an f-line end the apex lies as close as 1e-9 R
    to the arc, and this is what the double S loses (1e-11 rad at 4e-5 R:
    far more than its summation or quadrature error)."""
    delta = 4.0 * np.finfo(float).eps * (abs(p["h_c"]) + p["radius"])
    if p["model"] == "paper":
        dist = np.linalg.norm(fan_points(p) - np.array([0.0, 0.0, h]), axis=1)
        return float(2.0 * np.sum(delta / np.maximum(dist, 1e-300)))
    r, a, b = p["radius"], math.radians(p["alpha"]), math.radians(p["beta"])
    # the apex's distance from the arc's circle: |P - A| >= it for every P
    foot = math.hypot(p["h_c"], h * math.sin(b) - r * math.sin(a))
    gap = max(math.hypot(foot - r, h * math.cos(b)), delta)
    return 2.0 * delta * (math.pi + 2.0 * a) / gap


def angle_sum(p: dict[str, Any], h: float) -> tuple[float, float]:
    """One side's angle sum S(h) (radians) and a bound on its numerical error:
    the fan sum, or scipy's adaptive quadrature of the cone (its estimate),
    plus :func:`placement_error`."""
    if p["model"] == "paper":
        g = fan_gammas(p, h)
        err = 4.0 * len(g) * np.finfo(float).eps * math.pi + placement_error(p, h)
        return float(g.sum()), err
    from scipy.integrate import quad

    p0, p1 = _arc_ends(p)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an IntegrationWarning shows in the error estimate
        f = _speed_function(p, h)
        val, err = quad(f, p0, p1, epsabs=1e-14, epsrel=1e-14, limit=400)
        mid = 0.5 * (p0 + p1)  # the same integral in two halves: a second opinion
        v1, e1 = quad(f, p0, mid, epsabs=1e-14, epsrel=1e-14, limit=400)
        v2, e2 = quad(f, mid, p1, epsabs=1e-14, epsrel=1e-14, limit=400)
    err = max(err, e1 + e2, abs(val - (v1 + v2)))
    return float(val), float(err) + 4.0 * np.finfo(float).eps * val + placement_error(p, h)


def mp_angle_sum(p: dict[str, Any], h: Any, dps: int = 20, ref: float = 0.0) -> Any:
    """S(h) in mpmath at ``dps`` digits (the inputs taken as exact binary
    floats): the fan summed, or the cone integrated by tanh-sinh on the
    panels of :func:`_mp_nodes` for the apex at ``ref`` (0: at h)."""
    return _mp_angle_sum(p, h, dps, ref)[0]


def mp_fan_rulings(p: dict[str, Any], h: float, pick: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The paper fan in mpmath (30 digits, the inputs exact): the flat angles
    of the division rulings ``pick`` (the apex angles summed from the +x end)
    and their unit directions from the apex (0, 0, h), as doubles."""
    import mpmath as m

    with m.workdps(30):
        r, a, b = m.mpf(p["radius"]), m.radians(m.mpf(p["alpha"])), m.radians(m.mpf(p["beta"]))
        hc, hh, n = m.mpf(p["h_c"]), m.mpf(h), p["divisions"]
        vs = []
        for i in range(n + 1):
            phi = -a + (m.pi + 2 * a) * i / n
            d = r * m.sin(a) + r * m.sin(phi)
            v = (-hc + r * m.cos(phi), d * m.cos(b), d * m.sin(b) - hh)
            norm = m.sqrt(sum(c * c for c in v))
            vs.append([c / norm for c in v])
        theta = [m.mpf(0)]
        for u, w in zip(vs[:-1], vs[1:], strict=True):
            cr = m.sqrt(
                (u[1] * w[2] - u[2] * w[1]) ** 2
                + (u[2] * w[0] - u[0] * w[2]) ** 2
                + (u[0] * w[1] - u[1] * w[0]) ** 2
            )
            theta.append(theta[-1] + m.atan2(cr, sum(x * y for x, y in zip(u, w, strict=True))))
        return (
            np.array([float(theta[i]) for i in pick]),
            np.array([[float(c) for c in vs[i]] for i in pick]),
        )


def _mp_cone(p: dict[str, Any], h: Any) -> tuple[Callable[[Any], Any], Any, Any]:
    """In mpmath at the working precision: |u'(phi)| for the apex at (0, 0, h),
    |P' x (P - A)| / |P - A|^2, and the arc's ends p0, p1."""
    import mpmath as m

    r, a, b = m.mpf(p["radius"]), m.radians(m.mpf(p["alpha"])), m.radians(m.mpf(p["beta"]))
    hc, hh = m.mpf(p["h_c"]), m.mpf(h)
    sa, cb, sb = m.sin(a), m.cos(b), m.sin(b)

    def speed(phi: Any) -> Any:
        d = r * sa + r * m.sin(phi)
        v = (-hc + r * m.cos(phi), d * cb, d * sb - hh)
        dp = (-r * m.sin(phi), r * m.cos(phi) * cb, r * m.cos(phi) * sb)
        cr = (
            dp[1] * v[2] - dp[2] * v[1],
            dp[2] * v[0] - dp[0] * v[2],
            dp[0] * v[1] - dp[1] * v[0],
        )
        return m.sqrt(sum(c * c for c in cr)) / sum(c * c for c in v)

    return speed, -a, m.pi + a


def _mp_nodes(p: dict[str, Any], h: Any, upto: Any = None, depth: int = 0) -> list[Any]:
    """Panel edges on [p0, upto] (default the whole arc) for tanh-sinh: the
    arc split at its ends, at ``upto``, at the arc point nearest the apex's
    foot F = (0, h sin(beta)) in the frame plane, and (F outside the circle)
    at the tangent points from F, each piece's panels halved ``depth`` times
    towards both its ends (0: until the smallest panel is a quarter of the
    apex's distance from the arc, over R). The integrand |u'| is analytic except
    near those points (its complex singularities lie within about the apex's
    distance from the arc of them: H near an f-line end puts one 1e-9 R from
    the end, beta near 90 deg puts them near the arc), so every panel is at
    least as far from a singularity as it is wide."""
    import mpmath as m

    r, a, b = m.mpf(p["radius"]), m.radians(m.mpf(p["alpha"])), m.radians(m.mpf(p["beta"]))
    hc, hh = m.mpf(p["h_c"]), m.mpf(h)
    p0, p1 = -a, m.pi + a
    top = p1 if upto is None else upto
    # F - C in the plane's (x, d) coordinates, C = (-h_c, R sin(alpha))
    fx, fd = hc, hh * m.sin(b) - r * m.sin(a)
    foot = m.atan2(fd, fx)
    if foot < p0:
        foot += 2 * m.pi
    cuts = {p0, top, foot}
    dist = m.hypot(fx, fd)
    if dist > r:
        off = m.acos(r / dist)
        cuts |= {foot - off, foot + off, foot - off + 2 * m.pi, foot + off - 2 * m.pi}
    cuts = sorted(c for c in cuts if p0 <= c <= top)
    if not depth:  # the apex's distance from the circle, over R (at least 1e-40)
        gap = m.hypot(dist - r, hh * m.cos(b)) / r + m.mpf(10) ** -40
        depth = min(int(m.ceil(m.log(2 * m.pi / gap, 2))) + 2, 160)
    nodes = [p0]
    grade = [m.mpf(2) ** -k for k in range(depth, 0, -1)]
    for lo, hi in zip(cuts[:-1], cuts[1:], strict=True):
        w = (hi - lo) / 2
        nodes += [lo + w * g for g in grade] + [lo + w] + [hi - w * g for g in reversed(grade)]
        nodes.append(hi)
    return sorted(set(nodes))


def _mp_angle_sum(p: dict[str, Any], h: Any, dps: int, ref: float) -> tuple[Any, float]:
    """:func:`mp_angle_sum` and the height whose panels it used (0 for the fan)."""
    import mpmath as m

    with m.workdps(dps):
        r, a, b = m.mpf(p["radius"]), m.radians(m.mpf(p["alpha"])), m.radians(m.mpf(p["beta"]))
        hc, h = m.mpf(p["h_c"]), m.mpf(h)
        sa, cb, sb = m.sin(a), m.cos(b), m.sin(b)

        def vec(phi: Any) -> tuple[Any, Any, Any]:
            d = r * sa + r * m.sin(phi)
            return (-hc + r * m.cos(phi), d * cb, d * sb - h)

        p0, p1 = -a, m.pi + a
        if p["model"] == "paper":
            n = p["divisions"]
            pts = [vec(p0 + (p1 - p0) * i / n) for i in range(n + 1)]
            total = m.mpf(0)
            for u, w in zip(pts[:-1], pts[1:], strict=True):
                cr = (
                    u[1] * w[2] - u[2] * w[1],
                    u[2] * w[0] - u[0] * w[2],
                    u[0] * w[1] - u[1] * w[0],
                )
                total += m.atan2(
                    m.sqrt(sum(c * c for c in cr)), sum(x * y for x, y in zip(u, w, strict=True))
                )
            return total, 0.0
        ref = ref or float(h)
        speed = _mp_cone(p, h)[0]
        return m.quad(speed, _mp_nodes(p, ref)), ref


def mp_developed_angle(p: dict[str, Any], h: float, u: np.ndarray, dps: int = 30) -> float:
    """The developed angle (radians, from the arc's +x end) of the point where
    the ray from the apex (0, 0, h) along ``u`` (a double unit vector, taken
    as exact) meets the frame plane, all in mpmath at ``dps`` digits.

    Why not doubles: near an f-line end the apex lies about L (the end's
    distance from H) above the arc, and |u'| peaks at about R / L there; an
    arc parameter phi near pi rounded to a double (4e-16) then moves the
    developed angle by 4e-16 R / L (1e-9 rad at L = 4e-7 R), and scipy's
    quad over [p0, phi] may step over a peak a millionth of the arc wide.
    Here phi is the exact angle of the meeting point about the arc's centre,
    and the integral runs on the graded panels of :func:`_mp_nodes`."""
    import mpmath as m

    with m.workdps(dps):
        r, a, b = m.mpf(p["radius"]), m.radians(m.mpf(p["alpha"])), m.radians(m.mpf(p["beta"]))
        hc, hh = m.mpf(p["h_c"]), m.mpf(h)
        sa, cb, sb = m.sin(a), m.cos(b), m.sin(b)
        uu = [m.mpf(float(c)) for c in u]
        # the frame plane holds the points (x, d cb, d sb); its normal (0, -sb, cb)
        t = -(hh * cb) / (-uu[1] * sb + uu[2] * cb)
        x = uu[0] * t
        d = uu[1] * t * cb + (hh + uu[2] * t) * sb
        phi = m.atan2(d - r * sa, x + hc)
        if phi < -a - m.mpf(10) ** -12:
            phi += 2 * m.pi
        speed = _mp_cone(p, hh)[0]
        return float(m.quad(speed, _mp_nodes(p, hh, upto=phi)))


def mp_root(p: dict[str, Any], h: float, resolve: float = 0.0) -> tuple[float, float, float]:
    """S(h) - pi in mpmath at the returned h, and the root that one Newton
    step from h gives, h - (S_mp(h) - pi) / S'(h), with S'(h) a central
    difference of S_mp (steps of 1e-6 h, 10 more digits, the panels of
    S_mp(h) for both, so their quadrature errors cancel). S_mp works at 20
    digits, or more when ``resolve`` (radians) asks: S - pi is then resolved
    to about 1e-8 of it (up to 60 digits). Returns (residual in radians,
    root, abs(S'(h)))."""
    import mpmath as m

    dps = 20
    if resolve > 0.0:
        dps = min(60, max(20, math.ceil(-math.log10(resolve)) + 9))
    with m.workdps(dps):
        s_h, ref = _mp_angle_sum(p, h, dps, 0.0)
        residual = float(s_h - m.pi)
    with m.workdps(dps + 10):
        x, d = m.mpf(h), m.mpf(10) ** -6
        up = _mp_angle_sum(p, x * (1 + d), dps + 10, ref)[0]
        down = _mp_angle_sum(p, x * (1 - d), dps + 10, ref)[0]
        slope = float((up - down) / (2 * d * x))
    return residual, (h - residual / slope if slope else h), abs(slope)


def polygon_area(v: np.ndarray) -> float:
    """Shoelace area of a closed polygon ``(n, 2)`` (counter-clockwise positive)."""
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def ring_through(vertices: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """The closed boundary of a polygon star-shaped about H (counter-clockwise
    ``(n, 2)``, vertex 0 on the +x axis) through its vertices and the points
    where rays from H at polar angles ``psi`` (radians) meet it, in order.
    Each ray is intersected with the one edge whose angular sector holds it."""
    ang = np.arctan2(vertices[:, 1], vertices[:, 0]) % (2.0 * math.pi)
    ang[0] = 0.0
    psi = np.unique(np.asarray(psi, dtype=float) % (2.0 * math.pi))
    k = np.searchsorted(ang, psi, side="right") - 1
    on_vertex = np.isclose(psi, ang[k], rtol=0.0, atol=1e-15)
    nxt = np.roll(vertices, -1, axis=0)
    psi, k = psi[~on_vertex], k[~on_vertex]
    a, e = vertices[k], (nxt - vertices)[k]
    d = np.stack([np.cos(psi), np.sin(psi)], axis=-1)
    rho = (a[:, 0] * e[:, 1] - a[:, 1] * e[:, 0]) / (d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0])
    pts = np.concatenate([vertices, d * rho[:, None]])
    order = np.lexsort((np.concatenate([ang, psi]), np.concatenate([np.arange(len(ang)), k])))
    return pts[order]


def fan_area_and_length(apex: np.ndarray, ring: np.ndarray) -> tuple[float, float]:
    """Area of the triangle fan from ``apex`` over the closed ring ``(k, 3)``,
    and the ring's length."""
    nxt = np.roll(ring, -1, axis=0)
    area = 0.5 * float(np.linalg.norm(np.cross(ring - apex, nxt - apex), axis=1).sum())
    return area, float(np.linalg.norm(nxt - ring, axis=1).sum())


def refined_ring(
    folded: Any, verts: np.ndarray, max_angle: float = 1e-2, max_sag: float = 1e-4
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The flat boundary ``(k, 2)``, its folded image ``(k, 3)`` and the image
    with every other point dropped, refined by bisecting each edge's pieces
    until each spans at most ``max_angle`` (radians) seen from H and its
    image's midpoint lies within ``max_sag`` of its chord's length of the
    chord (then the chord misses the arc's length by < 8/3 max_sag^2 < 3e-8
    of it)."""
    n = len(verts)
    nxt = np.roll(verts, -1, axis=0)
    edge = np.arange(n)
    t0, t1 = np.zeros(n), np.ones(n)
    a3, b3 = folded.map_points(verts), folded.map_points(nxt)
    done_e, done_t, done_3 = [], [], []
    for _ in range(60):
        a2 = verts[edge] + t0[:, None] * (nxt - verts)[edge]
        b2 = verts[edge] + t1[:, None] * (nxt - verts)[edge]
        tm = 0.5 * (t0 + t1)
        m3 = folded.map_points(verts[edge] + tm[:, None] * (nxt - verts)[edge])
        chord = b3 - a3
        clen = np.linalg.norm(chord, axis=1)
        sag = np.linalg.norm(np.cross(m3 - a3, chord), axis=1) / np.maximum(clen, 1e-300)
        span = np.abs(np.arctan2(a2[:, 0] * b2[:, 1] - a2[:, 1] * b2[:, 0], (a2 * b2).sum(1)))
        split = ((sag > max_sag * clen) | (span > max_angle)) & (t1 - t0 > 1e-15)
        keep = ~split
        done_e.append(edge[keep])
        done_t.append(t0[keep])
        done_3.append(a3[keep])
        if not split.any() or split.sum() > 200_000:
            break
        e, s0, s1, m = edge[split], t0[split], t1[split], m3[split]
        edge = np.concatenate([e, e])
        t0, t1 = np.concatenate([s0, tm[split]]), np.concatenate([tm[split], s1])
        a3, b3 = np.concatenate([a3[split], m]), np.concatenate([m, b3[split]])
    e, t = np.concatenate(done_e), np.concatenate(done_t)
    order = np.lexsort((t, e))
    e, t = e[order], t[order]
    ring2 = verts[e] + t[:, None] * (nxt - verts)[e]
    ring3 = np.concatenate(done_3)[order]
    return ring2, ring3, ring3[::2]


# -- the checks -------------------------------------------------------------
class Wrong(Exception):
    """An independent check failed."""

    def __init__(self, check: str, detail: str) -> None:
        super().__init__(f"{check}: {detail}")
        self.check = check


def check_solution(p: dict[str, Any], sol: Any, mp_sample: bool) -> dict[str, Any]:
    """The angle condition at the returned h, the root's side of the maximum,
    the reported error, and (sample) the mpmath root."""
    h = float(sol.apex_height)
    info: dict[str, Any] = {}
    if not (math.isfinite(h) and h > 0.0):
        raise Wrong("apex", f"apex height {h!r}")
    s, err = angle_sum(p, h)
    measured = abs(2.0 * math.degrees(s) - 360.0)
    err_deg = 2.0 * math.degrees(err)
    claimed = float(sol.angle_condition_error_deg)
    # the solver's own bound must cover what an independent recomputation sees
    # (up to that recomputation's error and the rounding of a sum in degrees)
    vague = err_deg > 0.1 * ANGLE_TOL_DEG  # the double S cannot decide at the spec
    if measured > ANGLE_TOL_DEG + err_deg or measured > claimed + err_deg + 1e-12 or vague:
        # near an f-line end the double S loses digits (points placed to 1e-16
        # R, see placement_error; a quadrature that fails): the verdict is S's
        # in mpmath (30 digits: to ~1e-26 rad, the inputs exact)
        import mpmath as m

        with m.workdps(30):
            measured = float(abs(2 * m.degrees(mp_angle_sum(p, h, dps=30) - m.pi)))
        err_deg = 0.0
        info["angle_error_mp"] = True
    info["angle_error_deg"] = measured
    if measured > ANGLE_TOL_DEG + err_deg:
        raise Wrong(
            "angle condition",
            f"|sum - 360| = {measured:.3g} deg at h = {h!r} (independent; bound "
            f"{ANGLE_TOL_DEG + err_deg:.3g} deg); the solver reports {claimed:.3g} deg",
        )
    if not measured <= claimed + err_deg + 1e-12:
        raise Wrong(
            "claimed error",
            f"|sum - 360| = {measured:.3g} deg at h = {h!r} (independent, +- "
            f"{err_deg:.2g}); the solver claims <= {claimed:.3g} deg",
        )
    # the root past the maximum: S > pi on (0, h*), S < pi beyond (up to S's error)
    half, err_half = angle_sum(p, 0.5 * h)
    double, err_double = angle_sum(p, 2.0 * h)
    half, double = half - math.pi, double - math.pi  # S - pi at h/2 and 2h
    slack = 0.0
    if not (half > 2.0 * err_half and double < -2.0 * err_double):
        # the double S fails or cannot decide (tiny beta: S - pi ~ 1e-20; near
        # an f-line end scipy's quad steps over |u'|'s peak, about L / R wide,
        # and the points' rounding is felt): mpmath on graded panels decides
        import mpmath as m

        with m.workdps(30):
            half = float(mp_angle_sum(p, 0.5 * h, dps=30) - m.pi)
            double = float(mp_angle_sum(p, 2.0 * h, dps=30) - m.pi)
        err_half = err_double = 0.0
        # S_max - pi is stated to its evaluation's bound plus ~1e-14 of itself
        # (h/2 may be the maximum itself: S - pi is nearly quadratic in h)
        slack = 1e-13 * abs(half)
        info["falling_root_mp"] = True
    if not (half > 2.0 * err_half and double < -2.0 * err_double):
        raise Wrong(
            "falling root",
            f"S(h/2) - 180 = {math.degrees(half):.3g} deg, S(2h) - 180 = "
            f"{math.degrees(double):.3g} deg at h = {h!r}: not the root past the maximum",
        )
    # the conditioning the solver reports: max S - pi is at least S(h/2) - pi
    s_max = getattr(sol, "s_max_minus_pi", None)
    if s_max is not None:
        low = half - 2.0 * err_half - slack > float(s_max)
        if "falling_root_mp" not in info and (low or 2.0 * err_half > 1e-6 * half):
            # near an f-line end the double S(h/2) is off by more than its
            # stated error (1e-11 rad at L = 4e-5 R): 30-digit S decides
            import mpmath as m

            with m.workdps(30):
                half = float(mp_angle_sum(p, 0.5 * h, dps=30) - m.pi)
            low = half - 1e-13 * abs(half) > float(s_max)
        info["s_max_low"] = bool(low)
    if mp_sample:
        # resolve S - pi well below the solver's verified bound on it
        claimed = float(getattr(sol, "apex_height_error", math.inf))
        ds_dh = abs(float(getattr(sol, "ds_dh", math.nan)))
        e_f = (claimed - 4.0 * np.finfo(float).eps * h) * ds_dh
        residual, root, slope = mp_root(p, h, e_f if math.isfinite(e_f) and e_f > 0 else 0.0)
        info["mp_h_error"] = abs(h - root)
        check_h_error(sol, h, root, slope, info)
        # the spec, or what the nearest doubles to the root can give
        if abs(residual) > math.radians(ANGLE_TOL_DEG) + 4.0 * np.finfo(float).eps * h * slope:
            raise Wrong(
                "mpmath root",
                f"S - 180 deg = {math.degrees(residual):.3g} deg at h = {h!r} in 20+ digit "
                f"arithmetic; the root is {root!r} (|dS/dh| = {slope:.3g})",
            )
    return info


def check_h_error(sol: Any, h: float, root: float, slope: float, info: dict[str, Any]) -> None:
    """The solver's bound on |h - h*|, ``apex_height_error`` = e / |dS/dh| +
    4 eps h with e its verified bound on |S(h) - pi|, against the mpmath root.

    The bound is rebuilt with the independent slope (``slope`` = |S'(h)|), so
    what is checked strictly is e, the verified part; the solver's own dS/dh
    is conditioning information, and its relative deviation from the
    independent slope is recorded (``ds_dh_deviation``) and summarised."""
    eps_h = 4.0 * np.finfo(float).eps * h
    claimed = float(getattr(sol, "apex_height_error", math.inf))
    ds_dh = abs(float(getattr(sol, "ds_dh", math.nan)))
    bound = claimed
    if slope > 0.0 and math.isfinite(ds_dh) and math.isfinite(claimed):
        info["ds_dh_deviation"] = abs(ds_dh - slope) / slope
        bound = max(claimed - eps_h, 0.0) * ds_dh / slope + eps_h
    # slack: the mpmath residual (1e-8 of e) and slope, the Newton step's
    # second-order term; the rounding of h and of the root to doubles
    if not abs(h - root) <= bound * (1.0 + 1e-6) + eps_h:
        raise Wrong(
            "claimed h error",
            f"|h - h*| = {abs(h - root):.3g} at h = {h!r} (mpmath root {root!r}); the solver "
            f"claims <= {claimed:.3g} ({bound:.3g} with the independent |dS/dh| = {slope:.6g})",
        )


def check_no_solution(p: dict[str, Any]) -> None:
    """A NoSolutionError is right only if S(h) <= 180 deg (within its error) on
    a log grid of apex heights from 1e-12 R to 1e3 R."""
    hs = p["radius"] * np.logspace(-12, 3, 151)
    for h in hs:
        s, err = angle_sum(p, float(h))
        if s - math.pi > 2.0 * err + 1e-12:
            raise Wrong(
                "no-solution refusal",
                f"S({h:.6g}) - 180 deg = {math.degrees(s - math.pi):.3g} deg > 0: a root exists",
            )


def check_fold(p: dict[str, Any], design: Any, folded: Any, rng: np.random.Generator) -> None:
    """Rulings through the frame curve, distances from H, boundary length and
    area of the folded form against the flat sheet (independent measures)."""
    apex = np.array([0.0, 0.0, float(folded.solution.apex_height)])
    verts = np.asarray(design.sheet.vertices, dtype=float)
    size = float(np.max(np.hypot(verts[:, 0], verts[:, 1])))
    # the input polygon itself: the sheet must be it (area and perimeter)
    kind, s = next(iter(p["sheet"].items()))
    if kind == "quadrilateral":
        ref = np.array(
            [(s["x_plus"], 0), (0, s["y_plus"]), (-s["x_minus"], 0), (0, -s["y_minus"])], float
        )
    elif kind == "rectangle":
        ref = np.array([(0, 0), (s["width"], 0), (s["width"], s["height"]), (0, s["height"])])
    else:
        ref = np.asarray(s, dtype=float)
    flat_area = abs(polygon_area(ref))
    flat_len = float(np.linalg.norm(np.roll(ref, -1, axis=0) - ref, axis=1).sum())
    if abs(abs(polygon_area(verts)) - flat_area) > LENGTH_TOL * flat_area:
        raise Wrong("sheet", f"area {polygon_area(verts)!r} vs the input's {flat_area!r}")
    # 1. rulings pass through the frame curve
    total = float(folded.solution.surface.total_angle)
    theta = np.linspace(0.0, total, 9)[1:-1]
    if p["model"] == "paper":
        g = fan_gammas(p, float(apex[2]))
        theta = np.concatenate([[0.0], np.cumsum(g)])
        pick = np.unique(np.linspace(0, len(theta) - 1, 9).round().astype(int))
        want = fan_points(p)[pick] - apex
        want /= np.linalg.norm(want, axis=1)[:, None]
        theta = np.minimum(theta[pick], total)
    far = p["radius"] + float(apex[2]) + size  # far from A: no cancellation in X - A
    pts = np.stack([np.cos(theta), np.sin(theta)], axis=-1) * far
    u = folded.map_points(pts) - apex
    u /= np.linalg.norm(u, axis=1)[:, None]
    if p["model"] == "paper":
        dev = float(np.max(np.linalg.norm(u - want, axis=1)))
        if dev > 1e-9:
            # near an f-line end the double division point's P - A loses digits
            # (x = R cos(phi) - h_c to 1e-16 R, over |P - A| ~ L): mpmath decides
            theta, want = mp_fan_rulings(p, float(apex[2]), pick)
            theta = np.minimum(theta, total)
            pts = np.stack([np.cos(theta), np.sin(theta)], axis=-1) * far
            u = folded.map_points(np.asarray(pts)) - apex
            u /= np.linalg.norm(u, axis=1)[:, None]
            dev = float(np.max(np.linalg.norm(u - want, axis=1)))
        if dev > 1e-9:
            raise Wrong("rulings", f"a division ruling is {dev:.3g} rad off its division point")
    else:
        b, r = math.radians(p["beta"]), p["radius"]
        normal = np.array([0.0, -math.sin(b), math.cos(b)])
        with np.errstate(divide="ignore", invalid="ignore"):
            t = -(apex @ normal) / (u @ normal)
        x = apex + t[:, None] * u
        d = x @ np.array([0.0, math.cos(b), math.sin(b)])
        off = np.hypot(x[:, 0] + p["h_c"], d - r * math.sin(math.radians(p["alpha"]))) - r
        if float(np.max(np.abs(off))) > 1e-9 * r:
            raise Wrong("rulings", f"a ruling meets the frame plane {np.max(np.abs(off)):.3g} off")
        # the developed angle of those rulings: the arc length of u on the sphere
        from scipy.integrate import quad

        phi = np.arctan2(d - r * math.sin(math.radians(p["alpha"])), x[:, 0] + p["h_c"])
        p0 = _arc_ends(p)[0]
        phi = np.where(phi < p0 - 1e-9, phi + 2 * math.pi, phi)
        for th, ph in zip(theta[::3], phi[::3], strict=True):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                dev, err = quad(
                    _speed_function(p, float(apex[2])),
                    p0,
                    ph,
                    epsabs=1e-14,
                    epsrel=1e-14,
                    limit=400,
                )
            if abs(dev - th) > 1e-9 + 2 * err:
                # the double integral's phi and quad fail near an f-line end
                # (see mp_developed_angle): mpmath at the same ruling decides
                k = int(np.flatnonzero(theta == th)[0])
                dev = mp_developed_angle(p, float(apex[2]), u[k])
                if abs(dev - th) > 1e-9:
                    raise Wrong(
                        "developed angle",
                        f"ruling at {float(th)!r} rad develops to {dev!r} rad (mpmath)",
                    )
    # 2. distances from H survive the fold
    ring = ring_through(verts, rng.uniform(0.0, 2.0 * math.pi, 64))
    inner = ring * rng.uniform(0.0, 1.0, len(ring))[:, None]
    dist = np.linalg.norm(folded.map_points(inner) - apex, axis=1)
    dev = float(np.max(np.abs(dist - np.hypot(inner[:, 0], inner[:, 1]))))
    if dev > LENGTH_TOL * size:
        raise Wrong("distance from H", f"off by {dev:.3g} (sheet size {size:.6g})")
    # 3. boundary length and area: exact for the fan (points on every ruling),
    #    Richardson-extrapolated samples for the cone
    if p["model"] == "paper":
        fan = np.concatenate([[0.0], np.cumsum(fan_gammas(p, float(apex[2])))])
        fan = fan[fan < math.pi - 1e-12]
        ring2 = ring_through(verts, np.concatenate([fan, -fan]))
        est = (0.0, 0.0)
        area3, len3 = fan_area_and_length(apex, folded.map_points(ring2))
    else:
        ring2, ring3, coarse3 = refined_ring(folded, verts)
        area3, len3 = fan_area_and_length(apex, ring3)
        area_c, len_c = fan_area_and_length(apex, coarse3)
        est = (abs(area3 - area_c), abs(len3 - len_c))
    if abs(len3 - flat_len) > LENGTH_TOL * flat_len + 10.0 * est[1]:
        raise Wrong("boundary length", f"folded {len3!r} vs flat {flat_len!r} (est. {est[1]:.2g})")
    # what doubles can give: each folded point A + r u carries a rounding of
    # about eps (h + size) per coordinate, which moves the area by at most the
    # perimeter times it (felt only by slivers, whose width is far below h)
    rounding = flat_len * 16.0 * np.finfo(float).eps * (float(apex[2]) + size)
    if abs(area3 - flat_area) > LENGTH_TOL * flat_area + 10.0 * est[0] + rounding:
        raise Wrong(
            "area",
            f"folded {area3!r} vs flat {flat_area!r} (est. {est[0]:.2g}, rounding {rounding:.2g})",
        )


def check_resting(rest: Any, design: Any, folded: Any, rng: np.random.Generator) -> None:
    """The resting placement (what the report, STEP, GLB and previews use): a
    proper rotation, finite numbers, the ground at z = 0 under the body, its
    contacts on the ground, and no point of the sheet's folded boundary below
    it (the reference surface lies in the body, whatever the thickness)."""
    rot = np.asarray(rest.rotation, dtype=float)
    if not np.allclose(rot @ rot.T, np.eye(3), rtol=0.0, atol=1e-12) or np.linalg.det(rot) < 0:
        raise Wrong("resting", f"the placement's rotation is not a proper rotation: {rot!r}")
    arrays = (rest.translation, rest.centre_of_mass, rest.contacts, rest.bounds, rest.footprint)
    if not all(np.all(np.isfinite(np.asarray(a, dtype=float))) for a in arrays) or not (
        math.isfinite(rest.tipping_margin_deg)
    ):
        raise Wrong("resting", "a non-finite number in the resting placement")
    verts = np.asarray(design.sheet.vertices, dtype=float)
    size = float(np.max(np.hypot(verts[:, 0], verts[:, 1])))
    tol = LENGTH_TOL * size
    if abs(float(rest.bounds[0, 2])) > tol:
        raise Wrong("resting", f"the body's lowest point is at z = {rest.bounds[0, 2]:.3g}, not 0")
    contacts = np.asarray(rest.contacts, dtype=float).reshape(-1, 3)
    if len(contacts) == 0 or float(np.max(np.abs(contacts[:, 2]))) > tol:
        raise Wrong("resting", f"contacts off the ground: {contacts[:, 2]!r}")
    ring = ring_through(verts, rng.uniform(0.0, 2.0 * math.pi, 256))
    low = float(np.min(rest.apply(folded.map_points(ring))[:, 2]))
    if low < -tol:
        raise Wrong("resting", f"the folded boundary reaches z = {low:.3g} below the ground")


def _non_finite(obj: Any, path: str = "") -> str | None:
    """The path of the first non-finite float in a JSON-like report, else None."""
    if isinstance(obj, float):
        return None if math.isfinite(obj) else path or "."
    if isinstance(obj, dict):
        items: Iterable[tuple[Any, Any]] = obj.items()
    elif isinstance(obj, list | tuple):
        items = enumerate(obj)
    else:
        return None
    for k, v in items:
        bad = _non_finite(v, f"{path}.{k}")
        if bad:
            return bad
    return None


def check_outputs(
    p: dict[str, Any], design: Any, folded: Any, tmp: Path, stages: list[str]
) -> None:
    """Report (finite), flat pattern (area for an uncompensated sheet), DXF
    (re-read and audited) and, for the STEP slice, STEP (re-read, valid)."""
    from onefold_cad.export.dxf import export_design_dxf
    from onefold_cad.fabrication.flat_pattern import flat_pattern
    from onefold_cad.fabrication.report import design_report, report_json

    stages.append("flat pattern")
    fp = flat_pattern(design, folded)
    if design.material.thickness == 0.0 and fp.hole_diameter == 0.0:
        area = float(design.sheet.area)
        if abs(fp.area - area) > LENGTH_TOL * area:
            raise Wrong("flat pattern", f"area {fp.area!r} vs the sheet's {area!r}")
    stages.append("report")
    rep = design_report(design, folded, pattern=fp)
    bad = _non_finite(rep)
    if bad:
        raise ValueError(f"non-finite number in the report at {bad}")
    report_json(rep)
    stages.append("dxf")
    import ezdxf  # noqa: TID251 (a script: re-reads the DXF as a user would)

    path = export_design_dxf(design, tmp / "fuzz.dxf", folded=folded)
    if p.get("reread_dxf", True):
        auditor = ezdxf.readfile(path).audit()
        if auditor.has_errors:
            raise Wrong("dxf", f"{len(auditor.errors)} audit errors")
    if p.get("step"):
        stages.append("step")
        import build123d as bd  # noqa: TID251 (re-reads the STEP)

        from onefold_cad.export.step import export_design_step

        step = export_design_step(design, tmp / "fuzz.step", folded=folded)
        shape = bd.import_step(step)
        valid = shape.is_valid
        if not (valid() if callable(valid) else valid):
            raise Wrong("step", "the STEP file read back is not a valid shape")


def run_design(p: dict[str, Any], seed: int, mp_sample: bool) -> dict[str, Any]:
    """Every stage of one design; its class, stage and message."""
    from onefold_cad import NoSolutionError, OneFoldError, fold_design
    from onefold_cad.fabrication.rules import resting_placement

    stages = ["design"]
    rng = np.random.default_rng(seed)
    t0 = time.perf_counter()
    out: dict[str, Any] = {"cls": "ok", "stage": "", "message": "", "check": ""}
    with warnings.catch_warnings(record=True) as caught, tempfile.TemporaryDirectory() as td:
        warnings.simplefilter("always")
        try:
            design = make_design(p)
            stages.append("solve+fold")
            folded = fold_design(design)
            stages.append("checks")
            out.update(check_solution(p, folded.solution, mp_sample))
            check_fold(p, design, folded, rng)
            stages.append("metrics")
            developability(folded)  # noqa: B018 (computed on access)
            rest = resting_placement(design, folded)  # what the report and files use
            out["solver_warnings"] = len(folded.solution.warnings)
            check_resting(rest, design, folded, rng)
            check_outputs(p, design, folded, Path(td), stages)
        except Wrong as w:
            out.update(cls="wrong", check=w.check, message=str(w))
        except OneFoldError as exc:
            msg = " ".join(str(exc).split())
            named = getattr(exc, "parameter", None) or _PARAM_RE.search(msg)
            out.update(cls="refused" if named else "crash", message=f"{type(exc).__name__}: {msg}")
            if isinstance(exc, NoSolutionError):
                try:
                    check_no_solution(p)
                except Wrong as w:
                    out.update(cls="wrong", check=w.check, message=f"{msg} / {w}")
        except Exception as exc:  # noqa: BLE001 (every other exception is a crash)
            tb = traceback.extract_tb(exc.__traceback__)[-1]
            where = f"{Path(tb.filename).name}:{tb.lineno}"
            msg = " ".join(str(exc).split())[:300]
            out.update(cls="crash", message=f"{type(exc).__name__} at {where}: {msg}")
        out["stage"] = stages[-1]
        if out["cls"] in ("ok", "refused", "wrong") and caught:
            w = caught[0]
            out.update(
                cls="crash",
                check="",
                message=f"{w.category.__name__} at {Path(w.filename).name}:{w.lineno}: {w.message}",
            )
    out["seconds"] = time.perf_counter() - t0
    return out


# -- bad command lines --------------------------------------------------------
BAD_LINES: list[tuple[list[str], str]] = [
    (["solve", "--alpha", "0"], "alpha"),
    (["solve", "--alpha", "90"], "alpha"),
    (["solve", "--alpha", "-1e-300"], "alpha"),
    (["solve", "--alpha", "nan"], "alpha"),
    (["solve", "--alpha", "inf"], "alpha"),
    (["solve", "--alpha", "abc"], "alpha"),
    (["solve", "--beta", "0"], "beta"),
    (["solve", "--beta", "90.000001"], "beta"),
    (["solve", "--beta", "-inf"], "beta"),
    (["solve", "--beta", "1e400"], "beta"),
    (["solve", "--hc", "nan"], "hc"),
    (["solve", "--hc", "1e308"], "hc"),
    (["solve", "--hc", "86.61"], "hc"),
    (["solve", "--radius", "0"], "radius"),
    (["solve", "--radius", "-5"], "radius"),
    (["solve", "--radius", "1e308"], "radius"),
    (["solve", "--radius", "1e-300"], "radius"),
    (["solve", "--radius", "inf"], "radius"),
    (["solve", "--radius", "1e-5"], "radius"),
    (["solve", "--radius", "1e12"], "radius"),
    (["solve", "--divisions", "0"], "divisions"),
    (["solve", "--divisions", "-3"], "divisions"),
    (["solve", "--divisions", "10000000"], "divisions"),
    (["solve", "--divisions", "10001"], "divisions"),
    (["solve", "--divisions", "2.5"], "divisions"),
    (["solve", "--rectangle", "1e308x1e308"], "rectangle"),
    (["solve", "--rectangle", "0x5"], "rectangle"),
    (["solve", "--rectangle", "5x-1"], "rectangle"),
    (["solve", "--rectangle", "nanx5"], "rectangle"),
    (["solve", "--rectangle", "5"], "rectangle"),
    (["solve", "--rectangle", "3000x1e-9"], "rectangle"),
    (["solve", "--apex-fraction", "0"], "apex-fraction"),
    (["solve", "--apex-fraction", "1"], "apex-fraction"),
    (["solve", "--apex-fraction", "1e-300"], "apex-fraction"),
    (["solve", "--polygon", "1e308,1e308;-1e308,1e308;-1e308,-1e308;1e308,-1e308"], "polygon"),
    (
        ["solve", "--polygon", "1e-300,1e-300;-1e-300,1e-300;-1e-300,-1e-300;1e-300,-1e-300"],
        "polygon",
    ),
    (["solve", "--polygon", "1e308,0;0,1e308;-1e308,0;0,-1e308"], "polygon"),
    (["solve", "--polygon", "1,1;-1,-1;1,-1;-1,1"], "polygon"),
    (["solve", "--polygon", "1,0;0,1"], "polygon"),
    (["solve", "--polygon", "1,1;2,1;2,2;1,2"], "polygon"),
    (["solve", "--polygon", "1,0;0,1;-1,0;0,0"], "polygon"),
    (["solve", "--polygon", "1,0;1,1;-1,1;-1,0"], "polygon"),
    (["solve", "--polygon", "-5,-1;1,-1;1,1;-3,1;-3,5;-5,5"], "polygon"),
    (["solve", "--polygon", "1,0;nan,1;-1,0;0,-1"], "polygon"),
    (["solve", "--polygon", "1,0;inf,1;-1,0;0,-1"], "polygon"),
    (["solve", "--polygon", "1,0;0,1;-1,0;0,-1;1,0;0,1"], "polygon"),
    (["solve", "--polygon", "1;2;3"], "polygon"),
    (["solve", "--polygon", "a,b;c,d;e,f"], "polygon"),
    (["solve", "--polygon", "300,0;0,300;-300,0;0,-300", "--x-plus", "3"], "polygon"),
    (["solve", "--x-plus", "1e308", "--x-minus", "1", "--y-plus", "1", "--y-minus", "1"], "x-plus"),
    (
        ["solve", "--x-plus", "1", "--x-minus", "1e-300", "--y-plus", "1", "--y-minus", "1"],
        "x-minus",
    ),
    (["solve", "--x-plus", "1", "--x-minus", "1", "--y-plus", "1e-10", "--y-minus", "1"], "y-plus"),
    (["solve", "--x-plus", "1", "--x-minus", "1", "--y-plus", "1"], "y-minus"),
    (["solve", "--x-plus", "nan", "--x-minus", "1", "--y-plus", "1", "--y-minus", "1"], "x-plus"),
    (["solve", "--thickness", "-1"], "thickness"),
    (["solve", "--thickness", "1e31"], "thickness"),
    (["solve", "--thickness", "nan"], "thickness"),
    (["solve", "--bend-radius", "-1"], "bend-radius"),
    (["solve", "--bend-radius", "1e300"], "bend-radius"),
    (["solve", "--k-factor", "2"], "k-factor"),
    (["solve", "--kerf", "-0.1"], "kerf"),
    (["solve", "--relief-hole", "-2"], "relief-hole"),
    (["solve", "--relief-hole", "1e300"], "relief-hole"),
    (["solve", "--density", "0"], "density"),
    (["solve", "--model", "fancy"], "model"),
    (["solve", "--units", "cubit"], "units"),
    (["solve", "--sheet-surface", "TOP"], "sheet-surface"),
    (["build", "--alpha", "1e400"], "alpha"),
    (["build", "--radius", "1e308"], "radius"),
    (["build", "--polygon", "1,1;-1,-1;1,-1;-1,1"], "polygon"),
    (["build", "--divisions", "10000000"], "divisions"),
    (["build", "--body", "foam"], "body"),
]


@contextlib.contextmanager
def _fd_captured(fd: int) -> Iterator[io.StringIO]:
    """Capture what is written to the file descriptor ``fd`` itself (not only
    to ``sys.stderr``/``sys.stdout``) into the StringIO yielded, filled on exit."""
    sys.stdout.flush()
    sys.stderr.flush()
    buf = io.StringIO()
    saved = os.dup(fd)
    with tempfile.TemporaryFile() as tmp:
        os.dup2(tmp.fileno(), fd)
        try:
            yield buf
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os.dup2(saved, fd)
            os.close(saved)
            tmp.seek(0)
            buf.write(tmp.read().decode(errors="replace"))


def run_bad_line(argv: list[str], param: str) -> dict[str, Any]:
    """Run one bad command line in-process: exit 2, one stderr line naming
    ``param``, no traceback, nothing in the output folder."""
    from onefold_cad.cli.main import main

    with tempfile.TemporaryDirectory() as td:
        outdir = Path(td) / "out"
        args = argv + (["-o", str(outdir)] if argv[0] == "build" else [])
        err, out = io.StringIO(), io.StringIO()
        with (
            _fd_captured(2) as raw_err,
            _fd_captured(1),
            warnings.catch_warnings(),
            contextlib.redirect_stderr(err),
            contextlib.redirect_stdout(out),
        ):
            warnings.simplefilter("always")
            try:
                rc = main(args)
            except BaseException as exc:  # noqa: BLE001
                rc = f"raised {type(exc).__name__}: {exc}"
        # the CLI writes its error line with os.write (signal-safe), Python's
        # warnings and tracebacks go to sys.stderr: both are what a user sees
        text = raw_err.getvalue() + err.getvalue()
        lines = text.splitlines()
        left = sorted(p.name for p in outdir.rglob("*")) if outdir.exists() else []
    problems = []
    if rc != 2:
        problems.append(f"exit {rc}")
    if len(lines) != 1:
        problems.append(f"{len(lines)} stderr lines")
    elif not lines[0].startswith("onefold: error: ") or param not in lines[0]:
        problems.append(f"line does not name {param!r}")
    if "Traceback" in text:
        problems.append("traceback")
    if left:
        problems.append(f"left {left}")
    line = lines[0] if lines else text[:200]
    return {"cls": "crash" if problems else "refused", "message": "; ".join(problems), "line": line}


# -- the worker pool ------------------------------------------------------------
def _worker(conn: mpc.Connection) -> None:
    while True:
        try:
            job = conn.recv()
        except EOFError:
            return
        if job is None:
            return
        kind, args = job
        try:
            res = run_bad_line(*args) if kind == "cli" else run_design(*args)
        except BaseException as exc:  # noqa: BLE001 (report, never die silently)
            res = {"cls": "crash", "stage": "worker", "message": f"{type(exc).__name__}: {exc}"}
        conn.send(res)


class Pool:
    """Worker processes that each run one job at a time; a job past its time
    limit is a hang: its worker is killed (by pid) and replaced."""

    def __init__(self, workers: int) -> None:
        self.ctx = mp.get_context("fork")
        self.slots = [self._start() for _ in range(max(1, workers))]

    def _start(self) -> tuple[Any, mpc.Connection]:
        parent, child = self.ctx.Pipe()
        proc = self.ctx.Process(target=_worker, args=(child,), daemon=True)
        proc.start()
        child.close()
        return proc, parent

    def run(
        self,
        jobs: list[tuple[str, tuple[Any, ...], float]],
        done: Callable[[int, dict[str, Any]], None],
    ) -> None:
        """Run ``(kind, args, timeout)`` jobs; ``done(index, result)`` for each."""
        queue = list(range(len(jobs)))[::-1]
        busy: dict[int, tuple[int, float]] = {}  # slot -> (job index, deadline)
        while queue or busy:
            for s in range(len(self.slots)):
                if s not in busy and queue:
                    j = queue.pop()
                    kind, args, limit = jobs[j]
                    self.slots[s][1].send((kind, args))
                    busy[s] = (j, time.monotonic() + limit)
            conns = {self.slots[s][1]: s for s in busy}
            wait = max(0.0, min(d for _, d in busy.values()) - time.monotonic())
            ready = mpc.wait(list(conns), timeout=min(wait, 1.0))
            for c in ready:
                s = conns[c]  # type: ignore[index]
                j, _ = busy.pop(s)
                try:
                    done(j, c.recv())  # type: ignore[union-attr]
                except (EOFError, OSError):
                    code = self.slots[s][0].exitcode
                    done(j, {"cls": "crash", "stage": "worker", "message": f"worker died ({code})"})
                    self._replace(s)
            now = time.monotonic()
            for s, (j, deadline) in list(busy.items()):
                if now > deadline:
                    busy.pop(s)
                    limit = jobs[j][2]
                    done(j, {"cls": "hang", "stage": "", "message": f"no result in {limit:g} s"})
                    self._replace(s)

    def _replace(self, s: int) -> None:
        proc, conn = self.slots[s]
        if proc.is_alive():
            os.kill(proc.pid, 9)
        proc.join(5)
        conn.close()
        self.slots[s] = self._start()

    def close(self) -> None:
        for proc, conn in self.slots:
            with contextlib.suppress(OSError):
                conn.send(None)
            proc.join(5)
            if proc.is_alive():
                os.kill(proc.pid, 9)
                proc.join(5)
            conn.close()


# -- a run ------------------------------------------------------------------------
def fuzz(
    n: int = 10_000,
    seed: int = 1,
    workers: int = 2,
    step_fraction: float = 0.02,
    mp_fraction: float = 0.02,
    timeout: float = 120.0,
    step_timeout: float = 600.0,
    bad_lines: bool = True,
    progress: bool = False,
    results_file: str | None = None,
) -> dict[str, Any]:
    """Run ``n`` random designs (and the bad command lines) and return
    ``{"designs": [(params, result)], "cli": [(argv, param, result)]}``;
    each design's ``{"params", "result"}`` is also appended to
    ``results_file`` (JSON lines) as it finishes."""
    rng = np.random.default_rng(seed)
    designs = [random_design(rng, step_fraction) for _ in range(n)]
    for i, p in enumerate(designs):
        p["index"] = i
    mp_pick = rng.random(n) < mp_fraction
    jobs: list[tuple[str, tuple[Any, ...], float]] = [
        (
            "design",
            (p, seed * 1_000_003 + i, bool(mp_pick[i])),
            step_timeout if p["step"] else timeout,
        )
        for i, p in enumerate(designs)
    ]
    if bad_lines:
        jobs += [("cli", (argv, param), timeout) for argv, param in BAD_LINES]
    results: list[dict[str, Any] | None] = [None] * len(jobs)
    t0 = time.monotonic()

    sink = open(results_file, "a") if results_file else None  # noqa: SIM115

    def done(j: int, res: dict[str, Any]) -> None:
        results[j] = res
        if sink is not None and j < n:
            sink.write(json.dumps({"params": designs[j], "result": res}) + "\n")
            sink.flush()
        count = sum(r is not None for r in results)
        if progress and (count % 200 == 0 or count == len(jobs)):
            print(f"  {count}/{len(jobs)} in {time.monotonic() - t0:.0f} s", file=sys.stderr)

    import onefold_cad.cli.main  # noqa: F401 (imported once, before forking)

    pool = Pool(workers)
    try:
        pool.run(jobs, done)
    finally:
        pool.close()
        if sink is not None:
            sink.close()
    return {
        "designs": [(designs[i], results[i]) for i in range(n)],
        "cli": [(BAD_LINES[k][0], BAD_LINES[k][1], results[n + k]) for k in range(len(jobs) - n)],
        "seconds": time.monotonic() - t0,
    }


def summary(run: dict[str, Any], examples: int = 3) -> str:
    """Counts per class, per class and stage (or check), and reproducers."""
    designs = run["designs"]
    classes = Counter(r["cls"] for _, r in designs)
    head = run.get("source") or f"{len(designs)} designs in {run['seconds']:.0f} s"
    lines = [
        head,
        "",
        "| class | designs |",
        "|---|---:|",
    ]
    lines += [f"| {c} | {classes.get(c, 0)} |" for c in CLASSES]
    step = [r for p, r in designs if p["step"]]
    step_ok = sum(r["cls"] == "ok" for r in step)
    mp_n = sum("mp_h_error" in r for _, r in designs)
    lines += [
        "",
        f"STEP built and re-read for {len(step)} designs ({step_ok} ok); "
        f"h recomputed with S in mpmath (20 digits or more) for {mp_n}.",
    ]
    # the solver's conditioning figures (reported, not the result): recorded, not classed
    dev = [r["ds_dh_deviation"] for _, r in designs if "ds_dh_deviation" in r]
    low = [p["index"] for p, r in designs if r.get("s_max_low")]
    checked = sum("s_max_low" in r for _, r in designs)
    if dev or checked:
        worst = f", worst {max(dev):.2g}" if dev else ""
        lines += [
            "",
            f"Conditioning as the solver reports it: its dS/dh against the mpmath slope on "
            f"{len(dev)} designs ({sum(d > 1e-3 for d in dev)} off by more than 1e-3{worst}); "
            f"its S_max - pi below S(h/2) - pi on {len(low)} of {checked} designs"
            + (f" (e.g. design {', '.join(map(str, low[:5]))})." if low else "."),
        ]
    by: dict[tuple[str, str], list[tuple[dict[str, Any], dict[str, Any]]]] = defaultdict(list)
    for p, r in designs:
        if r["cls"] != "ok":
            key = r.get("check") or r.get("stage") or ""
            by[(r["cls"], key)].append((p, r))
    lines += ["", "| class | stage or check | designs |", "|---|---|---:|"]
    for (c, key), rows in sorted(by.items(), key=lambda kv: (CLASSES.index(kv[0][0]), kv[0][1])):
        lines.append(f"| {c} | {key} | {len(rows)} |")
    cli = run["cli"]
    if cli:
        bad = [(a, prm, r) for a, prm, r in cli if r["cls"] != "refused"]
        lines += [
            "",
            f"Bad command lines: {len(cli)} run, {len(cli) - len(bad)} exit 2 with one "
            f"line naming the parameter, {len(bad)} not.",
        ]
        for argv, prm, r in bad:
            lines.append(
                f"- `onefold {shlex.join(argv)}` ({prm}): {r['message']} -- {r.get('line', '')}"
            )
    for (c, key), rows in sorted(by.items(), key=lambda kv: (CLASSES.index(kv[0][0]), kv[0][1])):
        if c == "refused":
            continue
        lines += ["", f"{c} / {key}:"]
        cmds = sorted(
            ((len(command_line(p)), i, p, r) for i, (p, r) in enumerate(rows)), key=lambda x: x[0]
        )
        for _, _, p, r in cmds[:examples]:
            cmd = command_line(p, build=r.get("stage") == "step")
            if len(cmd) > 2000:
                cmd = f"{cmd[:300]} ... ({len(cmd)} characters; --show {p['index']} prints it)"
            lines.append(f"- design {p['index']}: {r['message'][:400]}")
            lines.append(f"  `{cmd}`")
    return "\n".join(lines)


def write_docs(text: str, command: str, seed: int) -> None:
    """Put the command, the seed and the results between the markers of
    docs/reliability.md."""
    doc = DOCS.read_text()
    head, rest = doc.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    block = f"{BEGIN}\nCommand: `{command}` (seed {seed}).\n\n{text}\n{END}"
    DOCS.write_text(head + block + tail)


def cap_timings(repeat: int = 3) -> str:
    """Wall time (median of ``repeat``) of validate + solve + fold + flat pattern
    + DXF at the caps: a paper design of MAX_DIVISIONS triangles and, in both
    models, a polygon sheet of MAX_VERTICES vertices."""
    from onefold_cad import Design, FrameCurve, Sheet, fold_design
    from onefold_cad.export.dxf import export_design_dxf
    from onefold_cad.fabrication.flat_pattern import flat_pattern
    from onefold_cad.geometry.frame_curve import MAX_DIVISIONS
    from onefold_cad.geometry.sheet import MAX_VERTICES

    ang = np.linspace(0.0, 2.0 * math.pi, MAX_VERTICES, endpoint=False) + 0.1
    rad = 300.0 * (1.0 + 0.3 * np.sin(7.0 * ang))
    poly = np.stack([rad * np.cos(ang), rad * np.sin(ang)], axis=-1)
    cases = {
        f"paper, {MAX_DIVISIONS} divisions, quadrilateral": lambda: Design(
            "cap",
            FrameCurve(50, 45, 0, 100, MAX_DIVISIONS),
            Sheet.quadrilateral(*[300.0] * 4),
            model="paper",
        ),
        f"paper, 90 divisions, {MAX_VERTICES}-vertex polygon": lambda: Design(
            "cap", FrameCurve(50, 45, 0, 100, 90), Sheet.polygon(poly), model="paper"
        ),
        f"exact, {MAX_VERTICES}-vertex polygon": lambda: Design(
            "cap", FrameCurve(50, 45, 0, 100, 90), Sheet.polygon(poly), model="exact"
        ),
    }
    lines = ["| case | validate + solve + fold + flat pattern + DXF (s) |", "|---|---:|"]
    with tempfile.TemporaryDirectory() as td:
        for name, make in cases.items():
            times = []
            for _ in range(repeat):
                t0 = time.perf_counter()
                design = make()
                folded = fold_design(design)
                flat_pattern(design, folded)
                export_design_dxf(design, Path(td) / "cap.dxf", folded=folded)
                times.append(time.perf_counter() - t0)
            lines.append(f"| {name} | {sorted(times)[len(times) // 2]:.2f} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("-n", type=int, default=10_000, help="random designs (default 10000)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--step-fraction", type=float, default=0.02)
    ap.add_argument("--mp-fraction", type=float, default=0.02)
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds per design")
    ap.add_argument("--step-timeout", type=float, default=600.0, help="seconds per STEP design")
    ap.add_argument("--no-cli", action="store_true", help="skip the bad command lines")
    ap.add_argument("--write-docs", action="store_true", help="update docs/reliability.md")
    ap.add_argument("--show", type=int, metavar="I", help="print design I's command and run it")
    ap.add_argument("--caps", action="store_true", help="time the pipeline at the caps")
    ap.add_argument("--results", metavar="FILE", help="append each design's result (JSON lines)")
    ap.add_argument(
        "--from-results",
        metavar="FILE",
        help="summarise the designs of a --results file (a run cut short included) "
        "instead of running designs; the bad command lines still run",
    )
    a = ap.parse_args(argv)
    if a.caps:
        print(cap_timings())
        return 0
    if a.show is not None:
        rng = np.random.default_rng(a.seed)
        designs = [random_design(rng, a.step_fraction) for _ in range(a.show + 1)]
        p = designs[a.show]
        print(command_line(p, build=p["step"]))
        print(run_design(p, a.seed * 1_000_003 + a.show, False))
        return 0
    if a.from_results:
        rows = [json.loads(line) for line in Path(a.from_results).read_text().splitlines()]
        rows.sort(key=lambda row: row["params"]["index"])
        t0 = time.monotonic()
        cli = fuzz(0, a.seed, a.workers, bad_lines=not a.no_cli, timeout=a.timeout)["cli"]
        run = {
            "designs": [(row["params"], row["result"]) for row in rows],
            "cli": cli,
            "seconds": time.monotonic() - t0,
            "source": f"{len(rows)} designs of `{a.from_results}` (each design's own wall time: "
            f"{sum(row['result'].get('seconds', 0.0) for row in rows):.0f} s in all)",
        }
    else:
        run = fuzz(
            a.n,
            a.seed,
            a.workers,
            a.step_fraction,
            a.mp_fraction,
            a.timeout,
            a.step_timeout,
            not a.no_cli,
            progress=True,
            results_file=a.results,
        )
    text = summary(run)
    print(text)
    if a.write_docs and a.from_results:
        write_docs(text, f"python scripts/fuzz.py --results {a.from_results}", a.seed)
    elif a.write_docs:
        cmd = "python scripts/fuzz.py " + " ".join(
            shlex.quote(x)
            for x in (argv if argv is not None else sys.argv[1:])
            if x != "--write-docs"
        )
        write_docs(text, cmd.strip(), a.seed)
    bad = sum(r["cls"] in ("crash", "hang", "wrong") for _, r in run["designs"])
    bad += sum(r["cls"] != "refused" for _, _, r in run["cli"])
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
