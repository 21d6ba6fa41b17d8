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


def shoelace(xy: Any) -> float:
    """The area of a polygon ``(n, 2)`` (counter-clockwise: positive)."""
    import numpy as np

    x, y = np.asarray(xy, dtype=float).T
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
