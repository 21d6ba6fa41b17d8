"""The habits the tools check: mypy configured and run by ``make lint``."""

from __future__ import annotations

import re
import tomllib

from onefold_cad.layers import ROOT

PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def _make_target(name: str) -> list[str]:
    """The recipe lines of the Makefile's target ``name``."""
    text = (ROOT / "Makefile").read_text(encoding="utf-8")
    block = re.search(rf"^{name}:[^\n]*\n((?:\t[^\n]*\n)+)", text, re.M)
    assert block is not None, f"no target {name} in the Makefile"
    return [line.strip() for line in block.group(1).splitlines()]


def test_make_lint_runs_the_type_checker_over_the_package():
    assert "$(BIN)/mypy onefold_cad" in _make_target("lint")


def test_mypy_is_a_test_extra_with_a_lower_bound():
    extras = PYPROJECT["project"]["optional-dependencies"]["test"]
    assert any(re.fullmatch(r"mypy>=[0-9.]+", e) for e in extras)


def test_missing_stubs_are_ignored_module_by_module_not_for_all():
    mypy = PYPROJECT["tool"]["mypy"]
    assert "ignore_missing_imports" not in mypy
    assert "ignore_errors" not in mypy
    for override in mypy.get("overrides", []):
        modules = override["module"]
        for name in [modules] if isinstance(modules, str) else modules:
            assert name not in ("*", "onefold_cad", "onefold_cad.*")


def test_only_the_mechanics_family_is_held_back_from_the_check():
    held = [o["module"] for o in PYPROJECT["tool"]["mypy"]["overrides"] if o.get("ignore_errors")]
    assert held == [["onefold_cad.mechanics.*"]]
