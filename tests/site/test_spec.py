"""The site file's reader: the shipped site, and every malformed entry named
by its file, entry and key."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.site.spec import SHEET_KEYS, read_site

SHIPPED = Path(__file__).resolve().parents[2] / "templates" / "site-patkau-three.toml"

GOOD = """
name = "two"
units = "mm"
[[sheet]]
name = "a"
template = "paper-square"
x = 0.0
y = 0.0
[[sheet]]
name = "b"
template = "paper-square"
x = 1000
y = -20.5
rotation = 90
flags = { alpha = 40.0 }
"""


def write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "site.toml"
    p.write_text(text, encoding="utf-8")
    return p


def test_the_shipped_site_reads_as_its_file_says():
    raw = tomllib.loads(SHIPPED.read_text(encoding="utf-8"))
    site = read_site("site-patkau-three")
    assert site.path == SHIPPED and site.name == raw["name"] and site.units == "mm"
    assert [s.name for s in site.sheets] == [e["name"] for e in raw["sheet"]]
    for s, e in zip(site.sheets, raw["sheet"], strict=True):
        assert (s.x, s.y, s.rotation_deg) == (e["x"], e["y"], e.get("rotation", 0.0))
        assert s.data["name"] == "patkau-one-fold" and Path(s.source).name == "patkau-one-fold.toml"


def test_a_site_file_gives_positions_rotations_and_flags(tmp_path):
    site = read_site(write(tmp_path, GOOD))
    a, b = site.sheets
    assert (a.x, a.y, a.rotation_deg, a.flags) == (0.0, 0.0, 0.0, {})
    assert (b.x, b.y, b.rotation_deg, b.flags) == (1000.0, -20.5, 90.0, {"alpha": 40.0})
    assert b.entry == "sheet 2 'b'"


def test_an_inline_design_is_kept_as_template_data(tmp_path):
    text = GOOD.replace('template = "paper-square"\nx = 1000', "x = 1000", 1)
    text += '[sheet.design]\nname = "inline"\n[sheet.design.frame]\nalpha = 30.0\n'
    site = read_site(write(tmp_path, text))
    assert site.sheets[1].data == {"name": "inline", "frame": {"alpha": 30.0}}
    assert site.sheets[1].source == "site.toml: sheet 2 'b': design"


@pytest.mark.parametrize(
    ("old", "new", "where"),
    [
        ('rotation = 90', 'rotaton = 90', "site.toml: sheet 2 'b': rotaton"),
        ('rotation = 90', 'rotation = "ninety"', "site.toml: sheet 2 'b': rotation"),
        ('y = -20.5\n', '', "site.toml: sheet 2 'b': y"),
        ('name = "b"', 'name = "a"', "site.toml: sheet 2 'a': name"),
        ('name = "b"', 'name = "b/c"', "site.toml: sheet 2 'b/c': name"),
        ('flags = { alpha = 40.0 }', 'flags = 3', "site.toml: sheet 2 'b': flags"),
        ('template = "paper-square"\nx = 1000', 'template = "no-such"\nx = 1000',
         "site.toml: sheet 2 'b': template"),
        ('units = "mm"', 'units = "km"', "site.toml: units"),
        ('units = "mm"', 'units = "mm"\ncolour = 1', "site.toml: colour"),
    ],
)  # fmt: skip
def test_a_malformed_entry_names_the_entry_and_the_key(tmp_path, old, new, where):
    assert old in GOOD
    with pytest.raises(InvalidParameterError) as err:
        read_site(write(tmp_path, GOOD.replace(old, new, 1)))
    assert err.value.parameter == where
    assert "\n" not in str(err.value)


def test_a_sheet_needs_a_template_or_a_design_not_both(tmp_path):
    text = GOOD.replace('template = "paper-square"\nx = 1000', "x = 1000", 1)
    with pytest.raises(InvalidParameterError, match="exactly one of template"):
        read_site(write(tmp_path, text))


def test_an_unknown_key_lists_the_allowed_ones(tmp_path):
    with pytest.raises(InvalidParameterError) as err:
        read_site(write(tmp_path, GOOD.replace("rotation = 90", "angle = 90")))
    assert all(k in str(err.value) for k in SHEET_KEYS)


def test_an_unknown_site_or_bad_toml_is_named(tmp_path):
    with pytest.raises(InvalidParameterError, match="no such file or shipped site"):
        read_site("site-nowhere")
    with pytest.raises(InvalidParameterError, match="not valid TOML"):
        read_site(write(tmp_path, "name = "))
