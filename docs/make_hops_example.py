"""The generated blocks of docs/rhino.md: the Hops components' inputs and
outputs (from the server's own metadata), and the request and answer of one
real solve and of one refused value, posted to a server started here.

Run from the repository root (docs/make_reference.py runs it with the other
blocks; tests/test_docs.py checks that the page is current)::

    .venv/bin/python docs/make_reference.py

Long geometry and report strings of the answer are shortened with an
ellipsis (the page says so); everything else is the JSON as sent.
"""

from __future__ import annotations

import copy
import json
import threading
import urllib.error
import urllib.request
from typing import Any

#: The example: the paper-square template at alpha 40, beta 35 (Hops sends an
#: empty tree for every input left empty).
EXAMPLE = {"template": "paper-square", "alpha": 40.0, "beta": 35.0}
#: The refused value of the error example.
BAD = {"template": "paper-square", "alpha": 95.0}
#: A value's data longer than LONG (encoded geometry, the report) is cut after SHORT.
LONG, SHORT = 200, 60


def _post(url: str, body: dict[str, Any]) -> tuple[int, dict[str, Any]]:
    req = urllib.request.Request(
        url, json.dumps(body).encode(), {"Content-Type": "application/json"}
    )
    try:
        with urllib.request.urlopen(req, timeout=120) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as exc:
        return exc.code, json.loads(exc.read())


def _get(url: str) -> Any:
    with urllib.request.urlopen(url, timeout=60) as r:
        return json.loads(r.read())


def _short(body: dict[str, Any]) -> dict[str, Any]:
    out = copy.deepcopy(body)
    for entry in out.get("values", []):
        for items in entry["InnerTree"].values():
            for item in items:
                if len(item["data"]) > LONG:
                    item["data"] = item["data"][:SHORT] + "…"
    return out


def _lines(body: dict[str, Any]) -> str:
    """JSON with one line per key, per value entry and (in a long entry) per item."""
    dump = lambda v: json.dumps(v, ensure_ascii=False)  # noqa: E731
    keys = list(body)
    out = ["{"]
    for i, key in enumerate(keys):
        end = "," if i < len(keys) - 1 else ""
        value = body[key]
        if key != "values" or not value:
            out.append(f"  {dump(key)}: {dump(value)}{end}")
            continue
        out.append('  "values": [')
        for j, entry in enumerate(value):
            sep = "," if j < len(value) - 1 else ""
            text = dump(entry)
            if len(text) <= 100:
                out.append(f"    {text}{sep}")
                continue
            ((path, items),) = entry["InnerTree"].items()
            out.append(
                f'    {{"ParamName": {dump(entry["ParamName"])}, "InnerTree": {{{dump(path)}: ['
            )
            out += [
                f"      {dump(it)}{',' if k < len(items) - 1 else ''}" for k, it in enumerate(items)
            ]
            out.append(f"    ]}}}}{sep}")
        out.append(f"  ]{end}")
    out.append("}")
    return "\n".join(out)


def _table(params: list[dict[str, Any]], inputs: bool) -> list[str]:
    head = (
        "| input | type | optional | what it is |"
        if inputs
        else "| output | type | list | what it is |"
    )
    rows = [head, "|---|---|---|---|"]
    for p in params:
        if inputs:
            flag = "yes" if p["AtLeast"] == 0 else "**required**"
        else:
            flag = "list" if p.get("AtMost", 1) > 1 else "item"
        text = p["Description"].replace("|", "\\|")
        rows.append(f"| `{p['Name']}` | {p['ParamType']} | {flag} | {text} |")
    return rows


def hops_blocks() -> dict[str, str]:
    """The bodies of the blocks ``hops-components`` and ``hops-example``."""
    from onefold_cad.hops.inputs import SOLVE_INPUTS, hops_request
    from onefold_cad.hops.server import make_server

    server = make_server("127.0.0.1", 0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    url = f"http://127.0.0.1:{server.server_address[1]}"
    try:
        listing = _get(f"{url}/")
        request = hops_request("onefold/solve", SOLVE_INPUTS, EXAMPLE)
        status, answer = _post(f"{url}/solve", request)
        bad_status, bad = _post(f"{url}/solve", hops_request("onefold/solve", SOLVE_INPUTS, BAD))
    finally:
        server.shutdown()
        server.server_close()
    assert status == 200 and bad_status == 500, (answer, bad)
    comps = []
    for c in sorted(listing, key=lambda c: c["Uri"], reverse=True):
        comps += [f"#### `{c['Uri']}`", "", c["Description"] + ".", ""]
        comps += [*_table(c["Inputs"], True), "", *_table(c["Outputs"], False), ""]
    given = ", ".join(f"{k} = {v!r}" for k, v in EXAMPLE.items())
    example = [
        f"The request Hops posts to `/solve` for {given} (every other input empty):",
        "",
        "```json",
        _lines(request),
        "```",
        "",
        f"The answer (HTTP {status}; geometry and the report shortened to {SHORT} characters "
        "with an ellipsis, …):",
        "",
        "```json",
        _lines(_short(answer)),
        "```",
        "",
        f"The answer to alpha = {BAD['alpha']!r} (HTTP {bad_status}):",
        "",
        "```json",
        _lines(bad),
        "```",
        "",
    ]
    return {"hops-components": "\n".join(comps), "hops-example": "\n".join(example)}
