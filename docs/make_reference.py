"""Generated parts of docs/: CLI reference, template catalogue, bend example.

Run from the repository root (docs/make_figures.py runs it too)::

    .venv/bin/python docs/make_reference.py

Each generated block sits in a Markdown file between ``<!-- BEGIN name -->``
and ``<!-- END name -->``; everything outside the markers is hand-written.
tests/test_docs.py regenerates the cheap blocks in memory and checks that the
files are up to date.
"""

from __future__ import annotations

import functools
import math
import os
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from onefold_cad import Design, bend_values, fold_design

DOCS = Path(__file__).resolve().parent
IMAGES = DOCS / "images"
BLOCK = "<!-- BEGIN {name} -->\n{body}<!-- END {name} -->"


# -- blocks ------------------------------------------------------------------------
def replace_block(text: str, name: str, body: str) -> str:
    """``text`` with the block ``name`` replaced by ``body`` (ending in a newline)."""
    pat = re.compile(rf"<!-- BEGIN {re.escape(name)} -->\n.*?<!-- END {re.escape(name)} -->", re.S)
    if not pat.search(text):
        raise ValueError(f"markers for block {name!r} not found")
    return pat.sub(lambda _: BLOCK.format(name=name, body=body), text)


def read_block(text: str, name: str) -> str:
    """The current body of block ``name`` in ``text``."""
    m = re.search(
        rf"<!-- BEGIN {re.escape(name)} -->\n(.*?)<!-- END {re.escape(name)} -->", text, re.S
    )
    if not m:
        raise ValueError(f"markers for block {name!r} not found")
    return m.group(1)


def write_block(path: Path, name: str, body: str) -> None:
    """Replace block ``name`` in the file at ``path`` (atomically)."""
    new = replace_block(path.read_text(), name, body)
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(new)
    os.replace(tmp, path)


# -- templates -----------------------------------------------------------------------
def templates() -> list[tuple[Any, Design]]:
    """(TemplateInfo, Design) of every shipped template, sorted by name."""
    from onefold_cad.templates import list_templates, load_template

    return [(info, load_template(info.path)) for info in list_templates()]


def bend_template() -> tuple[str, Design]:
    """The shipped template with the thickest material (the bend example's source)."""
    name, design = max(
        ((i.name, d) for i, d in templates()), key=lambda nd: (nd[1].material.thickness, nd[0])
    )
    return name, design


def bend_example_block() -> str:
    """The fabrication guide's worked example, computed by bend_values."""
    name, design = bend_template()
    folded = fold_design(design)
    m, u = design.material, design.units.value
    lines = [
        f"Template `{name}` (`onefold build {name}`): thickness t = {m.thickness:g} {u}, "
        f"inside bend radius r = {m.bend_radius:g} {u}, K-factor K = {m.k_factor:g}, "
        f"reference surface {m.sheet_surface.value}, model {design.model.value}.",
        "",
        "| crease half | length | fold angle psi | bend | BA = psi (r + K t) | "
        "OSSB = (r + t) tan(psi/2) | BD = 2 SB - BA | SB = (r + s t) tan(psi/2) | "
        "reference in the bend | shift = SB - BA/2 |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for c in folded.crease:
        bv = bend_values(c.fold_angle_deg, m, c.bend)
        lines.append(
            f"| {c.name} | {c.length:.4g} {u} | {bv.angle_deg:.4f} deg | {c.bend} | "
            f"{bv.allowance:.4f} {u} | {bv.outside_setback:.4f} {u} | {bv.deduction:.4f} {u} | "
            f"{bv.setback:.4f} {u} | {bv.reference.value} (s = {bv.s:g}) | {bv.shift:.4f} {u} |"
        )
    c = folded.crease[0]
    bv = bend_values(c.fold_angle_deg, m, c.bend)
    psi = math.radians(c.fold_angle_deg)
    lines += [
        "",
        f"Step by step for `{c.name}`: psi = {c.fold_angle_deg:.4f} deg = {psi:.6f} rad; "
        f"BA = {psi:.6f} x ({m.bend_radius:g} + {m.k_factor:g} x {m.thickness:g}) = "
        f"{psi * (m.bend_radius + m.k_factor * m.thickness):.4f} {u}; the {c.bend} bend puts the "
        f"{m.sheet_surface.value} reference surface s = {bv.s:g} thicknesses from the inside "
        f"face, so SB = ({m.bend_radius:g} + {bv.s:g} x {m.thickness:g}) x "
        f"tan({c.fold_angle_deg / 2:.4f} deg) = "
        f"{(m.bend_radius + bv.s * m.thickness) * math.tan(psi / 2):.4f} {u}; "
        f"BD = 2 SB - BA = {bv.deduction:.4f} {u}; each side of the blank moves "
        f"SB - BA/2 = {bv.shift:.4f} {u} towards the fold line. "
        f"Relief hole at the apex: {m.relief_hole_diameter:.4g} {u} diameter.",
        "",
    ]
    return "\n".join(lines)


def template_previews_exist(name: str) -> list[str]:
    return [f"images/templates/{name}.png", f"images/templates/{name}-flat.png"]


def templates_block() -> str:
    """The template catalogue: one section per shipped template."""
    out = []
    for info, d in templates():
        fr, m, u = d.frame, d.material, d.units.value
        sheet = d.sheet
        out += [
            f"### {info.name}",
            "",
            info.description or "(no description)",
            "",
            f"- frame: alpha {fr.alpha:g} deg, beta {fr.beta:g} deg, h_c {fr.h_c:g}, "
            f"radius {fr.radius:g}, divisions {fr.divisions}; model {d.model.value}",
            f"- sheet: {sheet.kind} {_sheet_inputs(sheet)}; area {sheet.area:.6g} {u}^2",
            f"- material: {m.name or 'unnamed'}, thickness {m.thickness:g} {u}, "
            f"bend radius {m.bend_radius:g} {u}, K {m.k_factor:g}; units {u}",
            f"- build: `onefold build {info.name}`",
            "",
            f"![{info.name} folded](images/templates/{info.name}.png) "
            f"![{info.name} flat pattern](images/templates/{info.name}-flat.png)",
            "",
        ]
    return "\n".join(out)


def _sheet_inputs(sheet: Any) -> str:
    inputs = {k: v for k, v in sheet.inputs.items() if k != "points"}
    if "points" in sheet.inputs:
        inputs["vertices"] = len(sheet.inputs["points"])
    return ", ".join(
        f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}" for k, v in inputs.items()
    )


# -- CLI -------------------------------------------------------------------------------
def cli_help(args: list[str]) -> str:
    """The output of ``onefold ARGS --help`` (100 columns), trailing blanks removed."""
    from onefold_cad.cli.parser import help_text

    lines = [ln.rstrip() for ln in help_text(args[0] if args else "").splitlines()]
    return "\n".join(lines).strip("\n") + "\n"


def cli_block() -> str:
    """The CLI reference: ``onefold --help`` and each command's ``--help``."""
    from onefold_cad.cli.commands import COMMANDS

    out = ["### `onefold`", "", "```text", cli_help([]).rstrip(), "```", ""]
    for name in sorted(COMMANDS):
        out += [f"### `onefold {name}`", "", "```text", cli_help([name]).rstrip(), "```", ""]
    return "\n".join(out)


# -- images ---------------------------------------------------------------------------
def _flat_png(folded: Any, design: Design, path: Path) -> Path:
    """Flat pattern of ``design`` (fold frame): outline, crease halves, rulings, H."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 5))
    b = np.vstack([folded.boundary_flat, folded.boundary_flat[:1]])
    ax.plot(b[:, 0], b[:, 1], color="k", lw=1.2, label="CUT")
    for r in folded.rulings_flat[:: max(1, len(folded.rulings_flat) // 40)]:
        ax.plot(r[:, 0], r[:, 1], color="#aaaaaa", lw=0.4)
    for c in folded.crease:
        col = "#d62728" if c.bend == "UP" else "#1f77b4"
        ax.plot(
            [0, c.end_flat[0]],
            [0, c.end_flat[1]],
            color=col,
            lw=2,
            label=f"BEND_{c.bend} {c.fold_angle_deg:.1f} deg ({c.name})",
        )
    hole = design.material.relief_hole_diameter
    if hole > 0:
        ax.add_patch(plt.Circle((0, 0), hole / 2, fill=False, color="k", lw=0.8))
    ax.plot([0], [0], "k+", ms=8)
    ax.set_aspect("equal")
    ax.legend(fontsize=7, loc="lower left")
    ax.set_title(f"{design.name}: flat pattern (fold frame, {design.units.value})", fontsize=9)
    ax.tick_params(labelsize=7)
    fig.tight_layout()
    tmp = path.with_name(f".{path.name}.tmp")
    fig.savefig(tmp, format="png", dpi=100)
    plt.close(fig)
    os.replace(tmp, path)
    return path


def _flat_renderer() -> Callable[[Any, Design, Path], Path]:
    """The package's DXF preview of the real flat pattern if present, else ours."""
    try:
        from onefold_cad.export.dxf import draw_flat_pattern
        from onefold_cad.export.dxf_preview import render_preview
        from onefold_cad.fabrication.flat_pattern import flat_pattern
    except ImportError:
        return _flat_png

    def render(folded: Any, design: Design, path: Path) -> Path:
        return render_preview(draw_flat_pattern(flat_pattern(design, folded)), path, dpi=80)

    return render


def make_template_previews() -> list[Path]:
    """docs/images/templates/<name>.png (folded) and <name>-flat.png per template."""
    out_dir = IMAGES / "templates"
    out_dir.mkdir(parents=True, exist_ok=True)
    flat = _flat_renderer()
    out = []
    for info, design in templates():
        folded = fold_design(design)
        try:
            from onefold_cad.export.preview import render_folded_preview
        except ImportError:  # pragma: no cover - the preview module ships with the package
            render_folded_preview = None
        p3 = out_dir / f"{info.name}.png"
        if render_folded_preview is not None:
            render_folded_preview(
                folded, p3, title=info.name, units=design.units.value, size_px=(600, 450)
            )
        out.append(p3)
        out.append(flat(folded, design, out_dir / f"{info.name}-flat.png"))
    return out


def make_fabrication_figure() -> Path:
    """docs/images/fabrication_layers.png: the bend example's flat pattern (its DXF)."""
    name, design = bend_template()
    IMAGES.mkdir(parents=True, exist_ok=True)
    return _flat_renderer()(fold_design(design), design, IMAGES / "fabrication_layers.png")


# -- Hops ------------------------------------------------------------------------------
@functools.cache
def _hops_blocks() -> dict[str, str]:
    """The blocks of docs/rhino.md, made by docs/make_hops_example.py (a
    solve posted to a Hops server started for it), once per run."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "make_hops_example", DOCS / "make_hops_example.py"
    )
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.hops_blocks()


def _hops_block(name: str) -> Callable[[], str]:
    return lambda: _hops_blocks()[name]


GENERATED: dict[str, tuple[str, Callable[[], str]]] = {
    "bend-example": ("fabrication.md", bend_example_block),
    "templates": ("templates.md", templates_block),
    "cli": ("cli.md", cli_block),
    "hops-components": ("rhino.md", _hops_block("hops-components")),
    "hops-example": ("rhino.md", _hops_block("hops-example")),
}


def api_modules() -> list[str]:
    """Every module of the package, for pdoc (the package's ``__all__`` hides submodules)."""
    import pkgutil

    import onefold_cad

    names = [m.name for m in pkgutil.walk_packages(onefold_cad.__path__, "onefold_cad.")]
    return ["onefold_cad", *sorted(n for n in names if not n.split(".")[-1].startswith("_"))]


def build_api(outdir: Path) -> Path:
    """Run pdoc on the whole package into ``outdir``; return its index.html."""
    import subprocess
    import sys

    cmd = [sys.executable, "-m", "pdoc", *api_modules(), "-o", str(outdir)]
    subprocess.run([*cmd, "--docformat", "google"], check=True, capture_output=True, text=True)
    return outdir / "index.html"


def main(argv: list[str] | None = None) -> int:
    import argparse

    ap = argparse.ArgumentParser(description="regenerate the generated blocks of docs/")
    ap.add_argument("--api", type=Path, metavar="DIR", help="also build the pdoc API reference")
    args = ap.parse_args(argv)
    if args.api:
        print(build_api(args.api))
    for name, (fname, make) in GENERATED.items():
        write_block(DOCS / fname, name, make())
        print(f"{DOCS / fname}: block {name!r} updated")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
