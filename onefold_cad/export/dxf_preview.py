"""PNG/SVG preview of a DXF flat pattern, rendered by ezdxf's drawing add-on.

SVG uses ezdxf's own SVG back-end (no matplotlib); PNG uses the matplotlib
back-end, imported only here and only when a PNG is asked for. The file is
written atomically (temporary file in the same directory, then replaced).
"""

from __future__ import annotations

import os
from pathlib import Path

import ezdxf
from ezdxf.addons.drawing import Frontend, RenderContext
from ezdxf.addons.drawing.config import BackgroundPolicy, Configuration
from ezdxf.document import Drawing

from onefold_cad.errors import InvalidParameterError
from onefold_cad.export.dxf import atomic_output

__all__ = ["render_preview"]

_CONFIG = Configuration(background_policy=BackgroundPolicy.WHITE)


def _svg(doc: Drawing, out: Path) -> None:
    from ezdxf.addons.drawing import layout, svg

    backend = svg.SVGBackend()
    Frontend(RenderContext(doc), backend, config=_CONFIG).draw_layout(doc.modelspace())
    page = layout.Page(0, 0, layout.Units.mm, margins=layout.Margins.all(5))
    out.write_text(backend.get_string(page), encoding="utf-8")


def _png(doc: Drawing, out: Path, dpi: int) -> None:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend

    fig = plt.figure(figsize=(8, 8))
    try:
        ax = fig.add_axes((0, 0, 1, 1))
        Frontend(RenderContext(doc), MatplotlibBackend(ax), config=_CONFIG).draw_layout(
            doc.modelspace(), finalize=True
        )
        fig.savefig(out, dpi=dpi, format="png")
    finally:
        plt.close(fig)


def render_preview(
    dxf: Drawing | str | os.PathLike[str], out_path: str | os.PathLike[str], *, dpi: int = 150
) -> Path:
    """Render the modelspace of a DXF document or file to PNG or SVG.

    Args:
        dxf: an ezdxf document or the path of a DXF file.
        out_path: '.png' or '.svg' (chosen by the suffix).
        dpi: PNG resolution (dots per inch), 10..1200.

    Returns:
        The path written.
    """
    out = Path(out_path)
    kind = out.suffix.lower()
    if kind not in (".png", ".svg"):
        raise InvalidParameterError("out_path", f"must end in .png or .svg, got {out.name!r}")
    if not 10 <= int(dpi) <= 1200:
        raise InvalidParameterError("dpi", f"must be in [10, 1200], got {dpi}")
    doc = dxf if isinstance(dxf, Drawing) else ezdxf.readfile(dxf)
    with atomic_output(out) as tmp:
        _svg(doc, tmp) if kind == ".svg" else _png(doc, tmp, int(dpi))
    return out
