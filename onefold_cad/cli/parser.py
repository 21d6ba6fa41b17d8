"""The ``onefold`` command's option parsers, one per command, built from the
design flags (:mod:`onefold_cad.flags`) and the writers' registry
(:mod:`onefold_cad.export.writers`); nothing heavier than the standard
library is imported, so ``--help`` starts in a few milliseconds.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from onefold_cad.cli.compensate_parser import compensate_parser
from onefold_cad.cli.help_format import fill, formatter, raw_formatter
from onefold_cad.cli.hops_parser import HOPS_PORT, hops_parser, parse_port
from onefold_cad.cli.loads_parser import loads_parser
from onefold_cad.cli.site_parser import site_parser
from onefold_cad.export.writers import WRITERS, files_help
from onefold_cad.flags.design_flags import (
    BODIES,
    COMPENSATIONS,
    PLACEMENTS,
    parse_choice,
    parse_float,
    parse_int,
)
from onefold_cad.flags.parser import FlagParser, add_design_flags
from onefold_cad.templates import DEFAULT_TEMPLATE

__all__ = ["HOPS_PORT", "build_parser", "help_text", "parse_port"]


PROG = "onefold"


def _template_argument(parser: argparse.ArgumentParser, dest: str, nargs: str) -> None:
    """The positional TEMPLATE (``nargs`` '?' or '*') of a command that falls
    back on the default template."""
    parser.add_argument(
        dest,
        nargs=nargs,
        metavar="TEMPLATE",
        help=f"template file or shipped template name (default: {DEFAULT_TEMPLATE})",
    )


def _add_common(p: argparse.ArgumentParser | argparse._ArgumentGroup) -> None:
    p.add_argument(
        "--name", help="the design's name (file stem); default: the template's, with the "
        "flags given appended; without a template, made from the flags"
    )  # fmt: skip
    p.add_argument(
        "-q", "--quiet", action="store_true", help="no progress or material lines on stderr "
        "(warnings and errors are still printed)"
    )  # fmt: skip


class _VersionAction(argparse._VersionAction):
    """``--version``: the version read when asked (:mod:`onefold_cad.version`)."""

    def __call__(self, parser: Any, namespace: Any, values: Any, option: Any = None) -> None:
        from onefold_cad.version import __version__

        self.version = f"{PROG} {__version__}"
        super().__call__(parser, namespace, values, option)


def build_parser() -> dict[str, argparse.ArgumentParser]:
    """The parsers of the commands, by name (``""`` is ``onefold`` itself)."""
    top = FlagParser(
        prog=PROG,
        usage=f"{PROG} [-h] [--version] COMMAND [ARGS]",
        description=fill(
            "Design One-Fold curved-origami forms and write the files to make them: STEP, "
            "DXF (annotated and cut-only), bend sheet, FOLD, GLB, JSON report and previews."
        ),
        epilog="commands:\n"
        "  build      write the files of one or more designs (all or nothing)\n"
        "  solve      solve a design and print the result (writes nothing)\n"
        "  templates  list the shipped templates\n"
        "  explore    explore a design in the browser (sliders, 3D form, flat pattern)\n"
        "  fit        find the frame whose resting form has a target height and span\n"
        "  sweep      evaluate many designs (a pool or a Dask cluster): table, Pareto front\n"
        "  simulate   the sheet as steel: formed, sprung back, standing under its weight\n"
        "  compensate the fold to form so that the steel stands as designed (springback)\n"
        "  hops       a Grasshopper Hops server: onefold/solve and onefold/fit in Grasshopper\n"
        "  site       a site of several sheets: their files, STEP/IFC/GLB, plan, order\n"
        "  loads      outdoors: wind, snow, a person; anchors or ballast per foot\n\n"
        f"'{PROG} COMMAND --help' shows a command's options.",
        formatter_class=lambda prog: argparse.RawDescriptionHelpFormatter(prog, width=100),
        allow_abbrev=False,
    )
    top.add_argument("--version", action=_VersionAction)

    build = FlagParser(
        prog=f"{PROG} build",
        usage=f"{PROG} build [TEMPLATE ...] [options]",
        description=fill(
            "Write the files below for each template's design (every one, or those "
            "--formats names): all files of all designs, or none. Flags change every "
            "template given; without a template they change the default one "
            f"({DEFAULT_TEMPLATE})."
        ),
        epilog=f"files (--formats NAME,NAME,...; default: all):\n{files_help()}",
        formatter_class=raw_formatter,
        allow_abbrev=False,
    )
    _template_argument(build, "templates", "*")
    out = build.add_argument_group("output")
    out.add_argument("-o", "--outdir", type=Path, default=Path("out"), metavar="DIR",
                     help="output folder (default: out)")  # fmt: skip
    out.add_argument(
        "--formats", metavar="LIST", help="comma-separated formats to write (default: all): "
        f"{', '.join(WRITERS)} (see the files below)"
    )  # fmt: skip
    out.add_argument(
        "--body", type=parse_choice(BODIES), default="auto", metavar="auto|solid|shell",
        help="STEP body: 'solid' (the sheet's thickness, exact model), 'shell' (the "
        "reference surface) or 'auto' (solid with thickness and a relief hole, else shell)",
    )  # fmt: skip
    out.add_argument(
        "--compensation", type=parse_choice(COMPENSATIONS), default=COMPENSATIONS[0],
        metavar="sharp|none", help="flat pattern: bend compensation of the sharp-crease "
        "model (default), or none (the designed sheet uncompensated, said in the notes); "
        "a STEP solid past the bend model's limits is written only with none",
    )  # fmt: skip
    out.add_argument(
        "--placement", type=parse_choice(PLACEMENTS), default=PLACEMENTS[0],
        metavar="rest|frame", help="where the STEP, GLB, 3DM and 3D preview put the form: 'rest' "
        "(default: standing on the ground z = 0 as the report's resting numbers say) or "
        "'frame' (the fold frame: H at the origin, the fold line on x, the apex above H)",
    )  # fmt: skip
    out.add_argument(
        "-j", "--jobs", type=parse_int, default=1, metavar="N",
        help="build N designs at a time in separate processes (default 1)",
    )  # fmt: skip
    _add_common(out)
    add_design_flags(build)

    solve = FlagParser(
        prog=f"{PROG} solve",
        usage=f"{PROG} solve [TEMPLATE] [options]",
        description="Solve a design and print the result; nothing is written. Fabrication "
        "problems are warnings here (exit status 0); only build refuses.",
        formatter_class=formatter,
        allow_abbrev=False,
    )
    _template_argument(solve, "template", "?")
    o = solve.add_argument_group("output")
    o.add_argument("--json", action="store_true", help="print the JSON report")
    _add_common(o)
    add_design_flags(solve)

    templates = FlagParser(
        prog=f"{PROG} templates",
        usage=f"{PROG} templates",
        description="List the shipped templates, one line each: name and description; then, "
        "after a blank line and a heading, the shipped site files (onefold site NAME).",
        formatter_class=formatter,
        allow_abbrev=False,
    )
    explore = FlagParser(
        prog=f"{PROG} explore",
        usage=f"{PROG} explore [TEMPLATE] [--port N] [--no-browser]",
        description="Explore a design in the browser: sliders, the 3D form, the flat pattern, "
        "downloads. Serves a page on 127.0.0.1 until Ctrl-C; the solver runs here, the page "
        "only draws.",
        formatter_class=formatter,
        allow_abbrev=False,
    )
    _template_argument(explore, "template", "?")
    explore.add_argument("--port", type=parse_int, default=8765, metavar="N",
                         help="port on 127.0.0.1 (0: any free port; default 8765)")  # fmt: skip
    explore.add_argument("--no-browser", action="store_true",
                         help="only print the address; do not open a browser")  # fmt: skip
    fit = FlagParser(
        prog=f"{PROG} fit",
        usage=f"{PROG} fit [TEMPLATE] --height H --span S [--depth D]\n"
        "         [--min-tipping-margin DEG] [--json] [-o DIR] [-q]",
        description="Find alpha, beta and h_c whose resting form has the target height and "
        "span (footprint width), and depth if given, each within 0.5 %. The template's sheet, "
        "material and model are kept; lengths are in its unit. A target out of reach is an "
        "error that gives the ranges the template's sheet can reach.",
        formatter_class=formatter,
        allow_abbrev=False,
    )
    fit.add_argument(
        "template",
        nargs="?",
        metavar="TEMPLATE",
        help="template file or shipped template name: sheet and material "
        f"(default: {DEFAULT_TEMPLATE})",
    )
    fit.add_argument(
        "--height",
        type=parse_float,
        required=True,
        metavar="H",
        help="height of the form as it rests on the ground, > 0",
    )
    fit.add_argument(
        "--span",
        type=parse_float,
        required=True,
        metavar="S",
        help="footprint width of the resting form (along the fold line), > 0",
    )
    fit.add_argument(
        "--depth",
        type=parse_float,
        metavar="D",
        help="footprint depth of the resting form (across it), > 0",
    )
    fit.add_argument(
        "--min-tipping-margin",
        type=parse_float,
        metavar="DEG",
        help="smallest tipping margin allowed (deg)",
    )
    fit.add_argument("--json", action="store_true", help="print the result as JSON")
    fit.add_argument(
        "-o",
        "--outdir",
        type=Path,
        metavar="DIR",
        help="also build the found design into this folder (as NAME-fit)",
    )
    fit.add_argument("-q", "--quiet", action="store_true",
                     help="no progress lines on stderr (the search's, the build's)")  # fmt: skip
    return {
        "": top,
        "build": build,
        "solve": solve,
        "templates": templates,
        "explore": explore,
        "fit": fit,
        "hops": hops_parser(PROG),
        "sweep": _sweep_parser(),
        "simulate": _simulate_parser(),
        "compensate": compensate_parser(PROG),
        "site": site_parser(PROG),
        "loads": loads_parser(PROG),
    }


def _simulate_parser() -> FlagParser:
    """``onefold simulate``: the mechanics' options, then the design flags."""
    p = FlagParser(
        prog=f"{PROG} simulate",
        usage=f"{PROG} simulate [TEMPLATE] [--supports anchored|frictionless]\n"
        "         [--reference flat|designed] [--json] [-o DIR] [options]",
        description=fill(
            "Simulate the design's sheet as steel: bent flat into the design (where it "
            "yields), let go by the folding machine (its springback), and standing on the "
            "ground under its own weight (its sag, stresses, and whether it stands), with a "
            "shell model of the sheet calibrated to its Young's modulus, Poisson's ratio, "
            "yield stress, thickness and density (docs/mechanics.md). With --reference "
            "designed the designed form is taken as stress-free and checked under its weight "
            "on its resting contacts, as an FE program does. It is solved again on the next "
            "coarser level's mesh to say how converged the answer is (not for --mesh coarse, "
            "a preview)."
        ),
        formatter_class=raw_formatter,
        allow_abbrev=False,
    )
    _template_argument(p, "template", "?")
    from onefold_cad.choices import CheckMesh

    g = p.add_argument_group("simulation")
    simulation_options(g, defaults=True)
    words = tuple(c.value for c in CheckMesh)
    g.add_argument(
        "--check-mesh", type=parse_choice(words), default=None, metavar="|".join(words),
        help="the convergence check's mesh: the next coarser level's (normal: coarse; "
        "fine: normal; the default), a fraction of the CPU, its change a cautious bound "
        "on the answer's error, or about twice the nodes (the default for a checked "
        "coarse mesh)",
    )  # fmt: skip
    o = p.add_argument_group("output")
    o.add_argument("--json", action="store_true",
                   help="print the JSON report with its simulation section")  # fmt: skip
    o.add_argument(
        "-o", "--outdir", type=Path, metavar="DIR", help="write NAME.json, NAME-standing.glb, "
        "NAME-released.glb, NAME-deviation.png, NAME-stress.png, NAME.inp (the designed "
        "form's structural check for CalculiX or Abaqus) and NAME.vtu (the stages, for "
        "ParaView) into DIR"
    )  # fmt: skip
    _add_common(o)
    o.add_argument(
        "-v", "--verbose", action="store_true",
        help="also Newton's iterations on stderr (default: one line per stage)",
    )  # fmt: skip
    add_design_flags(p)
    return p


def simulation_options(g: Any, *, defaults: bool) -> None:
    """``onefold simulate``'s options (supports, reference, crease, mesh, the
    convergence check) on the argument group ``g``; ``defaults``: their
    defaults set (simulate), else None where not given (sweep: they need
    ``--measure simulate``, and the plan fills in simulate's defaults)."""
    from onefold_cad.choices import SIMULATION_DEFAULTS

    for name, text in (
        ("supports", "where the sheet touches the ground it is anchored (does not slide; "
         "default) or slides freely"),
        ("reference", "the stress-free form: the flat sheet (forming, springback, standing; "
         "default) or the designed form (a structural check)"),
        ("crease", "the crease keeps its set angle (default), or bends with its bend zone's "
         "own stiffness"),
        ("law", "how the steel yields: J2 (von Mises) plasticity through the thickness, "
         "membrane and bending together, unloading and reverse yield following the law "
         "(default), or the 1D moment law of a rectangular section (a fifth to a half of "
         "the CPU: elastic membrane and unloading, its springback a third to two fifths "
         "short, its stresses past yield estimates)"),
        ("mesh", "mesh fineness (default normal; coarse: a quick preview without the "
         "convergence check)"),
    ):  # fmt: skip
        default = SIMULATION_DEFAULTS[name]
        words = tuple(c.value for c in type(default))
        g.add_argument(
            f"--{name}", type=parse_choice(words), default=default.value if defaults else None,
            metavar="|".join(words), help=text,
        )  # fmt: skip
    check = g.add_mutually_exclusive_group()
    check.add_argument(
        "--check", dest="check", action="store_true", default=None,
        help="solve again on a mesh with about twice the nodes (default, but for coarse)",
    )  # fmt: skip
    check.add_argument("--no-check", dest="check", action="store_false",
                       help="skip the convergence check")  # fmt: skip


def _sweep_parser() -> FlagParser:
    """``onefold sweep``: the sweep's options, then the design flags (fixed for
    every design). The measures' and samplers' names come from the sweep's
    registries (imported here: standard library only)."""
    from onefold_cad.sweep.measures import measure_help
    from onefold_cad.sweep.samplers import SAMPLERS

    p = FlagParser(
        prog=f"{PROG} sweep",
        usage=f"{PROG} sweep [TEMPLATE] --vary NAME=SPEC [--vary ...] -o DIR [options]",
        description=fill(
            "Evaluate many designs of one template: every design is solved, folded and "
            "stood on the ground (the STEP's body), on a local process pool or a Dask "
            "cluster. Writes DIR/results.parquet (every input and output, units in its "
            "metadata), DIR/data.csv (Design Explorer), DIR/pareto.csv (with --objectives) "
            "and DIR/parallel.png. Rows are journaled as they finish (DIR/journal.jsonl): "
            "rerun the same command to resume. A design that fails records its error. The design "
            "flags below, when given, apply to every design."
        ),
        epilog=(
            "NAME is a design flag without its dashes (alpha, hc, apex-fraction, rectangle, ...).\n"
            "SPEC: LO:HI:N (N values from LO to HI), LO:HI (a range for --sampler lhs|sobol,\n"
            "or --samples values on a grid), V,V,... (a list; a polygon's list uses |), V.\n"
            "e.g. onefold sweep patkau-one-fold --vary alpha=10:80:15 "
            "--vary hc-fraction=-0.5,0,0.5 -o out\n\n"
            f"measures (--measure NAME,...):\n{measure_help()}"
        ),
        formatter_class=raw_formatter,
        allow_abbrev=False,
    )
    _template_argument(p, "template", "?")
    g = p.add_argument_group("sweep")
    g.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="NAME=SPEC",
        help="a design flag to vary and its values (repeat for more flags)",
    )
    g.add_argument(
        "-o",
        "--outdir",
        type=Path,
        required=True,
        metavar="DIR",
        help="output folder (its journal resumes a stopped sweep)",
    )
    g.add_argument(
        "--sampler",
        type=parse_choice(SAMPLERS),
        default="grid",
        metavar="|".join(SAMPLERS),
        help="grid: every combination (default); lhs, "
        "sobol: --samples space-filling points of the LO:HI ranges",
    )
    g.add_argument(
        "--samples",
        type=parse_int,
        metavar="N",
        help="points for lhs/sobol; values per LO:HI range on a grid",
    )
    g.add_argument(
        "--seed",
        type=parse_int,
        default=0,
        metavar="N",
        help="seed of lhs/sobol (default 0: the same points every run)",
    )
    g.add_argument(
        "--measure",
        action="append",
        default=[],
        metavar="NAME,...",
        help="what each design gets beyond solve + fold + rest (see below)",
    )
    g.add_argument(
        "--objectives",
        metavar="LIST",
        help="Pareto objectives: max:COLUMN, min:COLUMN, target:COLUMN=VALUE, "
        "comma-separated (e.g. max:tipping_margin_deg,target:height=3000)",
    )
    g.add_argument(
        "--images",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="a 3D thumbnail per design in DIR/img/ (default: on up to 1000 designs)",
    )
    g.add_argument(
        "-j",
        "--jobs",
        type=parse_int,
        metavar="N",
        help="worker processes (default: every core; 1: in this process)",
    )
    g.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run on a Dask cluster: tcp://HOST:8786 (default: "
        "$DASK_SCHEDULER_ADDRESS if set), or 'local' for a LocalCluster of -j "
        "workers; needs onefold_cad[cluster]",
    )
    g.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    simulation_options(
        p.add_argument_group("simulation (with --measure simulate; as onefold simulate's)"),
        defaults=False,
    )
    add_design_flags(p)
    return p


def help_text(command: str = "") -> str:
    """The ``--help`` text of ``onefold`` or of one of its commands."""
    return build_parser()[command].format_help()
