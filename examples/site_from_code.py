"""A site of two sheets written from code, then built as ``onefold site`` does.

    python examples/site_from_code.py [OUTDIR]

The site file is plain TOML: each sheet a template (or an inline design),
design flags, a position and a turn about the vertical.
"""

import sys
from pathlib import Path

import tomli_w

import onefold_cad as of

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

site = {
    "name": "two-squares",
    "units": "mm",
    "sheet": [
        {"name": "left", "template": "table1-row1", "x": -700.0, "y": 0.0, "rotation": 0.0},
        {
            "name": "right",
            "template": "table1-row1",
            "flags": {"alpha": 40.0},
            "x": 700.0,
            "y": 0.0,
            "rotation": 180.0,
        },
    ],
}
spec = out / "two-squares.toml"
spec.write_text(tomli_w.dumps(site))

files = of.site(spec, out / "site", formats="plan,order,json", sheet_formats="dxf,json")
for path in files:
    print(path)
