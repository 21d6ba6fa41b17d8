"""The JSON report written as ``NAME.json``, atomically (the report itself is
:func:`onefold_cad.fabrication.report.design_report`)."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from onefold_cad.errors import ExportError
from onefold_cad.export.atomic import atomic_output
from onefold_cad.fabrication.report import report_json

__all__ = ["write_report"]


def write_report(path: str | os.PathLike[str], report: Mapping[str, Any]) -> Path:
    """Write ``report`` as JSON to ``path`` atomically (temp name, then rename).

    Raises:
        ExportError: the report holds a non-finite number (naming its key)
            or another value JSON cannot hold, or the file could not be
            written.
    """
    out = Path(path)
    try:
        text = report_json(report)
    except (TypeError, ValueError) as exc:
        raise ExportError(f"report of {report.get('name')!r} is not valid JSON: {exc}") from exc
    with atomic_output(out) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return out
