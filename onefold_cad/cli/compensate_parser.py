"""``onefold compensate``'s option parser (standard library only: ``--help``
starts in milliseconds)."""

from __future__ import annotations

import argparse
from pathlib import Path

from onefold_cad.choices import SIMULATION_DEFAULTS, Knob
from onefold_cad.cli.help_format import fill, raw_formatter
from onefold_cad.flags.design_flags import parse_choice, parse_float, parse_int
from onefold_cad.flags.parser import FlagParser, add_design_flags
from onefold_cad.templates import DEFAULT_TEMPLATE

__all__ = ["compensate_parser", "parse_knobs"]

KNOB_NAMES = tuple(k.value for k in Knob)


def parse_knobs(text: str) -> tuple[str, ...]:
    """``--knobs``: a comma-separated subset of the knobs, at least one, each
    named once, in :class:`~onefold_cad.choices.Knob`'s order."""
    names = [t.strip().lower() for t in text.split(",") if t.strip()]
    bad = [n for n in names if n not in KNOB_NAMES]
    if bad or not names:
        raise argparse.ArgumentTypeError(
            f"must be one or more of {', '.join(KNOB_NAMES)}, comma-separated, got {text!r}"
        )
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise argparse.ArgumentTypeError(f"{twice[0]!r} is named twice")
    return tuple(k for k in KNOB_NAMES if k in names)


def compensate_parser(prog: str) -> FlagParser:
    """The parser of ``PROG compensate``."""
    p = FlagParser(
        prog=f"{prog} compensate",
        usage=f"{prog} compensate [TEMPLATE] [--target design | --height H --span S "
        "[--depth D]]\n         [-j N] [--scheduler ADDRESS] [--json] [-o DIR] [options]",
        description=fill(
            "Find the fold to form so that the steel, after springback and standing under "
            "its weight (as onefold simulate computes it), takes the target form: the design "
            "itself (default: the least squares of the standing mid-surface's distance from "
            "the designed form as it stands) or a height and span. The knobs are the fold the "
            "sheet is formed to (alpha, beta, h_c), the crease set past it (overbend) and, with "
            "J2, the cones formed past their springback at every point (cones). Coarse mesh "
            "first, the normal mesh to finish; the answer and the "
            "uncompensated fold are checked on the normal mesh with its convergence check "
            "(docs/compensate.md)."
        ),
        formatter_class=raw_formatter,
        allow_abbrev=False,
    )
    p.add_argument(
        "template", nargs="?", metavar="TEMPLATE",
        help=f"template file or shipped template name (default: {DEFAULT_TEMPLATE})",
    )  # fmt: skip
    t = p.add_argument_group("target (default: the design's own form)")
    t.add_argument("--target", type=parse_choice(("design",)), default=None, metavar="design",
                   help="the designed form as it stands (the default)")  # fmt: skip
    for name, text in (("height", "the standing steel's height"),
                       ("span", "its footprint's width (the resting frame's x)"),
                       ("depth", "its footprint's depth (optional third target)")):  # fmt: skip
        t.add_argument(f"--{name}", type=parse_float, metavar="LENGTH",
                       help=f"{text}, in the design's unit")  # fmt: skip
    r = p.add_argument_group("evaluations")
    r.add_argument(
        "--knobs", type=parse_knobs, default=None, metavar="K[,K...]",
        help="what the search may change, of " + ", ".join(KNOB_NAMES) + " (default: all; "
        "cones only with --law j2): the fold's angles and height, the crease set past its "
        "fold angle (overbend; leave it out where the crease cannot be set apart from the "
        "cones) and the cones formed past their springback (cones: each station's radius in "
        "NAME-cones.csv)",
    )  # fmt: skip
    r.add_argument(
        "--law", type=parse_choice(("j2", "moment")), default=SIMULATION_DEFAULTS["law"].value,
        metavar="j2|moment",
        help="the bending law of every simulation, as onefold simulate's --law: J2 "
        "plasticity through the thickness (default; the springback CalculiX supports, "
        "docs/mechanics.md) or the 1D moment law (a fifth to a half of the CPU; it "
        "compensates too little)",
    )  # fmt: skip
    r.add_argument(
        "-j", "--jobs", type=parse_int, default=None, metavar="N",
        help="simulations side by side in a local process pool (default: the cores this "
        "process may use, at most 4)",
    )  # fmt: skip
    r.add_argument(
        "--scheduler", metavar="ADDRESS",
        help="run them on a Dask cluster (tcp://HOST:PORT, or local for a LocalCluster)",
    )  # fmt: skip
    o = p.add_argument_group("output")
    o.add_argument("--json", action="store_true",
                   help="print the JSON report with its compensation section")  # fmt: skip
    o.add_argument(
        "-o", "--outdir", type=Path, metavar="DIR",
        help="write NAME-compensated.toml (the compensated design as a template), its build "
        "files, NAME-compensated-standing.glb and .step (the steel as it stands), "
        "NAME-compensation.png and NAME-compensation.json into DIR, all or nothing",
    )  # fmt: skip
    o.add_argument(
        "-q", "--quiet", action="store_true",
        help="no progress on stderr (warnings and errors are still printed)",
    )  # fmt: skip
    add_design_flags(p)
    return p
