"""onefold_cad: the One-Fold curved-origami construction as fabrication files.

The core (:mod:`onefold_cad.geometry`) is pure numpy/scipy; the adapters in
:mod:`onefold_cad.export` turn its results into STEP (build123d), DXF (ezdxf),
previews and JSON reports.
"""

from onefold_cad.design import Design, build_design
from onefold_cad.errors import (
    ExportError,
    FabricationError,
    InvalidParameterError,
    InvalidSheetError,
    NoSolutionError,
    OneFoldError,
)
from onefold_cad.geometry.folding import CreaseHalf, Developability, FoldedSheet, fold
from onefold_cad.geometry.material import BendValues, Material, SheetSurface, Units, bend_values
from onefold_cad.geometry.params import FrameCurve, Model
from onefold_cad.geometry.placement import RestingPlacement
from onefold_cad.geometry.sheet import Placement2D, Sheet
from onefold_cad.geometry.solver import Solution, solve

__version__ = "0.1.0"

__all__ = [
    "BendValues",
    "CreaseHalf",
    "Design",
    "Developability",
    "ExportError",
    "FabricationError",
    "FoldedSheet",
    "FrameCurve",
    "InvalidParameterError",
    "InvalidSheetError",
    "Material",
    "Model",
    "NoSolutionError",
    "OneFoldError",
    "Placement2D",
    "RestingPlacement",
    "Sheet",
    "SheetSurface",
    "Solution",
    "Units",
    "bend_values",
    "build_design",
    "fold",
    "solve",
]
