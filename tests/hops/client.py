"""What the Hops server's tests send and read: requests as Hops sends them,
answers read back, the command's error line."""

from __future__ import annotations

import json
import urllib.error
import urllib.request
from typing import Any


def get(url: str) -> tuple[int, Any]:
    """``GET url``: (status, JSON body)."""
    with urllib.request.urlopen(url, timeout=60) as r:
        return r.status, json.loads(r.read())


def post(url: str, body: Any) -> tuple[int, Any]:
    """``POST url`` with ``body`` (JSON, or raw bytes): (status, JSON answer)."""
    data = body if isinstance(body, bytes) else json.dumps(body).encode()
    req = urllib.request.Request(url, data=data, headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=120) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as exc:
        return exc.code, json.loads(exc.read())


def outputs(answer: dict[str, Any]) -> dict[str, list[dict[str, str]]]:
    """The answer's values: output name -> its items (``{"type", "data"}``)."""
    return {
        v["ParamName"]: [item for branch in v["InnerTree"].values() for item in branch]
        for v in answer["values"]
    }


def data(items: list[dict[str, str]]) -> list[Any]:
    """The items' data read back (JSON text)."""
    return [json.loads(i["data"]) for i in items]


def cli_error(err: str) -> str:
    """The message of the command's one error line (without ``onefold: error: ``)."""
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("onefold: error: "), err
    return lines[0][len("onefold: error: ") :]


def surface_area(surface: Any) -> float:
    """The area of a rhino3dm face (cubic in u, linear in v, non-rational, as
    the .3dm's), integrated from its control net: Gauss-Legendre on each knot
    span of u, and in v."""
    import numpy as np
    from scipy.interpolate import BSpline

    n = surface.ToNurbsSurface()
    assert (n.OrderU, n.OrderV) == (4, 2) and not n.IsRational
    knots = np.array([n.KnotsU[i] for i in range(len(n.KnotsU))])
    knots = np.concatenate([knots[:1], knots, knots[-1:]])  # openNURBS drops the end knots
    net = np.array(
        [[[(q := n.Points[i, j]).X, q.Y, q.Z] for j in range(2)] for i in range(n.Points.CountU)]
    )
    inner, outer = BSpline(knots, net[:, 0], 3), BSpline(knots, net[:, 1], 3)
    d_in, d_out = inner.derivative(), outer.derivative()
    g, w = np.polynomial.legendre.leggauss(8)
    spans = np.unique(knots)
    total = 0.0
    for a, b in zip(spans[:-1], spans[1:], strict=True):
        u = 0.5 * (a + b) + 0.5 * (b - a) * g
        for v, wv in zip(0.5 + 0.5 * g, 0.5 * w, strict=True):
            su = (1 - v) * d_in(u) + v * d_out(u)
            sv = outer(u) - inner(u)
            total += float(
                np.sum(0.5 * (b - a) * w * wv * np.linalg.norm(np.cross(su, sv), axis=1))
            )
    return total


def shoelace(xy: Any) -> float:
    """The area of a polygon ``(n, 2)`` (counter-clockwise: positive)."""
    import numpy as np

    x, y = np.asarray(xy, dtype=float).T
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
