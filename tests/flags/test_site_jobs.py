"""A site's sheets as designs: the template with the sheet's flags, in the
site's unit, named after the sheet."""

from __future__ import annotations

from pathlib import Path

import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.flags.site_jobs import sheet_job, site_jobs
from onefold_cad.site.spec import read_site
from onefold_cad.templates import load_template

TEXT = """
name = "s"
units = "{units}"
[[sheet]]
name = "a"
template = "paper-square"
x = 0.0
y = 0.0
[[sheet]]
name = "b"
template = "paper-square"
flags = {{ alpha = 35.0, bend-radius = 0.5, apex_fraction = 0.4 }}
x = 1.0
y = 0.0
"""


def site(tmp_path: Path, units: str = "mm", text: str = TEXT):
    p = tmp_path / "s.toml"
    p.write_text(text.format(units=units), encoding="utf-8")
    return read_site(p)


def test_each_sheet_is_its_template_with_its_flags_named_after_the_sheet(tmp_path):
    base = load_template("paper-square")
    a, b = (j.design for j in site_jobs(site(tmp_path)))
    assert (a.name, b.name) == ("a", "b")
    assert a.frame == base.frame and a.material == base.material.with_changes(name=a.material.name)
    assert b.frame.alpha == 35.0 and b.frame.beta == base.frame.beta
    assert b.material.bend_radius == 0.5
    assert b.sheet.inputs["apex_fraction"] == 0.4
    assert "changed by --units" not in a.description  # the site's unit is the template's


def test_a_site_in_inches_converts_the_template(tmp_path):
    (a, _) = (j.design for j in site_jobs(site(tmp_path, "in")))
    base = load_template("paper-square")
    assert a.units.value == "in"
    assert a.sheet.inputs["width"] == pytest.approx(base.sheet.inputs["width"] / 25.4)


@pytest.mark.parametrize(
    ("flag", "where", "words"),
    [
        ("alpah = 3.0", "flags.alpah", "unknown design flag"),
        ("units = 'in'", "flags.units", "unknown design flag"),
        ("alpha = 'wide'", "flags.alpha", "wide"),
        ("alpha = 95.0", "flags.alpha", "(0, 90)"),
    ],
)
def test_a_bad_flag_names_the_entry_and_the_key(tmp_path, flag, where, words):
    text = TEXT.replace("alpha = 35.0", flag)
    s = site(tmp_path, text=text)
    with pytest.raises(InvalidParameterError) as err:
        sheet_job(s, s.sheets[1])
    assert err.value.parameter == f"s.toml: sheet 2 'b': {where}", str(err.value)
    assert words in str(err.value)


INLINE = """
[sheet.design]
name = "x"
[sheet.design.frame]
alpha = 40.0
beta = 40.0
[sheet.design.sheet.rectangle]
width = 100.0
height = 50.0
apex_fraction = 0.5
"""


def test_an_inline_design_takes_the_site_s_unit_and_names_its_bad_keys(tmp_path):
    text = TEXT.replace('template = "paper-square"\nflags', "flags") + INLINE
    s = site(tmp_path, text=text)
    d = sheet_job(s, s.sheets[1]).design
    assert d.units.value == "mm" and d.sheet.inputs["width"] == 100.0 and d.frame.alpha == 35.0
    s = site(tmp_path, text=text.replace("width = 100.0", "widht = 100.0"))
    with pytest.raises(InvalidParameterError) as err:
        sheet_job(s, s.sheets[1])
    assert "s.toml: sheet 2 'b': design" in err.value.parameter
    assert "widht" in str(err.value)
