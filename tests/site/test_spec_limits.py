"""A site's number of sheets is bounded: a larger one is refused up front,
naming the limit, before any sheet is read or built (a site of 1 000 sheets
once grew to about 9 GB and 351 MB of staging before a refusal)."""

from __future__ import annotations

from pathlib import Path

import pytest

import onefold_cad.cli.site as site_cli
from onefold_cad.cli.main import main
from onefold_cad.errors import InvalidParameterError
from onefold_cad.site.spec import MAX_SHEETS, read_site


def site_text(n: int) -> str:
    """A row of ``n`` paper squares 400 mm apart (200 mm each: apart)."""
    head = 'name = "row"\nunits = "mm"\n'
    sheet = '[[sheet]]\nname = "s{i}"\ntemplate = "paper-square"\nx = {x}\ny = 0.0\n'
    return head + "".join(sheet.format(i=i, x=400.0 * i) for i in range(n))


def write(tmp_path: Path, n: int) -> Path:
    p = tmp_path / "site.toml"
    p.write_text(site_text(n), encoding="utf-8")
    return p


def test_the_largest_site_is_read(tmp_path):
    site = read_site(write(tmp_path, MAX_SHEETS))
    assert len(site.sheets) == MAX_SHEETS == 100


def test_one_sheet_more_is_refused_naming_the_limit(tmp_path):
    with pytest.raises(InvalidParameterError) as err:
        read_site(write(tmp_path, MAX_SHEETS + 1))
    assert err.value.parameter == "site.toml: sheet"
    assert f"at most {MAX_SHEETS} sheets in a site, got {MAX_SHEETS + 1}" in str(err.value)


def test_the_command_refuses_a_thousand_sheets_before_building_any(tmp_path, capfd, monkeypatch):
    def built(*args, **kwargs):
        raise AssertionError("a sheet was solved before the site was refused")

    monkeypatch.setattr(site_cli, "check_jobs", built)
    out = tmp_path / "out"
    capfd.readouterr()
    assert main(["site", str(write(tmp_path, 1000)), "-o", str(out)]) == 2
    stdout, stderr = capfd.readouterr()
    assert stdout == "" and stderr.splitlines() == [
        f"onefold: error: site.toml: sheet: at most {MAX_SHEETS} sheets in a site, got 1000 "
        "(every sheet's part stays in memory until the site's files are written; split the "
        "site into several files)"
    ]
    assert not out.exists()
