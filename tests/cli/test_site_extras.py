"""``onefold site`` without an optional package: the file it leaves out of the
default (all) is said, in one warning line with the extra to install."""

from __future__ import annotations

import dataclasses

from onefold_cad.cli.main import main
from onefold_cad.export.site import writers as site_writers
from tests.cli.test_site import TWO


def _site(capfd, tmp_path, *args: str) -> tuple[int, list[str], list[str]]:
    tmp_path.mkdir(exist_ok=True)
    path = tmp_path / "site.toml"
    path.write_text(TWO.replace("x = 40.0", "x = 400.0"), encoding="utf-8")
    out = tmp_path / "out"
    capfd.readouterr()
    rc = main(["site", str(path), "-o", str(out), "--sheet-formats", "none", "-q", *args])
    stdout, stderr = capfd.readouterr()
    return rc, [p.name for p in out.iterdir()], stderr.splitlines()


def test_without_ifcopenshell_the_default_site_says_the_ifc_is_not_written(
    capfd, tmp_path, monkeypatch
):
    ifc = dataclasses.replace(site_writers.SITE_WRITERS["ifc"], requires="onefold_no_such_module")
    monkeypatch.setitem(site_writers.SITE_WRITERS, "ifc", ifc)
    rc, files, err = _site(capfd, tmp_path)
    assert rc == 0 and "two.ifc" not in files and "two.step" in files
    assert err == [
        "onefold: warning: two.ifc not written: the ifc file needs onefold_no_such_module, which "
        "is not installed: pip install 'onefold_cad[bim]'"
    ]


def test_with_every_package_or_formats_named_nothing_is_said(capfd, tmp_path, monkeypatch):
    rc, files, err = _site(capfd, tmp_path, "--formats", "order")
    assert rc == 0 and files == ["two-order.csv"] and err == []
    ifc = dataclasses.replace(site_writers.SITE_WRITERS["ifc"], requires="onefold_no_such_module")
    monkeypatch.setitem(site_writers.SITE_WRITERS, "ifc", ifc)
    rc, files, err = _site(capfd, tmp_path / "b", "--formats", "order")
    assert rc == 0 and err == []
