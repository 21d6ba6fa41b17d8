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


def test_the_version_is_pyproject_s_read_back_from_the_package_metadata():
    import importlib.metadata

    from onefold_cad import __version__

    assert PYPROJECT["project"]["version"] == importlib.metadata.version("onefold_cad")
    assert __version__ == PYPROJECT["project"]["version"]
    version_py = (ROOT / "onefold_cad" / "version.py").read_text(encoding="utf-8")
    assert PYPROJECT["project"]["version"] not in version_py  # written once


def test_onefold_version_prints_it(capsys):
    from onefold_cad.cli.main import main

    assert main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"onefold {PYPROJECT['project']['version']}"


def test_the_readme_s_test_command_runs_the_lint_and_ci_runs_that_command():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "make test" in readme
    recipe = _make_target("test")
    assert any("lint" in line for line in recipe) or "lint" in _prerequisites("test")
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert [line for line in ci.splitlines() if line and not line.startswith("#")][-1] == (
        "exec make test"
    )


def _prerequisites(name: str) -> list[str]:
    text = (ROOT / "Makefile").read_text(encoding="utf-8")
    line = re.search(rf"^{name}:([^\n]*)$", text, re.M)
    assert line is not None
    return line.group(1).split()


def test_the_pre_commit_hooks_run_ruff_and_the_layer_contract():
    text = (ROOT / ".pre-commit-config.yaml").read_text(encoding="utf-8")
    entries = re.findall(r"entry: (\S+)", text)
    assert {".venv/bin/ruff", ".venv/bin/lint-imports"} <= set(entries)
    assert "repo: local" in text


def test_the_changelog_keeps_a_changelog_s_form():
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert "[Keep a Changelog]" in text
    versions = re.findall(r"^## \[([^\]]+)\]", text, re.M)
    assert versions[0] == "Unreleased"
    assert PYPROJECT["project"]["version"] in versions
    for section in re.findall(r"^### (\w+)", text, re.M):
        assert section in {"Added", "Changed", "Deprecated", "Removed", "Fixed", "Security"}


def test_contributing_says_how_to_set_up_test_and_commit():
    text = (ROOT / "CONTRIBUTING.md").read_text(encoding="utf-8")
    for needed in ("make test", '-m "not browser"', "layers", "72 characters"):
        assert needed in text
