"""The package's layers, lowest first: a module imports only modules of its own
layer or of layers below it, in any form (at module top, inside a function,
under ``TYPE_CHECKING``). docs/architecture.md draws them from the imports;
the tests (tests/architecture/) and ``make lint`` (import-linter) hold the
code to them.

Each layer is a tuple of module or package names side by side (neither
imports the other).
"""

from __future__ import annotations

__all__ = ["LAYERS", "layer_of"]

#: (name of the layer, its modules and packages), lowest first.
LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("errors", ("onefold_cad.errors", "onefold_cad.version", "onefold_cad.layers")),
    ("choices", ("onefold_cad.choices",)),
    ("geometry", ("onefold_cad.geometry",)),
    ("design", ("onefold_cad.design",)),
    ("templates", ("onefold_cad.templates",)),
    ("fabrication", ("onefold_cad.fabrication",)),
    ("mechanics", ("onefold_cad.mechanics",)),
    ("export", ("onefold_cad.export",)),
    ("flags", ("onefold_cad.flags",)),
    ("commands", ("onefold_cad.explore", "onefold_cad.fit", "onefold_cad.sweep")),
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
