"""The design flags of ``onefold build`` and ``onefold solve`` (and the
explorer's controls): :data:`DESIGN_FLAGS` lists every flag once, with its
parser; the choices are the enums' of :mod:`onefold_cad.choices`.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from onefold_cad.choices import (
    Body,
    Compensation,
    ConeForming,
    Model,
    Placement,
    SheetSurface,
    Units,
)

if TYPE_CHECKING:
    pass

__all__ = [
    "BODIES",
    "COMPENSATIONS",
    "CONE_FORMINGS",
    "DESIGN_FLAGS",
    "FLAG_OF",
    "MODELS",
    "PLACEMENTS",
    "SURFACES",
    "UNITS",
    "Flag",
    "parse_choice",
    "parse_float",
    "parse_int",
]


#: The choices of the flags, from the enums of :mod:`onefold_cad.choices`
#: (the default first where the flag has one).
MODELS = (Model.EXACT.value, Model.PAPER.value)
UNITS = tuple(u.value for u in Units)
SURFACES = tuple(s.value for s in SheetSurface)
BODIES = ("auto", Body.SOLID.value, Body.SHELL.value)
COMPENSATIONS = tuple(c.value for c in Compensation)
CONE_FORMINGS = tuple(c.value for c in ConeForming)
PLACEMENTS = tuple(p.value for p in Placement)


# -- flag values -------------------------------------------------------------------
def parse_float(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text.strip()!r} is not a number") from None


def parse_int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text.strip()!r} is not a whole number") from None


def parse_int_in(text: str, low: int, high: int, note: str = "", more: str = "") -> int:
    """A whole number in [``low``, ``high``]; ``note`` says what its values
    mean, ``more`` names what else the flag takes (its caller parses that)."""
    try:
        n = int(text)
    except ValueError:
        n = low - 1
    if not low <= n <= high:
        raise argparse.ArgumentTypeError(
            f"must be a whole number in [{low}, {high}]{note}{more}, got {text.strip()!r}"
        )
    return n


def parse_choice(values: Sequence[str], upper: bool = False) -> Callable[[str], str]:
    def parse(text: str) -> str:
        v = text.strip().upper() if upper else text.strip().lower()
        if v not in values:
            raise argparse.ArgumentTypeError(
                f"must be one of {', '.join(values)}, got {text.strip()!r}"
            )
        return v

    return parse


@dataclass(frozen=True)
class Flag:
    """A design flag shared by ``build`` and ``solve``."""

    dest: str
    flag: str
    kind: Callable[[str], Any]
    help: str
    group: str
    metavar: str | None = None


_FRAME = "frame curve (paper section 3.2; lengths in the design's unit)"


_SHEET = "sheet (fold frame: fold line on the x axis, H at the origin; design unit)"


_MAT = "material (lengths in the design's unit)"


_DESIGN = "design"


DESIGN_FLAGS: tuple[Flag, ...] = (
    Flag("model", "--model", parse_choice(MODELS), "exact: the cone over the arc; paper: the "
         "paper's fan of --divisions triangles (default: the template's)", _DESIGN, "exact|paper"),
    Flag("units", "--units", parse_choice(UNITS), "the design's length unit: the template's values "
         "are converted into it and the flags below are read in it", _DESIGN, "mm|in|ft"),
    Flag("alpha", "--alpha", parse_float, "arc opening alpha, deg in (0, 90)", _FRAME, "DEG"),
    Flag("beta", "--beta", parse_float, "tilt beta of the arc's plane, deg in (0, 90)", _FRAME,
         "DEG"),
    Flag("hc", "--hc", parse_float, "offset h_c of H from the f-line's midpoint (the paper's "
         "tables: R = 100); |h_c| < R cos(alpha)", _FRAME, "LENGTH"),
    Flag("hc_fraction", "--hc-fraction", parse_float, "where H sits on the f-line, whatever R "
         "and alpha: h_c as a fraction of the half f-line R cos(alpha), in (-1, 1) (0: the "
         "midpoint, -1 / 1: the -x / +x end; instead of --hc)", _FRAME, "F"),
    Flag("radius", "--radius", parse_float, "frame-curve radius R > 0, from 1e-6 to 1e6 times "
         "the sheet's size", _FRAME, "LENGTH"),
    Flag("divisions", "--divisions", parse_int, "triangles of the paper model's fan, in "
         "[1, 10000]", _FRAME, "N"),
    Flag("x_plus", "--x-plus", parse_float, "quadrilateral: distance from H to the +x vertex",
         _SHEET, "LENGTH"),
    Flag("x_minus", "--x-minus", parse_float, "quadrilateral: distance from H to the -x vertex",
         _SHEET, "LENGTH"),
    Flag("y_plus", "--y-plus", parse_float, "quadrilateral: distance from H to the +y vertex",
         _SHEET, "LENGTH"),
    Flag("y_minus", "--y-minus", parse_float, "quadrilateral: distance from H to the -y vertex",
         _SHEET, "LENGTH"),
    Flag("polygon", "--polygon", str, 'polygon sheet "x,y;x,y;...", star-shaped about H',
         _SHEET, "X,Y;..."),
    Flag("rectangle", "--rectangle", str, "rectangle folded along its diagonal", _SHEET,
         "WIDTHxHEIGHT"),
    Flag("apex_fraction", "--apex-fraction", parse_float, "rectangle: where H sits along the "
         "diagonal, in (0, 1)", _SHEET, "F"),
    Flag("thickness", "--thickness", parse_float, "sheet thickness t >= 0", _MAT, "LENGTH"),
    Flag("bend_radius", "--bend-radius", parse_float, "inside bend radius r >= 0", _MAT, "LENGTH"),
    Flag("k_factor", "--k-factor", parse_float, "K-factor in [0, 1]", _MAT, "K"),
    Flag("kerf", "--kerf", parse_float, "cutting kerf >= 0", _MAT, "LENGTH"),
    Flag("relief_hole", "--relief-hole", parse_float, "relief hole diameter at the apex >= 0 "
         "(0: none)", _MAT, "DIAMETER"),
    Flag("density", "--density", parse_float, "density in kg/m^3, in [1e-15, 1e15] (e.g. 7850 for "
         "steel), whatever the design unit", _MAT, "KG/M3"),
    Flag("youngs_modulus", "--youngs-modulus", parse_float, "Young's modulus in GPa, in [1e-6, "
         "10000] (193 for 304 stainless; for `simulate`)", _MAT, "GPA"),
    Flag("poisson", "--poisson", parse_float, "Poisson's ratio, > -1 and < 0.5 (0.29 for 304 "
         "stainless; for `simulate`)", _MAT, "NU"),
    Flag("yield_stress", "--yield-stress", parse_float, "yield stress in MPa, at least 0.001 "
         "and at most the modulus (215 for 304 stainless; for `simulate`)", _MAT, "MPA"),
    Flag("hardening_modulus", "--hardening-modulus", parse_float, "linear hardening modulus in "
         "MPa, >= 0 and below the modulus (0: perfectly plastic; for `simulate`)", _MAT, "MPA"),
    Flag("kinematic_hardening", "--kinematic-hardening", parse_float, "the share of the "
         "hardening that is kinematic (Bauschinger), in [0, 1] (for `simulate`)", _MAT, "SHARE"),
    Flag("crease_overbend", "--crease-overbend", parse_float, "how much further than its fold "
         "angle each crease half is set, in degrees, in [-45, 45] (the cones formed as designed; "
         "for `simulate` and the bend sheet)", _MAT, "DEG"),
    Flag("cone_forming", "--cone-forming", parse_choice(CONE_FORMINGS), "the curvature the "
         "cones are formed to: design (the design's) or compensated (past its springback at "
         "every point, NAME-cones.csv; for `simulate --law j2` and `build`)", _MAT,
         "design|compensated"),
    Flag("sheet_surface", "--sheet-surface", parse_choice(SURFACES, upper=True), "the sheet face "
         "the designed surface is: INSIDE, OUTSIDE or MID", _MAT, "INSIDE|OUTSIDE|MID"),
)  # fmt: skip


FLAG_OF = {f.dest: f.flag for f in DESIGN_FLAGS}
