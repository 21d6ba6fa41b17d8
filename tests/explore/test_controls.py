"""The page's query: bounded, validated by the CLI's own parser, the CLI's messages."""

from __future__ import annotations

import builtins
import io
import os
import pathlib

import pytest

from onefold_cad.cli.main import main
from onefold_cad.explore.controls import (
    MAX_POLYGON,
    MAX_QUERY,
    MAX_VALUE,
    ParameterProblem,
    QueryError,
    design_from_params,
    page_values,
    parse_query,
)
from onefold_cad.explore.server import load_templates
from onefold_cad.templates import design_to_data, list_templates


@pytest.fixture(scope="module")
def templates():
    return load_templates(None)


def _cli_error(capfd, args: list[str]) -> str:
    """The one line `onefold solve ARGS` prints after 'onefold: error: ' (exit 2)."""
    capfd.readouterr()
    assert main(["solve", *args]) == 2
    err = capfd.readouterr().err.strip()
    assert err.startswith("onefold: error: ") and "\n" not in err
    return err[len("onefold: error: ") :]


@pytest.mark.parametrize(
    ("params", "args", "controls"),
    [
        ({"alpha": "95"}, ["--alpha", "95"], ("alpha",)),
        ({"alpha": "abc"}, ["--alpha", "abc"], ("alpha",)),
        ({"beta": "0"}, ["--beta", "0"], ("beta",)),
        ({"hc": "90"}, ["--hc", "90"], ("hc",)),
        ({"model": "cone"}, ["--model", "cone"], ("model",)),
        ({"divisions": "0", "model": "paper"}, ["--divisions", "0", "--model", "paper"], ()),
        ({"width": "-5", "height": "7315.2"}, ["--rectangle", "-5x7315.2"], ("width", "height")),
        ({"cone_forming": "die"}, ["--cone-forming", "die"], ("cone_forming",)),
        ({"apex_fraction": "1"}, ["--apex-fraction", "1"], ("apex_fraction",)),
        ({"thickness": "-1"}, ["--thickness", "-1"], ("thickness",)),
        ({"bend_radius": "nan"}, ["--bend-radius", "nan"], ("bend_radius",)),
        ({"polygon": "1,2;3"}, ["--polygon", "1,2;3"], ("polygon",)),
        ({"x_plus": "10"}, ["--x-plus", "10"], ("x_minus",)),  # the first one missing
    ],
    ids=lambda v: "-".join(v) if isinstance(v, list) else None,
)
def test_a_bad_value_gets_the_message_onefold_solve_prints(
    templates, capfd, params, args, controls
):
    data, key = templates
    expected = _cli_error(capfd, args)
    with pytest.raises(ParameterProblem) as info:
        design_from_params(params, data, key)
    assert info.value.message == expected
    assert set(controls) <= set(info.value.controls)


def test_the_values_reach_the_design(templates):
    data, key = templates
    params = {
        "model": "paper",
        "divisions": "12",
        "alpha": "40",
        "beta": "35.5",
        "hc": "-5",
        "radius": "120",
        "width": "1000",
        "height": "2500",
        "apex_fraction": "0.3",
        "thickness": "1.5",
        "bend_radius": "2.25",
    }
    d = design_from_params(params, data, key)
    assert (d.model.value, d.frame.divisions) == ("paper", 12)
    assert (d.frame.alpha, d.frame.beta, d.frame.h_c, d.frame.radius) == (40.0, 35.5, -5.0, 120.0)
    assert d.sheet.kind == "rectangle"
    assert d.sheet.inputs == {"width": 1000.0, "height": 2500.0, "apex_fraction": 0.3}
    assert (d.material.thickness, d.material.bend_radius) == (1.5, 2.25)


@pytest.mark.parametrize("name", [t.name for t in list_templates()])
def test_the_page_values_of_every_template_give_back_the_same_design(templates, name):
    """What the page shows for a template, sent back unchanged, is that template exactly."""
    data, _ = templates
    design = design_from_params({"template": name}, data, name)
    page = page_values(design)
    again = design_from_params({"template": name, **page["values"]}, data, name)
    assert design_to_data(again) == design_to_data(design)
    assert page["sheet_kind"] == design.sheet.kind


def test_a_thickness_changed_on_the_page_unclaims_the_template_s_gauge(templates):
    data, key = templates
    page = page_values(design_from_params({}, data, key))["values"]
    d = design_from_params({**page, "thickness": "2", "alpha": "41"}, data, key)
    assert d.material.name == "304 stainless steel (from template patkau-one-fold), t from the page"
    assert d.description.endswith("(changed by --alpha 41 --thickness 2)")  # only what changed


def test_the_hc_limit_is_r_cos_alpha(templates):
    data, key = templates
    d = design_from_params({"alpha": "60", "radius": "50"}, data, key)
    assert page_values(d)["hc_limit"] == pytest.approx(25.0, rel=1e-15)


@pytest.mark.parametrize(
    ("query", "why"),
    [
        ("alpha=30&colour=red", "unknown parameter"),
        ("alpha=30&alpha=31", "given twice"),
        ("alpha=" + "1" * (MAX_VALUE + 1), "too long"),
        ("polygon=" + "1" * (MAX_POLYGON + 1), "too long"),
        ("a=" * (MAX_QUERY // 2 + 1), "query too long"),
        ("&".join(f"alpha{i}=1" for i in range(40)), "malformed query"),
        ("alpha=%ff", "malformed query"),
    ],
    ids=["unknown", "twice", "long-value", "long-polygon", "long-query", "many", "not-utf8"],
)
def test_a_malformed_query_is_refused(query, why):
    with pytest.raises(QueryError, match=why):
        parse_query(query)


def test_a_well_formed_query_is_split():
    assert parse_query("alpha=30.5&polygon=1%2C2%3B3%2C4&template=paper-square") == {
        "alpha": "30.5",
        "polygon": "1,2;3,4",
        "template": "paper-square",
    }


@pytest.mark.parametrize(
    "params",
    [
        {"template": "/etc/passwd"},
        {"template": "../../templates/paper-square.toml"},
        {"template": "paper-square.toml"},
        {"polygon": "/etc/passwd"},
        {"alpha": "../../../etc/passwd"},
    ],
    ids=["absolute", "relative", "file-name", "polygon", "alpha"],
)
def test_path_like_input_never_reaches_the_file_system(templates, monkeypatch, params):
    """Every file-system call made while the page's values are read is
    recorded: none of them is given anything made from those values (the
    standard library may still look up its own files, e.g. gettext's
    message catalogues when argparse words an error)."""
    data, key = templates
    design_from_params({}, data, key)  # imports done before the calls are recorded
    seen: list[str] = []

    def recording(original):
        def call(*args, **kwargs):
            seen.append(" ".join(str(a) for a in args))
            return original(*args, **kwargs)

        return call

    for target, name in [
        (builtins, "open"),
        (io, "open"),
        (os, "open"),
        (os, "stat"),
        (os, "listdir"),
        (os, "scandir"),
        (pathlib.Path, "open"),
        (pathlib.Path, "exists"),
        (pathlib.Path, "is_file"),
        (pathlib.Path, "read_bytes"),
        (pathlib.Path, "read_text"),
    ]:
        monkeypatch.setattr(target, name, recording(getattr(target, name)))
    try:
        with pytest.raises(ParameterProblem) as info:
            design_from_params(params, data, key)
    finally:
        monkeypatch.undo()
    given = [v for v in params.values()]
    leaked = [call for call in seen for v in given if v in call or "passwd" in call]
    assert not leaked
    if "template" in params:
        assert info.value.message.startswith("template: no such template")
        assert info.value.controls == ("template",)


def test_the_cones_control_reaches_the_material_and_comes_back(templates):
    data, _ = templates
    design = design_from_params({"cone_forming": "compensated"}, data, "patkau-one-fold")
    assert design.material.cones_compensated
    assert page_values(design)["values"]["cone_forming"] == "compensated"
    # 'design', the page's default, changes nothing of a template that gives none
    plain = design_from_params({"cone_forming": "design"}, data, "patkau-one-fold")
    assert design_to_data(plain) == design_to_data(design_from_params({}, data, "patkau-one-fold"))
