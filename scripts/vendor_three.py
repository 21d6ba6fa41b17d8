"""Vendor three.js into the explorer: npm install into a temporary folder, copy the
module build, OrbitControls and the licence, record version and checksums.

    .venv/bin/python scripts/vendor_three.py [VERSION]     # default: the latest release

Needs Node.js's npm and the npm registry. The files are copied unchanged, so
``onefold_cad/explore/static/three/VENDORED.txt`` lets anyone check them
against the package (tests/explore/test_vendored.py does).
"""

from __future__ import annotations

import hashlib
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

DEST = Path(__file__).resolve().parents[1] / "onefold_cad" / "explore" / "static" / "three"
FILES = {
    "build/three.module.js": "three.module.js",
    "build/three.core.js": "three.core.js",
    "examples/jsm/controls/OrbitControls.js": "OrbitControls.js",
    "LICENSE": "LICENSE",
}


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    spec = f"three@{args[0]}" if args else "three"
    with tempfile.TemporaryDirectory(prefix="vendor-three-") as tmp:
        subprocess.run(
            ["npm", "install", "--no-audit", "--no-fund", "--prefix", tmp, spec], check=True
        )
        pkg = Path(tmp) / "node_modules" / "three"
        version = json.loads((pkg / "package.json").read_text())["version"]
        if json.loads((pkg / "package.json").read_text()).get("license") != "MIT":
            raise SystemExit("three's licence is no longer MIT: check before vendoring")
        for src, dst in FILES.items():
            shutil.copyfile(pkg / src, DEST / dst)
    lines = [
        'three.js, vendored from the npm package "three" (MIT licence, see LICENSE).',
        f"version: {version}",
        "files (unchanged from the package):",
        *(f"  {src} -> {dst}" for src, dst in FILES.items()),
        "sha256:",
        *(
            f"  {hashlib.sha256((DEST / dst).read_bytes()).hexdigest()}  {dst}"
            for dst in FILES.values()
        ),
        'How to update: see docs/explore.md ("three.js").',
    ]
    (DEST / "VENDORED.txt").write_text("\n".join(lines) + "\n")
    print(f"vendored three {version} into {DEST}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
