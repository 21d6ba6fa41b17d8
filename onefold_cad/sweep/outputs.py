"""The sweep's files, rebuilt from its journal: results.parquet, data.csv,
pareto.csv (with ``--objectives``) and parallel.png (the designs in
parallel coordinates, the Pareto front marked). Rebuilt at the end of every
run, and when a run is stopped, from every row the journal holds for the
sweep's designs (in the sweep's order, each once).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad.sweep.journal import JOURNAL, read_journal
from onefold_cad.sweep.pareto import costs, pareto_front
from onefold_cad.sweep.plan import SweepPlan
from onefold_cad.sweep.tables import column_units, table_columns, write_csv, write_parquet

__all__ = ["PICTURE", "SweepFiles", "finished_rows", "write_outputs"]

#: The picture's file name.
PICTURE = "parallel.png"
#: Outputs always drawn (when measured), after the inputs and objectives.
_DRAWN = ("height", "span", "tipping_margin_deg", "mass")


@dataclass(frozen=True)
class SweepFiles:
    """What :func:`write_outputs` wrote.

    Attributes:
        rows: designs with a row (of the sweep's).
        ok: those that solved.
        front: those on the Pareto front.
        files: the files written.
    """

    rows: int
    ok: int
    front: int
    files: tuple[Path, ...]


def finished_rows(plan: SweepPlan, folder: Path) -> list[dict[str, Any]]:
    """The journal's rows of the sweep's designs, in its order (lost ones left out)."""
    journal = read_journal(folder / JOURNAL)
    rows = (journal.get(k) for k in plan.keys)
    return [r for r in rows if r is not None and r.get("status") != "lost"]


def _front(plan: SweepPlan, rows: list[dict[str, Any]]) -> np.ndarray:
    ok = [i for i, r in enumerate(rows) if r.get("status") == "ok"]
    mask = np.zeros(len(rows), dtype=bool)
    if not plan.objectives or not ok:
        return mask
    table = {
        o.column: [np.nan if rows[i].get(o.column) is None else rows[i][o.column] for i in ok]
        for o in plan.objectives
    }
    mask[np.asarray(ok)[pareto_front(costs(plan.objectives, table))]] = True
    return mask


def _picture(plan: SweepPlan, rows: list[dict[str, Any]], front: np.ndarray, path: Path) -> None:
    from onefold_cad.export.pictures.sweep_plot import draw_parallel_coordinates

    ok = [r for r in rows if r.get("status") == "ok"]
    on = front[[i for i, r in enumerate(rows) if r.get("status") == "ok"]]
    cols = [c for _, c in table_columns(plan)]
    units = column_units(cols, ok)
    numeric = {c.name: c for c in cols if c.kind in ("float", "int")}
    names = [c.name for c in plan.input_columns if c.name in numeric and c.name != "seconds"]
    names += [o.column for o in plan.objectives]
    names += [n for n in _DRAWN if n in numeric]
    names = list(dict.fromkeys(names))

    def values(name: str) -> np.ndarray:
        return np.array([np.nan if r.get(name) is None else float(r[name]) for r in ok])

    axes = [(n, units.get(n, ""), values(n)) for n in names]
    axes = [a for a in axes if np.isfinite(a[2]).any()]  # a column no design has (no density)
    shade = plan.objectives[0].column if plan.objectives else "tipping_margin_deg"
    unit = units.get(shade, "")
    failed = len(rows) - len(ok)
    what = (
        f", Pareto front of {', '.join(o.text for o in plan.objectives)}" if plan.objectives else ""
    )
    name = str(plan.raw.get("name", Path(plan.template).stem))
    title = f"{name}: {len(ok)} designs" + (f" ({failed} failed)" if failed else "") + what
    draw_parallel_coordinates(
        path,
        axes,
        front=on if plan.objectives else None,
        colour=(f"{shade} ({unit})" if unit else shade, values(shade)),
        title=title,
    )


def write_outputs(plan: SweepPlan, folder: Path) -> SweepFiles:
    """Rebuild the sweep's files in ``folder`` from its journal."""
    rows = finished_rows(plan, folder)
    front = _front(plan, rows)
    if plan.objectives:
        rows = [{**r, "pareto": bool(f)} for r, f in zip(rows, front, strict=True)]
    files = [folder / "results.parquet", folder / "data.csv"]
    write_parquet(files[0], plan, rows)
    write_csv(files[1], plan, rows)
    if plan.objectives:
        best = [r for r, f in zip(rows, front, strict=True) if f]
        first = plan.objectives[0]
        best.sort(key=lambda r: float(first.cost(np.array([r[first.column]]))[0]))
        files.append(folder / "pareto.csv")
        write_csv(files[-1], plan, best, design_explorer=False)
    ok = sum(r.get("status") == "ok" for r in rows)
    if ok:
        files.append(folder / PICTURE)
        _picture(plan, rows, front, files[-1])
    return SweepFiles(len(rows), ok, int(front.sum()), tuple(files))
