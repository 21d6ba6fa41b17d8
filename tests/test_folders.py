"""Families live in folders: no folder of the package holds more than 20
modules directly, and the ``__init__`` docstring of export/, geometry/ and
each of their sub-packages names every module and sub-package it holds
(a new module is listed where it lands)."""

from __future__ import annotations

import ast
import re

import pytest

from onefold_cad.layers import PACKAGE

#: The most modules a folder of the package holds directly.
MAX_MODULES = 20
#: The trees whose __init__ docstrings map their folders.
MAPPED = ("export", "geometry")


def _packages():
    return sorted(p.parent for p in PACKAGE.rglob("__init__.py"))


def _members(folder):
    """The modules and sub-packages directly in ``folder``."""
    mods = {p.stem for p in folder.glob("*.py") if p.name != "__init__.py"}
    subs = {p.parent.name for p in folder.glob("*/__init__.py")}
    return mods, subs


def test_no_folder_holds_more_than_20_modules():
    crowded = {
        str(f.relative_to(PACKAGE)): len(_members(f)[0])
        for f in _packages()
        if len(_members(f)[0]) > MAX_MODULES
    }
    assert crowded == {}


@pytest.mark.parametrize(
    "folder",
    [f for f in _packages() if f.relative_to(PACKAGE).parts[:1] in [(m,) for m in MAPPED]],
    ids=lambda f: str(f.relative_to(PACKAGE)),
)
def test_the_init_docstring_names_every_module_of_its_folder(folder):
    doc = ast.get_docstring(ast.parse((folder / "__init__.py").read_text(encoding="utf-8")))
    assert doc, f"{folder.name}/__init__.py has no docstring"
    named = set(re.findall(r":mod:`\.(\w+)`", doc))
    mods, subs = _members(folder)
    assert (mods | subs) - named == set()
    assert named - (mods | subs) == set()  # no module named that is not there


def _feature_table() -> list[tuple[str, str]]:
    text = (PACKAGE.parent / "docs" / "architecture.md").read_text(encoding="utf-8")
    section = text.split("## Where each feature lives", 1)[1].split("\n## ", 1)[0]
    rows = [ln.split("|")[1:3] for ln in section.splitlines() if ln.startswith("| ")]
    return [(f.strip(), cell) for f, cell in rows[1:]]


def _paths(cell: str) -> list[str]:
    """The files and folders a cell names, under onefold_cad/: a bare
    ``name.py`` is in the last folder named before it in its ``;`` group."""
    out = []
    for group in cell.split(";"):
        folder = ""
        for token in re.findall(r"`([^`]+)`", group):
            if token.endswith("/"):
                folder = token
                out.append(token)
            elif token.endswith(".py"):
                out.append(token if "/" in token else folder + token)
    return out


def test_the_feature_table_names_files_that_exist():
    table = _feature_table()
    assert len(table) >= 15 and {"STEP", "site", "fit (inverse design)"} <= {f for f, _ in table}
    missing = [
        (feature, path)
        for feature, cell in table
        for path in _paths(cell)
        if not list(PACKAGE.glob(path.rstrip("/")))
    ]
    assert missing == []
