"""The design's named options read from text in any case; a bad name is an
error naming the parameter as the API spells it and listing the allowed names."""

from __future__ import annotations

import pytest

from onefold_cad.choices import (
    SIMULATION_DEFAULTS,
    CheckMesh,
    Compensation,
    Law,
    Model,
    SheetSurface,
    Units,
)
from onefold_cad.errors import InvalidParameterError

CHOICES = [
    (Model, "model", ["paper", "exact"]),
    (Units, "units", ["mm", "m", "in", "ft"]),
    (SheetSurface, "sheet_surface", ["INSIDE", "OUTSIDE", "MID"]),
    (Compensation, "compensation", ["sharp", "none"]),
]


@pytest.mark.parametrize(("cls", "parameter", "names"), CHOICES)
def test_every_name_parses_in_any_case_to_its_member(cls, parameter, names):
    assert [m.value for m in cls] == names
    for name in names:
        for text in (name, name.upper(), name.lower(), name.capitalize()):
            assert cls.parse(text) is cls(name)
        assert cls.parse(cls(name)) is cls(name)


@pytest.mark.parametrize(("cls", "parameter", "names"), CHOICES)
def test_a_bad_name_names_the_parameter_and_the_allowed_names(cls, parameter, names):
    with pytest.raises(InvalidParameterError) as err:
        cls.parse("bogus")
    assert err.value.parameter == parameter
    assert f"must be one of {', '.join(names)}, got 'bogus'" in str(err.value)


#: A parameter or field of one of these names is an option of :mod:`onefold_cad.choices`.
OPTION_NAMES = {"body", "placement", "compensation", "sheet_surface", "model"}


def _string_typed_options(path):
    """``(line, name)`` of each argument or field named as an option but
    annotated ``str`` or ``str | None`` in the module at ``path``."""
    import ast

    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.arg | ast.AnnAssign) and node.annotation is not None:
            name = node.arg if isinstance(node, ast.arg) else getattr(node.target, "id", "")
            if name in OPTION_NAMES and ast.unparse(node.annotation) in ("str", "str | None"):
                out.append((node.lineno, name))
    return out


def test_options_travel_as_their_enums_not_as_strings():
    from onefold_cad.layers import ROOT, modules

    found = [
        f"{path.relative_to(ROOT)}:{line} {name}: str"
        for module, path in modules().items()
        if not module.startswith("onefold_cad.mechanics")  # its own work in progress
        for line, name in _string_typed_options(path)
    ]
    assert found == []


@pytest.mark.parametrize(
    ("level", "h_max", "expected"),
    [
        ("normal", None, CheckMesh.COARSER),
        ("fine", None, CheckMesh.COARSER),
        ("coarse", None, CheckMesh.FINER),  # no level below it
        ("normal", 0.2, CheckMesh.FINER),  # a given edge has no coarser level
    ],
)
def test_the_check_s_default_mesh_is_the_coarser_level_where_there_is_one(level, h_max, expected):
    assert CheckMesh.default_for(level, h_max) is expected


def test_simulate_s_default_law_is_j2():
    assert SIMULATION_DEFAULTS["law"] is Law.J2
