"""Small sweeps the sweep's tests share: the paper model's square sheet
(table1-row1: a few hundredths of a second a design), four designs."""

from __future__ import annotations

import pytest

from onefold_cad.sweep.plan import make_plan
from onefold_cad.sweep.runner import run_sweep

SMALL = ("table1-row1", ["alpha=30:50:2", "beta=30,40"])


def table_rows(folder):
    """results.parquet as a list of dicts."""
    import pyarrow.parquet as pq

    return pq.read_table(folder / "results.parquet").to_pylist()


@pytest.fixture(scope="session")
def small_run(tmp_path_factory):
    """The small sweep run in this process, with bends, mass and objectives."""
    folder = tmp_path_factory.mktemp("small")
    plan = make_plan(
        *SMALL,
        measures=["bends", "mass"],
        images=False,
        objectives="max:tipping_margin_deg,target:height=300",
    )
    run = run_sweep(plan, folder, jobs=1, quiet=True)
    return plan, folder, run
