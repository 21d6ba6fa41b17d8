"""The package's layers, lowest first, and its imports read from its source:
a module imports only modules of its own layer or of layers below it, in any
form (at module top, inside a function, under ``TYPE_CHECKING``).
docs/make_architecture.py draws them from :func:`import_graph`;
tests/test_layers.py and ``make lint`` (import-linter) hold the code to them.
Standard library only.

Each layer is a tuple of module or package names side by side (neither
imports the other).
"""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

__all__ = [
    "LAYERS",
    "PACKAGE",
    "ROOT",
    "cycles",
    "import_graph",
    "imported",
    "layer_of",
    "module_name",
    "modules",
]

#: (name of the layer, its modules and packages), lowest first.
LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("errors", ("onefold_cad.errors", "onefold_cad.version", "onefold_cad.layers")),
    ("choices", ("onefold_cad.choices",)),
    ("geometry", ("onefold_cad.geometry",)),
    ("design", ("onefold_cad.design",)),
    ("toml_file", ("onefold_cad.toml_file",)),
    ("templates", ("onefold_cad.templates",)),
    ("fabrication", ("onefold_cad.fabrication",)),
    ("fit", ("onefold_cad.fit",)),
    ("mechanics", ("onefold_cad.mechanics",)),
    ("site", ("onefold_cad.site",)),
    ("export", ("onefold_cad.export",)),
    ("flags", ("onefold_cad.flags",)),
    ("commands", ("onefold_cad.sweep",)),
    ("compensate", ("onefold_cad.compensate",)),
    ("explore", ("onefold_cad.explore",)),
    ("hops", ("onefold_cad.hops",)),
    ("cli", ("onefold_cad.cli",)),
    ("main", ("onefold_cad.__main__",)),
)


def layer_of(module: str) -> tuple[int, str] | None:
    """``(index, top name)`` of the layer ``module`` (dotted) belongs to, the
    index counted from the lowest layer; None for the package itself
    (``onefold_cad``, the public API, which may name anything)."""
    for i, (_, names) in enumerate(LAYERS):
        for name in names:
            if module == name or module.startswith(name + "."):
                return i, name
    return None


#: The repository (the package's parent folder) and the package's folder.
ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "onefold_cad"


def module_name(path: Path) -> str:
    """``onefold_cad.geometry.sheet`` for onefold_cad/geometry/sheet.py (a
    package's ``__init__.py`` is the package)."""
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def modules() -> dict[str, Path]:
    """Every module of the package: dotted name -> file."""
    return {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imported(path: Path, known: set[str]) -> Iterator[tuple[str, int]]:
    """The package's modules that ``path`` imports (the longest known prefix of
    each import, a name imported from a package counting as its submodule
    when it is one), with the line of the import."""
    name = module_name(path)
    is_package = path.name == "__init__.py"
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".") if is_package else name.split(".")[:-1]
                base = base[: len(base) - (node.level - 1)]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            targets = [f"{mod}.{a.name}" for a in node.names]
        else:
            continue
        for target in targets:
            while target and target not in known:
                target = target.rpartition(".")[0]
            if target and target != name:
                yield target, node.lineno


def import_graph() -> dict[str, dict[str, int]]:
    """module -> {imported module: line of the first such import}."""
    mods = modules()
    known = set(mods)
    graph: dict[str, dict[str, int]] = {}
    for name, path in mods.items():
        edges: dict[str, int] = {}
        for target, line in imported(path, known):
            edges.setdefault(target, line)
        graph[name] = edges
    return graph


def cycles(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, {}):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out
