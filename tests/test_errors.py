"""The one form of every "install this" hint: ``pip install
'onefold_cad[EXTRA]'`` with an extra the package declares, in the messages
(:func:`onefold_cad.errors.not_installed`) and in the docs."""

from __future__ import annotations

import importlib.util
import re
import tomllib
from pathlib import Path

import pytest

from onefold_cad.errors import InvalidParameterError, not_installed
from onefold_cad.export.writers import WRITERS, parse_formats
from onefold_cad.flags.parser import UsageError
from onefold_cad.hops.launch import check_installed
from onefold_cad.sweep.backends import check_dask

REPO = Path(__file__).resolve().parents[1]
EXTRAS = set(tomllib.loads((REPO / "pyproject.toml").read_text())["project"][
    "optional-dependencies"]) - {"test"}  # fmt: skip


def test_the_sentence_lists_what_is_missing_and_the_extra_to_install():
    assert not_installed("x", ["a"], "bim") == (
        "x needs a, which is not installed: pip install 'onefold_cad[bim]'"
    )
    assert not_installed("onefold hops", ["ghhops_server", "werkzeug", "rhino3dm"], "rhino") == (
        "onefold hops needs ghhops_server, werkzeug and rhino3dm, which are not installed: "
        "pip install 'onefold_cad[rhino]'"
    )


def _hints(text: str) -> list[str]:
    """What follows each ``pip install`` that names an extra (has a ``[``)."""
    return [m for m in re.findall(r"pip\s+install\s+(\S+)", text) if "[" in m]


@pytest.mark.parametrize(
    "path",
    [
        *sorted((REPO / "onefold_cad").rglob("*.py")),
        REPO / "README.md",
        *sorted((REPO / "docs").glob("*.md")),
    ],
    ids=lambda p: str(p.relative_to(REPO)),
)
def test_every_install_hint_names_one_of_the_package_s_extras(path):
    for hint in _hints(path.read_text(encoding="utf-8")):
        m = re.fullmatch(r"'onefold_cad\[([\w{}]+)\]'[`\".,;:)]*", hint)
        assert m and m[1] in EXTRAS | {"EXTRA", "{extra}"}, hint


REAL_FIND_SPEC = importlib.util.find_spec


def _missing(monkeypatch, *names: str) -> None:
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda n, *a: None if n in names else REAL_FIND_SPEC(n, *a)
    )


def test_hops_says_in_one_sentence_what_is_missing(monkeypatch):
    _missing(monkeypatch, "ghhops_server", "werkzeug", "rhino3dm")
    with pytest.raises(UsageError) as exc:
        check_installed()
    assert str(exc.value) == (
        "onefold hops needs ghhops_server, werkzeug and rhino3dm, which are not installed: "
        "pip install 'onefold_cad[rhino]'"
    )
    _missing(monkeypatch, "werkzeug")
    with pytest.raises(UsageError, match=r"^onefold hops needs werkzeug, which is not installed"):
        check_installed()


def test_a_format_of_a_missing_extra_names_the_extra(monkeypatch):
    _missing(monkeypatch, WRITERS["3dm"].requires)
    monkeypatch.setattr("onefold_cad.export.writers.find_spec", importlib.util.find_spec)
    with pytest.raises(InvalidParameterError) as exc:
        parse_formats("3dm")
    assert str(exc.value) == (
        "--formats: '3dm' needs rhino3dm, which is not installed: pip install 'onefold_cad[rhino]'"
    )


def test_the_cluster_hint_names_the_extra(monkeypatch):
    _missing(monkeypatch, "distributed")
    with pytest.raises(UsageError) as exc:
        check_dask()
    assert str(exc.value).endswith("which is not installed: pip install 'onefold_cad[cluster]'")
