"""The package's shape: short modules, public names for what crosses a module."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from onefold_cad.layers import ROOT, modules

#: The longest a module may be (lines): split by job before it gets there.
MAX_LINES = 450


def test_no_module_is_over_450_lines():
    long = {
        name: n
        for name, path in modules().items()
        if (n := len(path.read_text(encoding="utf-8").splitlines())) > MAX_LINES
    }
    assert long == {}


def _private_imports(path: Path) -> list[tuple[str, str, int]]:
    """``(module, name, line)`` of each private name (``_x``, not dunder)
    imported from a module of the package."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("onefold_cad"):
            for a in node.names:
                if a.name.startswith("_") and not a.name.startswith("__"):
                    out.append((node.module, a.name, node.lineno))
    return out


@pytest.mark.parametrize("folder", ["onefold_cad", "benchmarks", "scripts", "docs"])
def test_no_private_name_is_imported_across_modules(folder):
    found = [
        f"{path.relative_to(ROOT)}:{line} imports {name} from {module}"
        for path in sorted((ROOT / folder).rglob("*.py"))
        for module, name, line in _private_imports(path)
    ]
    assert found == []


def test_tests_import_the_public_name_where_there_is_one():
    mods = modules()
    public = {
        name: {
            n.name if hasattr(n, "name") else t.id
            for n in ast.parse(path.read_text(encoding="utf-8")).body
            for t in ([n] if hasattr(n, "name") else getattr(n, "targets", []))
            if hasattr(t, "id") or hasattr(n, "name")
        }
        for name, path in mods.items()
    }
    found = [
        f"{path.relative_to(ROOT)}:{line} imports {name} from {module}"
        for path in sorted((ROOT / "tests").rglob("*.py"))
        for module, name, line in _private_imports(path)
        if name.lstrip("_") in public.get(module, set())
    ]
    assert found == []


def test_no_file_holds_a_merge_conflict_marker():
    """A merge left half-resolved shows in no source, doc or template."""
    root = ROOT
    marker = ("<" * 7 + " ", "=" * 7 + "\n", ">" * 7 + " ")
    found = []
    for sub in ("onefold_cad", "tests", "docs", "benchmarks", "scripts", "templates"):
        for path in (root / sub).rglob("*"):
            if path.suffix not in {".py", ".md", ".toml", ".js", ".html", ".css", ".txt"}:
                continue
            for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(True), 1):
                if line.startswith(marker):
                    found.append(f"{path.relative_to(root)}:{i}")
    for name in ("README.md", "Makefile", "pyproject.toml"):
        text = (root / name).read_text(encoding="utf-8")
        found += [
            f"{name}:{i}" for i, ln in enumerate(text.splitlines(True), 1) if ln.startswith(marker)
        ]
    assert found == []
