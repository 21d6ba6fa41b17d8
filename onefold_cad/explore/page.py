"""The page's files, held in memory, and its Content-Security-Policy.

:data:`STATIC` is the whole table of what the explorer serves besides its
API: a URL path maps to a file under ``static/`` and its MIME type, and no
path from a request ever reaches the file system. The policy allows the
page's own scripts and its inline import map alone (by its hash).
"""

from __future__ import annotations

import base64
import hashlib
import re
from importlib.resources import files

__all__ = ["STATIC", "TEXT", "csp", "static_files"]

TEXT = "text/plain; charset=utf-8"
_JS = "text/javascript; charset=utf-8"
#: URL path -> (file under static/, MIME type). Nothing else is ever served.
STATIC: dict[str, tuple[str, str]] = {
    "/": ("index.html", "text/html; charset=utf-8"),
    "/static/explore.js": ("explore.js", _JS),
    "/static/simulate.js": ("simulate.js", _JS),
    "/static/steel_view.js": ("steel_view.js", _JS),
    "/static/quality.js": ("quality.js", _JS),
    "/static/compensate.js": ("compensate.js", _JS),
    "/static/explore.css": ("explore.css", "text/css; charset=utf-8"),
    "/static/three/three.module.js": ("three/three.module.js", _JS),
    "/static/three/three.core.js": ("three/three.core.js", _JS),
    "/static/three/OrbitControls.js": ("three/OrbitControls.js", _JS),
    "/static/three/LICENSE": ("three/LICENSE", TEXT),
}
_IMPORTMAP = re.compile(rb'<script type="importmap">(.*?)</script>', re.S)


def static_files() -> dict[str, bytes]:
    """Every file of :data:`STATIC`, read once (bytes by URL path)."""
    root = files("onefold_cad.explore").joinpath("static")
    return {url: root.joinpath(*rel.split("/")).read_bytes() for url, (rel, _) in STATIC.items()}


def csp(index_html: bytes) -> str:
    """The page's Content-Security-Policy: its own scripts and the inline import map only."""
    hashes = " ".join(
        "'sha256-" + base64.b64encode(hashlib.sha256(m).digest()).decode() + "'"
        for m in _IMPORTMAP.findall(index_html)
    )
    return (
        f"default-src 'self'; script-src 'self' {hashes}; style-src 'self'; "
        "img-src 'self' data: blob:; connect-src 'self'; object-src 'none'; "
        "base-uri 'none'; form-action 'none'; frame-ancestors 'none'"
    )
