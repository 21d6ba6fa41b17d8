"""NAME-loads.csv: the outdoors check's cases, one row each, read from the
report's ``outdoors`` section (never recomputed).

Columns: the case, its kind (EQU, STR, SLS), whether it stands and why not,
the ground's vertical and horizontal load (N), the sliding ratio
``|H| / (mu V)``, the tipping margin and the largest deflection (design
unit), the peak linear elastic stress over f_y (``utilisation``,
information), the STR cases' J2 load path (``load_ratio`` r_R, what ended it,
the largest plastic strain and its area share; empty where none ran), then
per foot its reaction (N: ``foot1_x``, ``foot1_y``, ``foot1_z``, ...) and the ballast it needs (kg).
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from onefold_cad.export.atomic import atomic_output

__all__ = ["cases_csv", "write_cases_csv"]

_BASE = ("case", "kind", "stands", "reason", "vertical_N", "horizontal_N", "slide_ratio",
         "tip_margin", "max_deflection", "utilisation", "load_ratio", "load_ratio_limit",
         "max_plastic_strain", "plastic_area_share")  # fmt: skip


def _num(v: Any) -> Any:
    if v is None:
        return ""
    return f"{v:.10g}" if isinstance(v, float) else v


def cases_csv(outdoors: Mapping[str, Any]) -> str:
    """The CSV text of the report's ``outdoors`` section."""
    k = len(outdoors["feet"])
    head = list(_BASE)
    for i in range(1, k + 1):
        head += [f"foot{i}_x_N", f"foot{i}_y_N", f"foot{i}_z_N", f"foot{i}_ballast_kg"]
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(head)
    for c in outdoors["cases"]:
        row = [c["name"], c["kind"], c["stands"], c["reason"], c["vertical_N"],
               c["horizontal_N"], c["slide_ratio"], c["tip_margin"], c["max_deflection"],
               c["utilisation"]]  # fmt: skip
        s = c.get("strength") or {}
        row += [s.get("load_ratio"), s.get("limit"), s.get("max_plastic_strain"),
                s.get("plastic_area_share")]  # fmt: skip
        for r, b in zip(c["reactions_N"], c["ballast_kg"], strict=True):
            row += [*r, b]
        w.writerow([_num(v) for v in row])
    return out.getvalue()


def write_cases_csv(outdoors: Mapping[str, Any], path: str | os.PathLike[str]) -> Path:
    """Write NAME-loads.csv atomically; return the path."""
    text = cases_csv(outdoors)
    with atomic_output(path) as tmp:
        Path(tmp).write_text(text, encoding="utf-8")
    return Path(path)
