"""``onefold hops``'s option parser, and the port type the servers share
(standard library only)."""

from __future__ import annotations

from onefold_cad.cli.help_format import formatter
from onefold_cad.flags.design_flags import parse_int_in
from onefold_cad.flags.parser import FlagParser

__all__ = ["HOPS_PORT", "hops_parser", "parse_port"]

#: The Hops server's default port (Hops' own examples use it).
HOPS_PORT = 5000


def parse_port(text: str) -> int:
    """A TCP port in [0, 65535] (0: any free port)."""
    return parse_int_in(text, 0, 65535, " (0: any free port)")


def hops_parser(prog: str = "onefold") -> FlagParser:
    """The parser of ``onefold hops [--port N] [--host ADDRESS] ...``."""
    hops = FlagParser(
        prog=f"{prog} hops",
        usage=f"{prog} hops [--port N] [--host ADDRESS] [--templates DIR] [--allow-host NAME]",
        description="Serve the Grasshopper Hops components onefold/solve (a design: the folded "
        "form's Breps, creases, apex, flat pattern, fold angles, height, span, tipping margin, "
        "warnings) and onefold/fit (alpha, beta, h_c for a target height and span) until "
        "Ctrl-C. In Grasshopper, a Hops component's Path is http://127.0.0.1:5000/onefold/solve "
        "(docs/rhino.md). Needs onefold_cad[rhino] (ghhops-server, rhino3dm).",
        formatter_class=formatter,
        allow_abbrev=False,
    )
    hops.add_argument(
        "--port", type=parse_port, default=HOPS_PORT, metavar="N",
        help=f"port, in [0, 65535] (0: any free port; default {HOPS_PORT})",
    )  # fmt: skip
    hops.add_argument(
        "--host", default="127.0.0.1", metavar="ADDRESS",
        help="address to listen on (default 127.0.0.1: this machine only)",
    )  # fmt: skip
    hops.add_argument(
        "--templates", default=None, metavar="DIR",
        help="a folder of your own templates: a request may name its .toml files by name "
        "(requests never name a path; without it, the shipped templates only)",
    )  # fmt: skip
    hops.add_argument(
        "--allow-host", action="append", default=[], metavar="NAME",
        help="a name or address of this machine that clients may use in the Host header "
        "(repeatable; the listening address, and the loopback names for a loopback one, "
        "are always allowed)",
    )  # fmt: skip
    return hops
