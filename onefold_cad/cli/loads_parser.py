"""``onefold loads``'s option parser (standard library only) and the
:class:`~onefold_cad.mechanics.loads.spec.LoadSpec` it reads.

A command of its own rather than flags on ``onefold simulate``: the loads
take a dozen options of their own, check the designed form (not the forming
sequence simulate follows), and print a different report.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from onefold_cad.cli.help_format import fill, raw_formatter
from onefold_cad.flags.design_flags import parse_choice, parse_float, parse_int, parse_int_in
from onefold_cad.flags.parser import FlagParser, add_design_flags
from onefold_cad.templates import DEFAULT_TEMPLATE

__all__ = ["load_spec_values", "loads_parser", "parse_point", "parse_strength_cases"]

SUPPORTS = ("anchored", "friction", "ballast")
MESHES = ("coarse", "normal", "fine")


def parse_point(text: str) -> tuple[float, float]:
    """``X,Y`` as two numbers."""
    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"{text.strip()!r} is not X,Y")
    return parse_float(parts[0]), parse_float(parts[1])


#: How many STR cases past first yield get a J2 load path unless told.
STRENGTH_CASES = 3


def parse_strength_cases(text: str) -> int | None:
    """``N`` (0 to 100) or ``all`` (None)."""
    if text.strip().lower() == "all":
        return None
    return parse_int_in(text, 0, 100, more=" or 'all'")


def loads_parser(prog: str = "onefold") -> FlagParser:
    """The parser of ``onefold loads [TEMPLATE] --wind-speed V [options]``."""
    p = FlagParser(
        prog=f"{prog} loads",
        usage=f"{prog} loads [TEMPLATE] --wind-speed M/S [--terrain 0|I|II|III|IV] [--snow KPA]\n"
        "         [--supports anchored|friction|ballast] [--json] [-o DIR] [options]",
        description=fill(
            "The designed sheet standing outdoors: its weight, wind (EN 1991-1-4) from every "
            "direction, pushing down and lifting, snow (EN 1991-1-3) and a person (1 kN at "
            "the worst point of a grid), combined as EN 1990's EQU, STR and SLS cases. Per "
            "case: whether it stands on its supports (sliding, a foot lifting, tipping) and "
            "its stresses, the feet's reactions, and what each foot needs (an anchor's pull "
            "and shear, or ballast). docs/loads.md."
        ),
        formatter_class=raw_formatter,
        allow_abbrev=False,
    )
    p.add_argument(
        "template",
        nargs="?",
        metavar="TEMPLATE",
        help=f"template file or shipped template name (default: {DEFAULT_TEMPLATE})",
    )
    w = p.add_argument_group("wind (EN 1991-1-4)")
    w.add_argument(
        "--wind-speed",
        type=parse_float,
        metavar="M/S",
        help="basic wind velocity v_b of the site (its national annex), 0 to 100",
    )
    w.add_argument(
        "--terrain",
        default="II",
        metavar="0|I|II|III|IV",
        help="terrain category (Table 4.1; default II: open country)",
    )
    w.add_argument(
        "--velocity-pressure",
        type=parse_float,
        metavar="KPA",
        help="peak velocity pressure q_p, instead of --wind-speed and --terrain",
    )
    w.add_argument(
        "--height",
        type=parse_float,
        metavar="M",
        help="reference height z_e (default: the standing form's height)",
    )
    w.add_argument(
        "--cf-down",
        type=parse_float,
        default=0.2,
        metavar="C",
        help="net pressure coefficient pushing down (default 0.2: Table 7.6)",
    )
    w.add_argument(
        "--cf-up",
        type=parse_float,
        default=-0.5,
        metavar="C",
        help="net pressure coefficient lifting (default -0.5: Table 7.6, empty "
        "underneath; -1.3 when blocked)",
    )
    w.add_argument(
        "--directions",
        type=parse_int,
        default=8,
        metavar="N",
        help="wind directions, evenly over 360 deg (default 8)",
    )
    s = p.add_argument_group("snow (EN 1991-1-3) and a person (EN 1991-1-1)")
    s.add_argument(
        "--snow",
        type=parse_float,
        default=0.0,
        metavar="KPA",
        help="characteristic ground snow load s_k (default 0: none)",
    )
    s.add_argument(
        "--exposure",
        type=parse_float,
        default=1.0,
        metavar="C_E",
        help="exposure coefficient C_e (Table 5.1: 0.8 windswept, 1.0, 1.2 sheltered)",
    )
    s.add_argument(
        "--thermal",
        type=parse_float,
        default=1.0,
        metavar="C_T",
        help="thermal coefficient C_t (default 1.0)",
    )
    s.add_argument(
        "--person",
        type=parse_float,
        default=1.0,
        metavar="KN",
        help="a point load (default 1 kN, Table 6.10 roof category H; 0: none)",
    )
    s.add_argument(
        "--person-at",
        type=parse_point,
        metavar="X,Y",
        help="where it stands on the flat sheet (design unit, H at 0,0; default: "
        "the worst point of a grid)",
    )
    s.add_argument(
        "--person-grid",
        type=parse_int,
        default=6,
        metavar="N",
        help="the grid's points per side (default 6)",
    )
    g = p.add_argument_group("supports")
    g.add_argument(
        "--supports",
        type=parse_choice(SUPPORTS),
        default="anchored",
        metavar="|".join(SUPPORTS),
        help="anchored feet (bolts, ground screws; default), free-standing on "
        "friction, or held down by ballast",
    )
    g.add_argument(
        "--friction",
        type=parse_float,
        default=0.3,
        metavar="MU",
        help="the feet's friction coefficient on the ground (default 0.3)",
    )
    m = p.add_argument_group("model")
    m.add_argument(
        "--mesh",
        type=parse_choice(MESHES),
        default="normal",
        metavar="|".join(MESHES),
        help="mesh fineness (default normal)",
    )
    m.add_argument(
        "--nonlinear-check",
        action="store_true",
        help="solve the governing cases again with the full model (minutes)",
    )
    m.add_argument(
        "--strength-cases",
        type=parse_strength_cases,
        default=STRENGTH_CASES,
        metavar="N|all",
        help="how many STR cases past first yield a J2 load path checks (EN 1993-1-6 "
        "GMNA): the permanent one first, then those of the largest elastic peak "
        f"(default {STRENGTH_CASES}; all: every one; the others do not count as standing)",
    )
    o = p.add_argument_group("output")
    o.add_argument(
        "--json", action="store_true", help="print the JSON report with its outdoors section"
    )
    o.add_argument(
        "-o",
        "--outdir",
        type=Path,
        metavar="DIR",
        help="write NAME-loads.json, NAME-loads.csv (the cases) and NAME-loads.png "
        "(the governing case) into DIR",
    )
    o.add_argument("--name", help="the design's name (file stem)")
    o.add_argument("-q", "--quiet", action="store_true", help="no progress lines on stderr")
    add_design_flags(p)
    return p


def load_spec_values(ns: argparse.Namespace) -> dict[str, Any]:
    """The ``LoadSpec`` fields from the parsed options."""
    return {
        "wind_speed": ns.wind_speed,
        "terrain": ns.terrain,
        "velocity_pressure_kPa": ns.velocity_pressure,
        "height": ns.height,
        "cf_down": ns.cf_down,
        "cf_up": ns.cf_up,
        "directions": ns.directions,
        "snow_kPa": ns.snow,
        "exposure": ns.exposure,
        "thermal": ns.thermal,
        "person_kN": ns.person,
        "person_at": ns.person_at,
        "person_grid": ns.person_grid,
        "supports": ns.supports,
        "friction": ns.friction,
    }
