"""The sweep's tables, rebuilt from its journal's rows.

* ``results.parquet`` (pyarrow, imported here only): one row per design of
  the sweep, in its order: key, name, status, error, seconds, the varied
  inputs, every measured output (empty where the design failed), ``img``
  with thumbnails and ``pareto`` with objectives. Each field's metadata
  holds its ``unit`` (``mm``, ``deg``, ``kg``...; the design unit when every
  design has the same), ``role`` (row, input, output) and ``description``;
  the schema's metadata ``onefold.sweep`` holds the sweep (JSON: template,
  fixed flags, varies, sampler, measures, objectives).
* ``data.csv`` for Design Explorer: the designs that solved, inputs as
  ``in:NAME``, number outputs as ``out:NAME`` (a yes/no as 1/0; an output
  no design has, such as a mass without a density, left out), a unit in
  parentheses after the name (``out:height (mm)``), ``img`` naming the
  thumbnail (``img/KEY.png``, relative to the file), and ``name`` and
  ``key`` (which Design Explorer ignores).
* ``pareto.csv``: the Pareto designs (plain column names, the first
  objective's best first).
"""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from onefold_cad.export.atomic import atomic_output
from onefold_cad.sweep.measures import Column, resolve_unit
from onefold_cad.sweep.plan import ROW_COLUMNS, SweepPlan
from onefold_cad.version import __version__

__all__ = ["column_units", "plan_metadata", "table_columns", "write_csv", "write_parquet"]

_ARROW = {"float": "float64", "int": "int64", "bool": "bool_", "str": "string"}


def table_columns(plan: SweepPlan) -> list[tuple[str, Column]]:
    """``(role, column)`` of every column of results.parquet, in order."""
    cols = [("row", c) for c in ROW_COLUMNS]
    cols += [("input", c) for c in plan.input_columns]
    cols += [("output", c) for c in plan.output_columns]
    if plan.images:
        cols.append(("row", Column("img", "str", "", "the thumbnail, relative to DIR")))
    if plan.objectives:
        cols.append(("row", Column("pareto", "bool", "", "on the Pareto front of --objectives")))
    seen: set[str] = set()  # a varied --units is also the units output: once
    out = []
    for role, column in cols:
        if column.name not in seen:
            seen.add(column.name)
            out.append((role, column))
    return out


def column_units(columns: Sequence[Column], rows: Sequence[dict[str, Any]]) -> dict[str, str]:
    """The concrete unit of each column (its kind resolved with the rows'
    design unit and mass unit when all rows share one, else the kind's words)."""
    units = {str(r["units"]) for r in rows if r.get("units")}
    masses = {str(r["mass_unit"]) for r in rows if r.get("mass_unit")}
    out = {}
    for c in columns:
        if c.unit in ("length", "length^2") and len(units) != 1:
            out[c.name] = "design unit" + ("^2" if c.unit == "length^2" else "") + " (units)"
        elif c.unit == "mass" and len(masses) > 1:
            out[c.name] = "kg or lb (mass_unit)"
        else:
            unit = next(iter(units)) if units else "mm"
            out[c.name] = resolve_unit(c.unit, unit, next(iter(masses)) if masses else None)
    return out


def plan_metadata(plan: SweepPlan) -> dict[str, Any]:
    """The sweep as plain data (the schema's ``onefold.sweep`` metadata)."""
    return {
        "onefold_cad": __version__,
        "template": plan.template,
        "fixed": plan.fixed,
        "vary": [s.text for s in plan.specs],
        "sampler": plan.sampler,
        "samples": plan.samples,
        "seed": plan.seed,
        "measures": list(plan.measures),
        "simulation": plan.settings,
        "objectives": [o.text for o in plan.objectives],
        "designs": len(plan.points),
    }


def write_parquet(path: Path, plan: SweepPlan, rows: Sequence[dict[str, Any]]) -> None:
    """Write results.parquet (see the module docstring)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    cols = table_columns(plan)
    units = column_units([c for _, c in cols], rows)
    fields, arrays = [], []
    for role, c in cols:
        meta = {"unit": units[c.name], "role": role, "description": c.help}
        kind = getattr(pa, _ARROW[c.kind])()
        fields.append(pa.field(c.name, kind, metadata=meta))
        values = [r.get(c.name) for r in rows]
        if c.kind == "float":
            values = [None if v is None else float(v) for v in values]
        arrays.append(pa.array(values, type=kind))
    schema = pa.schema(fields, metadata={"onefold.sweep": json.dumps(plan_metadata(plan))})
    table = pa.Table.from_arrays(arrays, schema=schema)
    with atomic_output(path) as tmp:
        pq.write_table(table, tmp)


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def write_csv(
    path: Path, plan: SweepPlan, rows: Sequence[dict[str, Any]], design_explorer: bool = True
) -> None:
    """Write ``rows`` as data.csv for Design Explorer (``in:``/``out:``
    prefixes, units, ``img``; only the designs that solved) or, without
    ``design_explorer``, every column under its plain name (pareto.csv)."""
    cols = table_columns(plan)
    units = column_units([c for _, c in cols], rows)
    if design_explorer:
        rows = [r for r in rows if r.get("status") == "ok"]
        picked = [
            (f"in:{c.name}", c) for role, c in cols if role == "input" and c.name != "rectangle"
        ]
        picked += [  # an output no design has (a mass without a density) is left out
            (f"out:{c.name}", c)
            for role, c in cols
            if role == "output" and c.kind != "str" and any(r.get(c.name) is not None for r in rows)
        ]
        if plan.objectives:
            picked.append(("out:pareto", Column("pareto", "bool", "", "")))
        header = [f"{h} ({units[c.name]})" if units.get(c.name) else h for h, c in picked]
        extra = [("img", "img")] if plan.images else []
        extra += [("name", "name"), ("key", "key")]
        header += [h for h, _ in extra]
        names = [c.name for _, c in picked] + [n for _, n in extra]
    else:
        header = names = [c.name for _, c in cols]
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for r in rows:
        w.writerow([_cell(r.get(n)) for n in names])
    with atomic_output(path) as tmp:
        Path(tmp).write_text(buf.getvalue(), encoding="utf-8")
