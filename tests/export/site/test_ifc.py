"""SITE.ifc is deterministic: two writes of one site are the same
bytes, every GlobalId is a valid IFC GUID (22 characters of IFC's base64
alphabet, decoding to the uuid it came from), unique in the file, and none is
shared with a site of another name. The site here is two sheets whose parts
are boxes (the writer meshes whatever part it is given: the ids and the header
do not depend on the body; the shipped site's IFC is validated in
tests/cli/test_site.py)."""

from __future__ import annotations

import re
import uuid

import build123d as bd
import pytest

from onefold_cad.design import fold_design
from onefold_cad.export.site.context import SiteContext, SiteSheet
from onefold_cad.export.site.ifc import write_site_ifc
from onefold_cad.site.placement import SitePlacement
from onefold_cad.templates import load_template

#: IFC's base64 alphabet (IfcGloballyUniqueId): the first character encodes 2 bits.
GUID = re.compile(r"^[0-3][0-9A-Za-z_$]{21}$")


def _site(name: str) -> SiteContext:
    design = load_template("paper-square")
    folded = fold_design(design)
    size = float(design.sheet.size)
    sheets = [
        SiteSheet(
            sheet,
            design,
            folded,
            bd.Box(size, size / 2, size / 10),
            None,
            {"flat_area": float(design.sheet.area), "mass": None},
            SitePlacement(x, 0.0, turn),
        )
        for sheet, x, turn in (("north", 0.0, 0.0), ("south", 3 * size, 90.0))
    ]
    return SiteContext(name, "two boxes", design.units.value, sheets)


def _ids(path) -> list[str]:
    import ifcopenshell

    return [e.GlobalId for e in ifcopenshell.open(str(path)).by_type("IfcRoot")]


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("ifc")
    paths = {}
    # Five writes of one site: an order left to a set of IfcOpenShell's
    # entities (hashed by address) changed between writes only now and then.
    keys = [("one", "plaza")] + [(f"again{i}", "plaza") for i in range(4)] + [("other", "court")]
    for key, name in keys:
        (out / key).mkdir()
        paths[key] = out / key / "site.ifc"
        write_site_ifc(_site(name), paths[key])
    return paths


def test_two_writes_of_a_site_are_the_same_bytes(written):
    one = written["one"].read_bytes()
    for i in range(4):
        assert written[f"again{i}"].read_bytes() == one
    assert b"FILE_NAME('site.ifc'," in one  # its own name, not the temporary file's


def test_global_ids_are_ifc_guids_unique_in_the_file(written):
    from ifcopenshell.guid import compress, expand

    ids = _ids(written["one"])
    assert len(ids) >= 2 + 2 * 4  # project, site, and each plate with its relations
    assert len(set(ids)) == len(ids)
    for g in ids:
        assert GUID.match(g), g
        assert compress(uuid.UUID(expand(g)).hex) == g  # decodes to a uuid and back


def test_another_site_shares_no_global_id(written):
    assert not set(_ids(written["one"])) & set(_ids(written["other"]))


def test_the_unit_order_does_not_follow_ifcopenshells_set(tmp_path, monkeypatch):
    """IfcOpenShell's assign_unit gathers the units in a set, whose order
    follows the entities' addresses; a set that iterates backwards stands in
    for an unlucky run. The file must not change."""
    import importlib

    usecase = importlib.import_module("ifcopenshell.api.unit.assign_unit")

    class Backwards(list):
        def add(self, item):
            self.insert(0, item)

    paths = []
    for backwards in (False, True):
        if backwards:
            monkeypatch.setattr(
                usecase, "set", lambda items: Backwards(reversed(items)), raising=False
            )
        paths.append(tmp_path / f"{backwards}" / "site.ifc")
        paths[-1].parent.mkdir()
        write_site_ifc(_site("plaza"), paths[-1])
    assert paths[0].read_bytes() == paths[1].read_bytes()
