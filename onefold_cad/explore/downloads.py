"""The page's downloads: the current design as DXF, STEP, Rhino 3DM, JSON
report, TOML or the cones' forming sheet (``NAME-cones.csv``).

Each file is made by the package's own writer (the same calls as ``onefold
build``) into a private temporary folder and returned as bytes; no path
comes from the page. Only the STEP runs the CAD kernel, one at a time. The
3DM needs rhino3dm (the ``rhino`` extra); without it the download is refused
with a line saying so.
"""

from __future__ import annotations

import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

from onefold_cad.design import Design, fold_design
from onefold_cad.errors import ExportError, not_installed

__all__ = ["KINDS", "Download", "make_download"]

#: Download kind -> (file suffix, MIME type).
KINDS: dict[str, tuple[str, str]] = {
    "dxf": (".dxf", "application/dxf"),
    "step": (".step", "application/step"),
    "3dm": (".3dm", "model/vnd.3dm"),
    "json": (".json", "application/json"),
    "toml": (".toml", "application/toml"),
    "cones": ("-cones.csv", "text/csv"),
}

_KERNEL = threading.Lock()  # OCC is not known to be thread-safe


@dataclass(frozen=True)
class Download:
    """A file for the browser: its name, MIME type and bytes."""

    filename: str
    mime: str
    body: bytes


def make_download(kind: str, design: Design) -> Download:
    """The file of ``kind`` ('dxf', 'step', '3dm', 'json', 'toml' or 'cones') for ``design``.

    Raises:
        KeyError: an unknown kind.
        OneFoldError: the writer refuses the design (the CLI's message).
    """
    suffix, mime = KINDS[kind]
    name = f"{design.name}{suffix}"
    if kind == "toml":
        import tomli_w

        from onefold_cad.templates import design_to_data

        return Download(name, mime, tomli_w.dumps(design_to_data(design)).encode("utf-8"))
    folded = fold_design(design)
    if kind == "json":
        from onefold_cad.fabrication.report import design_report, report_json

        return Download(name, mime, report_json(design_report(design, folded)).encode("utf-8"))
    if kind == "cones":
        from onefold_cad.export.cone_csv import cone_csv

        return Download(name, mime, cone_csv(design, folded).encode("utf-8"))
    with tempfile.TemporaryDirectory(prefix="onefold-explore-") as tmp:
        path = Path(tmp) / name
        if kind == "dxf":
            from onefold_cad.export.dxf.pattern import export_design_dxf

            export_design_dxf(design, path, folded)
        elif kind == "3dm":
            from onefold_cad.export.writers import WRITERS

            if not WRITERS["3dm"].available:
                raise ExportError(not_installed("the .3dm", ["rhino3dm"], "rhino"))
            from onefold_cad.export.rhino.file import write_3dm

            write_3dm(design, folded, path)
        else:
            from onefold_cad.export.brep.step import export_design_step

            with _KERNEL:
                export_design_step(design, path, folded)
        return Download(name, mime, path.read_bytes())
