"""``onefold site``'s option parser (standard library only, with the
writers' registries for the file lists)."""

from __future__ import annotations

from pathlib import Path

from onefold_cad.cli.help_format import raw_formatter
from onefold_cad.export.site.writers import SITE_WRITERS, site_files_help
from onefold_cad.export.writers import WRITERS
from onefold_cad.flags.design_flags import COMPENSATIONS, parse_choice, parse_int
from onefold_cad.flags.parser import FlagParser

__all__ = ["site_parser"]


def site_parser(prog: str = "onefold") -> FlagParser:
    """The parser of ``onefold site SITE.toml -o DIR [options]``."""
    p = FlagParser(
        prog=f"{prog} site",
        usage=f"{prog} site SITE [-o DIR] [options]",
        description=(
            "Build a site of several sheets: each [[sheet]] of the site file built as\n"
            "`onefold build` builds it (its files in DIR/NAME/), then the site's files below,\n"
            "after a clearance check (sheets that touch or overlap are an error naming both).\n"
            "All files of the site, or none (docs/site.md)."
        ),
        epilog=f"site files (--formats NAME,NAME,...; default: all):\n{site_files_help()}",
        formatter_class=raw_formatter,
        allow_abbrev=False,
    )
    p.add_argument("site", metavar="SITE", help="site file (TOML) or shipped site name")
    p.add_argument("-o", "--outdir", type=Path, default=Path("out"), metavar="DIR",
                   help="output folder (default: out)")  # fmt: skip
    p.add_argument(
        "--formats", metavar="LIST", help="the site's files to write (default: all): "
        f"{', '.join(SITE_WRITERS)}"
    )  # fmt: skip
    p.add_argument(
        "--sheet-formats", metavar="LIST", help="each sheet's files, as `onefold build "
        f"--formats` (default: all; none for no sheet files): {', '.join(WRITERS)}"
    )  # fmt: skip
    p.add_argument(
        "--compensation", type=parse_choice(COMPENSATIONS), default=COMPENSATIONS[0],
        metavar="sharp|none", help="flat patterns' bend compensation, as `onefold build`",
    )  # fmt: skip
    p.add_argument(
        "--allow-touching", action="store_true",
        help="sheets may touch or overlap (meant to lean on each other): reported, not refused",
    )  # fmt: skip
    p.add_argument(
        "-j", "--jobs", type=parse_int, default=1, metavar="N",
        help="build N sheets at a time in separate processes (default 1)",
    )  # fmt: skip
    p.add_argument("-q", "--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(body="auto", placement="rest")
    return p
