"""The task a worker runs: a batch of designs in, their rows out, plain data
both ways (a process pool pickles it, a Dask cluster ships it to machines
that share no files with this one: the template travels as its data, a
thumbnail comes back as PNG bytes).

A design that fails (a combination of values the design refuses, a solver
with no solution, any exception) gives a row with status ``error`` and the
error's one line; the batch goes on.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from onefold_cad.design import fold_design
from onefold_cad.fabrication.rules import resting_placement
from onefold_cad.flags.jobs import template_job
from onefold_cad.sweep.measures import MEASURES

__all__ = ["Batch", "evaluate_batch", "evaluate_design"]


@dataclass(frozen=True)
class Batch:
    """Designs for one worker.

    Attributes:
        template: the template's path (named in messages) and ``raw`` its data.
        implicit: no template was named (designs are named as solve names them).
        designs: ``(key, flags)`` of each design (flags: dest -> value).
        measures: the measure names (``rest`` first).
        images: also draw each design's thumbnail.
        settings: the measures' settings as ``(name, value)`` pairs
            (:attr:`~onefold_cad.sweep.plan.SweepPlan.simulation`).
    """

    template: str
    raw: dict[str, Any]
    implicit: bool
    designs: tuple[tuple[str, dict[str, Any]], ...]
    measures: tuple[str, ...]
    images: bool = False
    settings: tuple[tuple[str, Any], ...] = ()


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    from onefold_cad.errors import OneFoldError

    return text if isinstance(exc, OneFoldError) else f"{type(exc).__name__}: {text}"


def evaluate_design(
    template: str,
    raw: dict[str, Any],
    flags: dict[str, Any],
    measures: Sequence[str],
    implicit: bool = False,
    images: bool = False,
    memo: dict[str, Any] | None = None,
    settings: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """One design's row: ``name``, ``status``, ``error``, ``seconds``, the
    measures' columns (None where the design failed) and, with ``images``,
    ``png`` (the thumbnail's bytes). ``memo``: shared by the designs of one
    template (:func:`~onefold_cad.flags.jobs.template_job`); ``settings``: the
    measures' (name -> value, ``simulate``'s options)."""
    t0 = time.perf_counter()
    row: dict[str, Any] = {"name": None, "status": "ok", "error": ""}
    try:
        design = template_job(raw, template, flags, None, implicit, memo).design
        row["name"] = design.name
        folded = fold_design(design)
        rest = resting_placement(design, folded)
        for m in measures:
            row.update(MEASURES[m].compute(design, folded, rest, settings or {}))
        if images:
            from onefold_cad.export.preview import thumbnail_png

            row["png"] = thumbnail_png(folded, rest)
    except Exception as exc:  # a failing design is a row, never the end of the sweep
        row.update(status="error", error=_one_line(exc))
        row.pop("png", None)
        for m in measures:  # no half-measured failure: every output is empty
            row.update(dict.fromkeys((c.name for c in MEASURES[m].columns), None))
    row["seconds"] = time.perf_counter() - t0
    return row


def evaluate_batch(batch: Batch) -> list[dict[str, Any]]:
    """The rows of a batch's designs, in its order, each with its ``key``
    (what depends on the template alone made once for the batch)."""
    memo: dict[str, Any] = {}
    b = batch
    settings = dict(b.settings)
    return [
        {
            "key": key,
            **evaluate_design(
                b.template, b.raw, flags, b.measures, b.implicit, b.images, memo, settings
            ),
        }
        for key, flags in b.designs
    ]
