"""Design flags: names of flag-made designs, template data with flags, units, sources."""

from __future__ import annotations

import re

import pytest
from hypothesis import given
from hypothesis import strategies as st

from onefold_cad import InvalidParameterError
from onefold_cad.flags.design_flags import DESIGN_FLAGS
from onefold_cad.flags.jobs import load_jobs
from onefold_cad.flags.overrides import Overrides, derived_name

NO_FLAGS = {f.dest: None for f in DESIGN_FLAGS}
SAFE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]{0,63}$")


def flags(**given):
    return {**NO_FLAGS, **given}


def test_derived_names_say_what_defines_the_design():
    assert derived_name("onefold", {"rectangle": "3048x7315.2", "alpha": 35.0}) == (
        "onefold-alpha35-3048x7315.2"
    )
    assert derived_name("table1-row1", {"model": "exact", "thickness": 3.0}) == (
        "table1-row1-exact-t3"
    )
    assert derived_name("t", {"hc": -10.0, "units": "in"}) == "t-in-hc-10"
    poly = derived_name("onefold", {"polygon": "300,0;0,200;-250,0;0,-150"})
    assert re.fullmatch(r"onefold-polygon4-[0-9a-f]{6}", poly)
    other = derived_name("onefold", {"polygon": "300,0;0,201;-250,0;0,-150"})
    assert other != poly  # another polygon, another name


@given(st.dictionaries(st.sampled_from([f.dest for f in DESIGN_FLAGS if f.dest not in
       ("polygon", "rectangle", "model", "units", "sheet_surface")]),
       st.floats(-1e300, 1e300, allow_nan=False), max_size=12))  # fmt: skip
def test_derived_names_are_always_file_safe(values):
    name = derived_name("onefold", values)
    assert SAFE.match(name), name


def test_a_long_name_keeps_its_start_and_ends_in_a_hash():
    values = {k: 123456.789 for k in ("alpha", "beta", "hc", "radius", "thickness", "kerf")}
    name = derived_name("a-rather-long-template-name", values)
    assert len(name) == 64 and name.startswith("a-rather-long-template-name-alpha123457")
    assert re.search(r"-[0-9a-f]{8}$", name)
    assert name != derived_name("a-rather-long-template-name", {**values, "kerf": 1.0})


def test_overrides_replace_template_values_and_name_the_flags():
    data = {"frame": {"alpha": 40}, "sheet": {"rectangle": {"width": 2, "height": 1}}}
    out, names = Overrides(alpha=50.0, apex_fraction=0.3, thickness=2.0).apply(data)
    assert out["frame"]["alpha"] == 50.0 and data["frame"]["alpha"] == 40  # a copy
    assert out["sheet"]["rectangle"] == {"width": 2, "height": 1, "apex_fraction": 0.3}
    assert out["material"]["thickness"] == 2.0
    assert names == {
        "frame.alpha": "--alpha",
        "material.thickness": "--thickness",
        "sheet.rectangle.apex_fraction": "--apex-fraction",
    }


@pytest.mark.parametrize(
    ("values", "flag", "words"),
    [
        ({"polygon": "1,0;0,1;-1,0", "rectangle": "2x2"}, "--rectangle", "cannot be combined"),
        ({"x_plus": 3.0}, "--x-minus", "missing"),
        ({"rectangle": "3x"}, "--rectangle", "WIDTHxHEIGHT"),
        ({"polygon": "1,2;3"}, "--polygon", '"x,y"'),
        ({"polygon": "1,a;0,1;-1,0"}, "--polygon", "'a' is not a number"),
    ],
)
def test_overrides_refuse_sheets_they_cannot_make(values, flag, words):
    with pytest.raises(InvalidParameterError) as exc:
        Overrides(**values).apply({"sheet": {"rectangle": {"width": 2, "height": 1}}})
    assert exc.value.parameter == flag and words in str(exc.value)


def test_load_jobs_names_sources_and_units():
    (job,) = load_jobs([], flags(thickness=2.0))
    assert job.design.name == "onefold-t2"  # never the default template's name
    assert job.template == "patkau-one-fold"
    assert job.sources["material.thickness"] == "--thickness"
    assert job.sources["material.bend_radius"] == "inherited from template patkau-one-fold"
    assert job.sources["material.relief_hole"] == "default"
    (plain,) = load_jobs([], NO_FLAGS)
    assert plain.design.name == "patkau-one-fold"  # no flag: it is the template itself
    (named,) = load_jobs(["table1-row1"], flags(alpha=40.0), name="mine")
    assert named.design.name == "mine" and named.sources["model"] == "template table1-row1"


def test_flags_are_read_in_the_unit_the_template_is_converted_to():
    (job,) = load_jobs(["paper-square"], flags(units="in", bend_radius=0.01))
    d = job.design
    assert d.units.value == "in"
    assert d.material.bend_radius == 0.01  # read in inches, not converted
    assert d.material.thickness == pytest.approx(0.1 / 25.4, rel=1e-15)  # the template's, converted
    assert d.sheet.inputs["width"] == pytest.approx(200 / 25.4, rel=1e-15)
    assert job.sources["units"] == "--units"


def test_a_flags_only_design_does_not_inherit_the_default_template_s_description():
    (job,) = load_jobs([], flags(rectangle="1000x400", alpha=30.0, beta=30.0))
    text = job.design.description
    default = load_jobs([], NO_FLAGS)[0].design.description
    assert default.startswith("Patkau Architects' One-Fold: 10 x 24 ft")  # the template's own
    assert "Patkau" not in text and "10 x 24 ft" not in text
    for flag in ("--rectangle 1000x400", "--alpha 30", "--beta 30"):
        assert flag in text
    assert "template patkau-one-fold" in text  # where the other values came from


def test_a_named_template_changed_by_flags_says_so_in_its_description():
    (plain,) = load_jobs(["table1-row1"], NO_FLAGS)
    (job,) = load_jobs(["table1-row1"], flags(alpha=40.0))
    assert job.design.description.startswith(plain.design.description)
    assert job.design.description.endswith("(changed by --alpha 40)")


@pytest.mark.parametrize(
    ("refs", "given", "name"),
    [
        ([], {"thickness": 1.0},
         "304 stainless steel (from template patkau-one-fold), t from flags"),
        ([], {"thickness": 1.0, "bend_radius": 2.0},
         "304 stainless steel (from template patkau-one-fold), t and r from flags"),
        (["broken-vault"], {"bend_radius": 0.1},
         "mild steel (from template broken-vault), r from flags"),
        (["paper-square"], {"thickness": 0.2},
         "office paper (from template paper-square), t from flags"),
    ],
)  # fmt: skip
def test_a_material_whose_t_or_r_a_flag_changed_claims_no_gauge(refs, given, name):
    (job,) = load_jobs(refs, flags(**given))
    assert job.design.material.name == name
    assert "gauge" not in name and "g/m^2" not in name


def test_a_flag_repeating_the_template_s_thickness_keeps_the_material_name():
    (job,) = load_jobs([], flags(thickness=3.57, k_factor=0.4))
    assert job.design.material.name == "304 stainless steel, 10 gauge (assumed)"


def test_a_converted_thickness_is_not_a_changed_one():
    (job,) = load_jobs(["broken-vault"], flags(units="mm"))
    assert job.design.material.name == "mild steel, 18 gauge"
    assert job.design.material.thickness == pytest.approx(0.0478 * 25.4, rel=1e-15)
