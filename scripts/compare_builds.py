"""Compare two folders of ``onefold build`` (or ``onefold site``) files: the
same files, byte for byte, but the JSON reports' timings; STEP files also
read back and compared by topology and volume.

    .venv/bin/python scripts/compare_builds.py BASE_DIR NEW_DIR

A refactoring that moves code (no behaviour changed) must leave every file
equal: build the shipped templates with the old code into BASE_DIR and with
the new into NEW_DIR, then run this. Prints one line per file and a summary;
exit status 0 when every file is equal, 1 otherwise, 2 on bad arguments.

- ``.json``: equal as JSON once every ``timings_s`` table is removed
  (wall-clock seconds, different on every run).
- ``.step``: bytes; and, read with build123d, the counts of solids, shells,
  faces, edges and vertices and the volume and area, equal (relative 1e-12),
  so a STEP that differs only in its header would still be told apart from
  one whose shape changed.
- every other file (DXF, cut DXF, bend CSV, FOLD, GLB, 3dm, PNG, SVG, IFC, ...):
  bytes.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path
from typing import Any

#: Keys of the JSON reports that hold wall-clock times.
TIMING_KEYS = ("timings_s",)


def _without_timings(value: Any) -> Any:
    if isinstance(value, dict):
        return {k: _without_timings(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [_without_timings(v) for v in value]
    return value


def step_summary(path: Path) -> dict[str, float]:
    """Topology counts, volume and area of a STEP file (read with build123d)."""
    from build123d import import_step

    shape = import_step(str(path))
    return {
        "solids": len(shape.solids()),
        "shells": len(shape.shells()),
        "faces": len(shape.faces()),
        "edges": len(shape.edges()),
        "vertices": len(shape.vertices()),
        "volume": shape.volume,
        "area": shape.area,
    }


def compare_file(base: Path, new: Path) -> str | None:
    """None when equal, else what differs."""
    a, b = base.read_bytes(), new.read_bytes()
    if base.suffix == ".json":
        ja, jb = json.loads(a), json.loads(b)
        return None if _without_timings(ja) == _without_timings(jb) else "JSON differs"
    if base.suffix == ".step":
        sa, sb = step_summary(base), step_summary(new)
        changed = [k for k in sa if not math.isclose(sa[k], sb[k], rel_tol=1e-12, abs_tol=0.0)]
        if changed:
            return "STEP shape differs: " + ", ".join(f"{k} {sa[k]} -> {sb[k]}" for k in changed)
        return None if a == b else "STEP bytes differ (same topology and volume)"
    return None if a == b else f"bytes differ ({len(a)} -> {len(b)} bytes)"


def compare(base_dir: Path, new_dir: Path) -> list[tuple[str, str | None]]:
    """(relative path, None or what differs) for every file of either folder."""
    names = sorted(
        {p.relative_to(base_dir) for p in base_dir.rglob("*") if p.is_file()}
        | {p.relative_to(new_dir) for p in new_dir.rglob("*") if p.is_file()}
    )
    out = []
    for rel in names:
        a, b = base_dir / rel, new_dir / rel
        if not a.exists():
            out.append((str(rel), "only in NEW_DIR"))
        elif not b.exists():
            out.append((str(rel), "only in BASE_DIR"))
        else:
            out.append((str(rel), compare_file(a, b)))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("base", type=Path, metavar="BASE_DIR")
    ap.add_argument("new", type=Path, metavar="NEW_DIR")
    args = ap.parse_args(argv)
    for name, d in (("BASE_DIR", args.base), ("NEW_DIR", args.new)):
        if not d.is_dir():
            print(f"compare_builds: {name} {d} is not a folder", file=sys.stderr)
            return 2
    results = compare(args.base, args.new)
    for rel, why in results:
        print(f"{'equal' if why is None else 'DIFFERS'}  {rel}" + (f": {why}" if why else ""))
    bad = sum(why is not None for _, why in results)
    print(f"{len(results) - bad} of {len(results)} files equal, {bad} differ")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
