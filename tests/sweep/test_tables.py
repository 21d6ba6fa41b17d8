"""The sweep's files: results.parquet with units in its metadata, data.csv in
Design Explorer's format, pareto.csv with the front."""

from __future__ import annotations

import csv
import json
import math

import numpy as np

from onefold_cad.sweep.pareto import costs, pareto_front
from onefold_cad.sweep.plan import make_plan
from onefold_cad.sweep.runner import run_sweep
from tests.sweep.conftest import SMALL, table_rows


def test_results_parquet_has_every_column_with_its_unit(small_run):
    import pyarrow.parquet as pq

    plan, folder, _ = small_run
    schema = pq.read_schema(folder / "results.parquet")
    meta = {f.name: {k.decode(): v.decode() for k, v in f.metadata.items()} for f in schema}
    names = list(meta)
    assert names[:5] == ["key", "name", "status", "error", "seconds"]
    assert names[5:7] == ["alpha", "beta"] and names[-1] == "pareto"
    assert {c.name for c in plan.output_columns} <= set(names)
    assert meta["alpha"] == {
        "unit": "deg",
        "role": "input",
        "description": "arc opening alpha, deg in (0, 90)",
    }
    assert meta["height"]["unit"] == "mm" and meta["height"]["role"] == "output"
    assert meta["footprint_area"]["unit"] == "mm^2" and meta["seconds"]["unit"] == "s"
    assert meta["tipping_margin_deg"]["unit"] == "deg" and meta["mass"]["unit"] == "kg"
    sweep = json.loads(schema.metadata[b"onefold.sweep"])
    assert sweep["vary"] == SMALL[1] and sweep["measures"] == ["rest", "bends", "mass"]
    assert sweep["objectives"] == ["max:tipping_margin_deg", "target:height=300"]


def test_data_csv_is_design_explorer_s_format(small_run):
    plan, folder, _ = small_run
    with open(folder / "data.csv", newline="") as fh:
        table = list(csv.reader(fh))
    header, body = table[0], table[1:]
    assert len(body) == 4
    ins = [h for h in header if h.startswith("in:")]
    outs = [h for h in header if h.startswith("out:")]
    assert ins == ["in:alpha (deg)", "in:beta (deg)"]
    assert "out:height (mm)" in outs and "out:tipping_margin_deg (deg)" in outs
    assert "out:stable" in outs and "out:pareto" in outs
    assert set(header) - set(ins) - set(outs) == {"name", "key"}  # no img: --no-images
    rows = {r["key"]: r for r in table_rows(folder)}
    for line in body:
        cell = dict(zip(header, line, strict=True))
        row = rows[cell["key"]]
        for h in ins + outs:  # every prefixed cell is a number
            assert math.isfinite(float(cell[h]))
        assert float(cell["out:height (mm)"]) == row["height"]
        assert cell["out:stable"] == ("1" if row["stable"] else "0")


def test_pareto_csv_is_the_front_of_the_rows(small_run):
    plan, folder, run = small_run
    rows = table_rows(folder)
    table = {o.column: [r[o.column] for r in rows] for o in plan.objectives}
    front = pareto_front(costs(plan.objectives, table))
    with open(folder / "pareto.csv", newline="") as fh:
        got = list(csv.DictReader(fh))
    assert sorted(r["key"] for r in got) == sorted(
        r["key"] for r, f in zip(rows, front, strict=True) if f
    )
    assert [r["pareto"] for r in rows] == list(front) and run.files.front == int(front.sum())
    margins = [float(r["tipping_margin_deg"]) for r in got]
    assert margins == sorted(margins, reverse=True)  # the first objective's best first


def test_thumbnails_are_named_in_the_img_column(tmp_path):
    plan = make_plan(SMALL[0], ["alpha=30,40"])
    assert plan.images  # on by default for a small sweep
    run_sweep(plan, tmp_path, jobs=1, quiet=True)
    with open(tmp_path / "data.csv", newline="") as fh:
        body = list(csv.DictReader(fh))
    assert [r["img"] for r in body] == [f"img/{k}.png" for k in plan.keys]
    for r in body:
        assert (tmp_path / r["img"]).read_bytes().startswith(b"\x89PNG")
    assert np.all([r["img"] for r in table_rows(tmp_path)])
    assert (tmp_path / "parallel.png").read_bytes().startswith(b"\x89PNG")
