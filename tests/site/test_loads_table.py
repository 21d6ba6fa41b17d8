"""The site file's ``[loads]`` table: checked when the file is read (named by
the file, the table and the key), and every sheet's anchors in the order."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from onefold_cad.cli.main import main
from onefold_cad.errors import InvalidParameterError
from onefold_cad.site.spec import read_site

SITE = """
name = "windy"
units = "mm"
[loads]
{loads}
[[sheet]]
name = "a"
template = "patkau-one-fold"
x = 0.0
y = 0.0
"""


def write(tmp_path: Path, loads: str) -> Path:
    p = tmp_path / "site.toml"
    p.write_text(SITE.format(loads=loads), encoding="utf-8")
    return p


def test_the_loads_table_reads_as_load_spec_fields(tmp_path):
    spec = read_site(write(tmp_path, 'wind_speed = 25.0\nterrain = "III"\nsnow = 1.0'))
    assert spec.loads == {"wind_speed": 25.0, "terrain": "III", "snow_kPa": 1.0, "mesh": "normal"}


@pytest.mark.parametrize(
    ("loads", "key", "words"),
    [
        ("wind_speed = -3.0", "wind_speed", "0 to 100 m/s"),
        ('wind_speed = 25.0\nterrain = "V"', "terrain", "0, I, II, III, IV"),
        ("wind_speed = 25.0\nsnow = -1.0", "snow", "--snow"),
        ("wind_speed = 25.0\ngust = 3.0", "gust", "unknown key"),
        ('wind_speed = 25.0\nmesh = "huge"', "mesh", "coarse, normal or fine"),
    ],
)
def test_a_bad_load_names_the_table_and_the_key(tmp_path, loads, key, words):
    with pytest.raises(InvalidParameterError) as err:
        read_site(write(tmp_path, loads))
    assert str(err.value).startswith(f"site.toml: loads: {key}: ")
    assert words in str(err.value)


def test_the_order_lists_each_sheet_s_anchors_and_their_total(tmp_path):
    site = write(tmp_path, 'wind_speed = 25.0\ndirections = 2\nperson = 0.0\nmesh = "coarse"')
    out = tmp_path / "out"
    argv = ["site", str(site), "-o", str(out), "--formats", "order", "--sheet-formats", "none"]
    assert main([*argv, "-q"]) == 0
    rows = list(csv.DictReader((out / "windy-order.csv").open(encoding="utf-8")))
    a, total = rows
    assert a["feet"] == "3" and int(a["anchors"]) >= 1
    assert float(a["anchor_pull_N"]) > 0.0 and a["governing_case"].startswith("EQU")
    assert total["anchor_pull_N"] == a["anchor_pull_N"]
