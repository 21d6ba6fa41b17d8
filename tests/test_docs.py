"""The documentation: links and images exist, generated blocks are current, pdoc builds."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[1] / "docs"
PAGES = sorted(DOCS.glob("*.md"))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")
BLOCKS = {
    "fabrication.md": ["bend-example"],
    "templates.md": ["templates"],
    "cli.md": ["cli"],
    "benchmarks.md": ["bench_solver", "bench_pipeline", "bench_sweep", "bench_explore"],
    "sweep.md": ["sweep-study"],
    "rhino.md": ["hops-components", "hops-example"],
}


def _reference():
    spec = importlib.util.spec_from_file_location("make_reference", DOCS / "make_reference.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def reference():
    return _reference()


def _code_free(text: str) -> str:
    """The Markdown without fenced code blocks (links there are not links)."""
    return re.sub(r"```.*?```", "", text, flags=re.S)


def test_pages_exist():
    names = {p.name for p in PAGES}
    for page in (
        "index.md",
        "theory.md",
        "fabrication.md",
        "cli.md",
        "templates.md",
        "benchmarks.md",
        "sweep.md",
        "api.md",
    ):
        assert page in names


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_relative_links_and_images_exist(page):
    targets = LINK.findall(_code_free(page.read_text()))
    missing = []
    for t in targets:
        if re.match(r"^[a-z]+:", t) or t.startswith("#"):
            continue  # external link or in-page anchor
        path = (page.parent / t.split("#", 1)[0]).resolve()
        if not path.exists():
            missing.append(t)
    assert not missing, f"{page.name}: missing link targets {missing}"


def test_every_page_is_reachable_from_the_index():
    linked = set(LINK.findall((DOCS / "index.md").read_text()))
    for page in PAGES:
        if page.name != "index.md":
            assert page.name in linked, f"index.md does not link {page.name}"


@pytest.mark.parametrize(("page", "name"), [(p, n) for p, ns in BLOCKS.items() for n in ns])
def test_generated_blocks_are_filled(reference, page, name):
    body = reference.read_block((DOCS / page).read_text(), name)
    assert body.strip(), f"{page}: block {name!r} is empty; run the generator"


@pytest.mark.parametrize(
    "name", ["bend-example", "templates", "cli", "hops-components", "hops-example"]
)
def test_generated_blocks_are_current(reference, name):
    page, make = reference.GENERATED[name]
    current = reference.read_block((DOCS / page).read_text(), name)
    assert current == make(), f"{page}: block {name!r} is stale; run docs/make_reference.py"


def test_bend_example_numbers_match_bend_values(reference):
    """The worked example's BA/OSSB/BD are those of bend_values at the template's angle."""
    from onefold_cad import bend_values, fold_design

    name, design = reference.bend_template()
    assert design.material.thickness > 0.0
    text = reference.read_block((DOCS / "fabrication.md").read_text(), "bend-example")
    for c in fold_design(design).crease:
        bv = bend_values(c.fold_angle_deg, design.material)
        row = next(r for r in text.splitlines() if r.startswith(f"| {c.name} |"))
        cells = [x.strip() for x in row.strip("|").split("|")]
        assert float(cells[2].split()[0]) == pytest.approx(c.fold_angle_deg, abs=1e-4)
        assert float(cells[4].split()[0]) == pytest.approx(bv.allowance, abs=1e-4)
        assert float(cells[5].split()[0]) == pytest.approx(bv.outside_setback, abs=1e-4)
        assert float(cells[6].split()[0]) == pytest.approx(bv.deduction, abs=1e-4)


def test_template_previews_exist(reference):
    for info, _ in reference.templates():
        for rel in reference.template_previews_exist(info.name):
            assert (DOCS / rel).is_file(), rel


def test_pdoc_builds_the_api_reference(reference, tmp_path):
    modules = reference.api_modules()
    assert "onefold_cad.geometry.solver" in modules and "onefold_cad.cli" in modules
    res = subprocess.run(
        [sys.executable, "-m", "pdoc", *modules, "-o", str(tmp_path), "--docformat", "google"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert res.returncode == 0, res.stderr
    for mod in modules:
        page = tmp_path.joinpath(*mod.split(".")).with_suffix(".html")
        assert page.is_file(), mod
    solver = (tmp_path / "onefold_cad" / "geometry" / "solver.html").read_text()
    assert "angle_condition_error_deg" in solver  # the Solution docstring made it in


FILES = {  # what `onefold build` writes, by --formats name
    "step": ".step", "dxf": ".dxf", "cut": "-cut.dxf", "bends": "-bends.csv",
    "cones": "-cones.csv", "fold": ".fold", "glb": ".glb", "3dm": ".3dm", "json": ".json",
    "png": "-3d.png", "svg": "-flat.svg",
}  # fmt: skip


@pytest.mark.parametrize("page", [DOCS.parent / "README.md", DOCS / "cli.md"], ids=str)
def test_the_files_build_writes_are_all_listed_with_their_format(page):
    from onefold_cad.export.writers import WRITERS

    assert {n: w.suffix for n, w in WRITERS.items()} == FILES
    rows = [ln for ln in page.read_text().splitlines() if ln.startswith("| `")]
    for name, suffix in FILES.items():
        assert any(f"`NAME{suffix}`" in r and f"`{name}`" in r for r in rows), (name, suffix)


@pytest.mark.parametrize("name", ["readme-folded.png", "readme-flat.png"])
def test_readme_pictures_are_at_least_800_px_wide(name):
    from PIL import Image

    with Image.open(DOCS / "images" / name) as img:
        assert img.width >= 800


def test_readme_python_examples_run(tmp_path):
    """The README's Python blocks, run in order as one script, write what they say."""
    readme = (DOCS.parent / "README.md").read_text()
    code = "\n".join(re.findall(r"```python\n(.*?)```", readme, flags=re.S))
    assert "build_part" in code and "export_stl" in code
    script = tmp_path / "readme_example.py"
    script.write_text(code)
    proc = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=600
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.splitlines()[1].startswith("True ")  # the solid is valid
    for name in ("demo.stl", "demo.glb", "demo.brep", "demo.step", "patkau.step", "patkau.dxf"):
        assert (tmp_path / name).stat().st_size > 0


def test_a_time_per_design_in_the_sweep_docs_states_its_command_and_load():
    """A time a design (``N s a design``) is stated with the command that
    measured it and the machine's load (timings depend on both)."""
    page = (DOCS / "sweep.md").read_text(encoding="utf-8")
    paragraphs = [
        " ".join(p.split()) for p in page.split("\n\n") if re.search(r"\d\s+s a design", p)
    ]
    assert paragraphs
    for p in paragraphs:
        assert "`onefold sweep" in p and "load average" in p, p
