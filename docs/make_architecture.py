"""Draw docs/images/architecture.png: the package's layers from its own imports.

Reads every module of onefold_cad with the AST (imports at module top, inside
functions and under TYPE_CHECKING all count), groups the modules by folder
into the layers of :data:`onefold_cad.layers.LAYERS`, and draws one box per
folder or top-level module, its layer's row, the number of modules in it, and
one arrow per pair of boxes that import each other's modules, labelled with
how many imports it stands for. Arrows only ever point down a layer or more:
the picture shows it (and tests/test_layers.py asserts it).

Run from the repository root: ``.venv/bin/python docs/make_architecture.py``.
"""

from __future__ import annotations

import collections
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "images" / "architecture.png"
sys.path.insert(0, str(ROOT))

from onefold_cad.layers import LAYERS, import_graph, layer_of  # noqa: E402


def graph() -> tuple[dict[str, int], collections.Counter[tuple[str, str]]]:
    """Boxes (the layers' folders and modules) with their module counts, and
    the imports between boxes: (from, to) -> count."""
    sizes: collections.Counter[str] = collections.Counter()
    edges: collections.Counter[tuple[str, str]] = collections.Counter()
    for name, imports in import_graph().items():
        here = layer_of(name)
        if here is None:
            continue
        sizes[here[1]] += 1
        for t in imports:
            there = layer_of(t)
            if there is not None and there[1] != here[1]:
                edges[(here[1], there[1])] += 1
    return dict(sizes), edges


def draw(path: Path = OUT) -> Path:
    """Draw the picture to ``path`` (PNG) and return it."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sizes, edges = graph()
    rows = [(label, [n for n in names if n in sizes] or list(names[:1])) for label, names in LAYERS]
    rows = [(label, names) for label, names in rows]
    place: dict[str, tuple[float, float]] = {}
    fig, ax = plt.subplots(figsize=(11, 0.72 * len(rows) + 0.8), dpi=110)
    for i, (label, names) in enumerate(rows):
        y = i
        ax.text(-0.55, y, label, ha="right", va="center", fontsize=10, color="0.35")
        for j, n in enumerate(names):
            x = (j + 0.5) / len(names) * 6.0 - 0.5 if len(names) > 1 else 2.5
            place[n] = (x, y)
            present = n in sizes
            text = n.removeprefix("onefold_cad.")
            text = f"{text}/" if (ROOT / "onefold_cad" / text).is_dir() else text
            text += f"  ({sizes[n]})" if present else "  (to come)"
            ax.text(
                x, y, text, ha="center", va="center", fontsize=9,
                color="black" if present else "0.55",
                bbox={"boxstyle": "round,pad=0.35", "fc": "#eef2f7" if present else "white",
                      "ec": "#4a6fa5" if present else "0.7", "ls": "-" if present else "--"},
            )  # fmt: skip
    for (a, b), count in sorted(edges.items()):
        (x0, y0), (x1, y1) = place[a], place[b]
        ax.annotate(
            "", xy=(x1, y1 + 0.22), xytext=(x0, y0 - 0.22),
            arrowprops={"arrowstyle": "->", "color": "#4a6fa5", "alpha": 0.45,
                        "lw": 0.6 + 0.25 * min(count, 12) ** 0.5,
                        "connectionstyle": "arc3,rad=0.08"},
        )  # fmt: skip
    ax.set_xlim(-2.2, 6.0)
    ax.set_ylim(len(rows) - 0.4, -0.6)
    ax.invert_yaxis()
    ax.axis("off")
    ax.set_title(
        "onefold_cad: layers drawn from the imports (arrows: imports, always downward; "
        "(n): modules)",
        fontsize=10,
    )
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, metadata={"Software": None})
    plt.close(fig)
    return path


if __name__ == "__main__":
    print(draw())
