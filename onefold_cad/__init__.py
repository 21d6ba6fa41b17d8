"""onefold_cad: the One-Fold curved-origami construction as fabrication files.

The core (:mod:`onefold_cad.geometry`) is pure numpy; the fabrication rules
(:mod:`onefold_cad.fabrication`) too; the adapters in :mod:`onefold_cad.export`
turn their results into STEP (build123d), DXF (ezdxf), previews and JSON
reports. docs/architecture.md draws the layers.

The public names below are imported on first use (PEP 562), so importing a
submodule such as :mod:`onefold_cad.cli.main` does not load the geometry core
until a command needs it (``onefold --help`` starts in a few milliseconds).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from onefold_cad.version import __version__

#: public name -> the module that defines it
_EXPORTS: dict[str, str] = {
    "Design": "onefold_cad.design",
    "build_design": "onefold_cad.design",
    "ExportError": "onefold_cad.errors",
    "FabricationError": "onefold_cad.errors",
    "InvalidParameterError": "onefold_cad.errors",
    "InvalidSheetError": "onefold_cad.errors",
    "NoSolutionError": "onefold_cad.errors",
    "OneFoldError": "onefold_cad.errors",
    "CreaseHalf": "onefold_cad.geometry.folding",
    "Developability": "onefold_cad.geometry.developability",
    "FoldedSheet": "onefold_cad.geometry.folding",
    "fold": "onefold_cad.geometry.folding",
    "BendValues": "onefold_cad.geometry.bend_model",
    "Material": "onefold_cad.geometry.material",
    "SheetSurface": "onefold_cad.choices",
    "Units": "onefold_cad.choices",
    "bend_values": "onefold_cad.geometry.bend_model",
    "FrameCurve": "onefold_cad.geometry.frame_curve",
    "Model": "onefold_cad.choices",
    "RestingPlacement": "onefold_cad.geometry.resting.placement",
    "Placement2D": "onefold_cad.geometry.sheet",
    "Sheet": "onefold_cad.geometry.sheet",
    "Solution": "onefold_cad.geometry.solver",
    "solve": "onefold_cad.geometry.solver",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'onefold_cad' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *_EXPORTS])


if TYPE_CHECKING:  # static type checkers and IDEs see the names directly
    # ruff: noqa: F401
    from onefold_cad.choices import Model, SheetSurface, Units
    from onefold_cad.design import Design, build_design
    from onefold_cad.errors import (
        ExportError,
        FabricationError,
        InvalidParameterError,
        InvalidSheetError,
        NoSolutionError,
        OneFoldError,
    )
    from onefold_cad.geometry.bend_model import BendValues, bend_values
    from onefold_cad.geometry.developability import Developability
    from onefold_cad.geometry.folding import CreaseHalf, FoldedSheet, fold
    from onefold_cad.geometry.frame_curve import FrameCurve
    from onefold_cad.geometry.material import Material
    from onefold_cad.geometry.resting.placement import RestingPlacement
    from onefold_cad.geometry.sheet import Placement2D, Sheet
    from onefold_cad.geometry.solver import Solution, solve
