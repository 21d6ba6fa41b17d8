"""``onefold site``: the shipped site built once (shared by the xdist workers
through a lock), its files read back with the libraries that read them, and
the refusals before anything is written."""

from __future__ import annotations

import csv
import fcntl
import json
import math
import tomllib
from pathlib import Path

import build123d as bd
import numpy as np
import pytest

from onefold_cad.cli.main import main

REPO = Path(__file__).resolve().parents[2]
SITE_FILE = REPO / "templates" / "site-patkau-three.toml"
SITE = tomllib.loads(SITE_FILE.read_text(encoding="utf-8"))
NAMES = [s["name"] for s in SITE["sheet"]]
STEM = SITE["name"]
SUFFIXES = (".step", ".glb", ".ifc", "-plan.dxf", "-order.csv", ".png", ".json")
SITE_FILES = [f"{STEM}{s}" for s in SUFFIXES]


@pytest.fixture(scope="module")
def built(tmp_path_factory, worker_id) -> Path:
    """DIR of ``onefold site site-patkau-three -o DIR -j 2``, built once per run."""
    base = tmp_path_factory.getbasetemp()
    root = base if worker_id == "master" else base.parent
    out = root / "site-patkau-three"
    with open(root / "site-patkau-three.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (root / "site-patkau-three.done").exists():
            assert main(["site", "site-patkau-three", "-o", str(out), "-j", "2", "-q"]) == 0
            (root / "site-patkau-three.done").write_text("ok")
    return out


@pytest.fixture(scope="module")
def assembly(built) -> dict:
    """The site's STEP read back with build123d: label -> part."""
    return {c.label: c for c in bd.import_step(built / f"{STEM}.step").children}


def site_motion(entry: dict) -> tuple[np.ndarray, np.ndarray]:
    """The site file's turn about z and move, read from the file itself."""
    t = math.radians(entry.get("rotation", 0.0))
    rot = np.array([[math.cos(t), -math.sin(t), 0.0], [math.sin(t), math.cos(t), 0.0], [0, 0, 1]])
    return rot, np.array([entry["x"], entry["y"], 0.0])


def test_the_site_writes_every_file_and_each_sheet_s_build(built):
    for name in SITE_FILES:
        assert (built / name).is_file() and (built / name).stat().st_size > 0, name
    for name in NAMES:
        files = sorted(p.name for p in (built / name).iterdir())
        assert f"{name}.step" in files and f"{name}.json" in files and f"{name}.dxf" in files
    assert not [p for p in built.iterdir() if p.name.startswith(".")]  # no staging left


def test_the_step_assembly_holds_each_sheet_named_and_placed_as_the_site_says(built, assembly):
    parts = assembly
    assert sorted(parts) == sorted(NAMES)
    for entry in SITE["sheet"]:
        part = parts[entry["name"]]
        single = bd.import_step(built / entry["name"] / f"{entry['name']}.step")
        assert len(part.solids()) == 1 == len(single.solids())
        assert part.volume == pytest.approx(single.volume, rel=1e-9)
        rot, move = site_motion(entry)
        centre = rot @ np.array(tuple(single.center())) + move
        size = max(single.bounding_box().size)
        assert np.allclose(tuple(part.center()), centre, atol=1e-6 * size)
        # the turn itself: a vertex of the single part lands where the motion puts it
        v = np.array([tuple(p) for p in single.vertices()]) @ rot.T + move
        w = np.array([tuple(p) for p in part.vertices()])
        assert np.abs(v - w).max() <= 1e-6 * size


def test_the_ifc_validates_and_its_plates_are_the_sheets_as_they_stand(built, assembly):
    import ifcopenshell
    import ifcopenshell.geom
    import ifcopenshell.util.unit
    import ifcopenshell.validate

    path = built / f"{STEM}.ifc"
    f = ifcopenshell.open(str(path))
    logger = ifcopenshell.validate.json_logger()
    ifcopenshell.validate.validate(f, logger)
    assert logger.statements == []
    assert f.schema == "IFC4"
    (project,) = f.by_type("IfcProject")
    (site,) = f.by_type("IfcSite")
    assert project.Name == site.Name == STEM
    plates = {p.Name: p for p in f.by_type("IfcPlate")}
    assert sorted(plates) == sorted(NAMES)
    metres = ifcopenshell.util.unit.calculate_unit_scale(f)  # one length unit of the file in m
    assert metres == pytest.approx(1e-3)  # the site's mm
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    for name, plate in plates.items():
        assert plate.PredefinedType == "SHEET"
        assert plate.ContainedInStructure[0].RelatingStructure == site
        (usage,) = [r.RelatingMaterial for r in plate.HasAssociations]
        assert usage.is_a("IfcMaterialLayerSetUsage")
        (layer,) = usage.ForLayerSet.MaterialLayers
        report = json.loads((built / name / f"{name}.json").read_text())
        assert layer.LayerThickness == report["inputs"]["material"]["thickness"]
        assert layer.Material.Name == report["inputs"]["material"]["name"]
        shape = ifcopenshell.geom.create_shape(settings, plate)
        v = np.array(shape.geometry.verts).reshape(-1, 3) / metres  # geom gives metres
        t = np.array(shape.geometry.faces).reshape(-1, 3)
        area = 0.5 * np.linalg.norm(
            np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1
        )
        part = assembly[name]
        assert area.sum() == pytest.approx(part.area, rel=5e-3)
        # where it stands: the mesh's box is the STEP part's (the mesh's deviation apart)
        box = part.bounding_box()
        lo, hi = np.array(tuple(box.min)), np.array(tuple(box.max))
        assert np.abs(v.min(axis=0) - lo).max() < 1e-3 * box.diagonal
        assert np.abs(v.max(axis=0) - hi).max() < 1e-3 * box.diagonal


def test_the_order_s_rows_are_the_reports_and_its_masses_add_up(built):
    rows = list(csv.DictReader((built / f"{STEM}-order.csv").open(encoding="utf-8")))
    total = rows.pop()
    assert total["sheet"] == "TOTAL" and [r["sheet"] for r in rows] == NAMES
    masses = []
    for r in rows:
        rep = json.loads((built / r["sheet"] / f"{r['sheet']}.json").read_text())
        masses.append(rep["mass"]["value"])
        assert float(r["mass"]) == pytest.approx(rep["mass"]["value"], rel=1e-9)
        # ordered in m^2 (the site is in mm; 1 m^2 = 1e6 mm^2)
        assert r["area_unit"] == "m^2"
        assert float(r["blank_area"]) == pytest.approx(rep["flat_area"] / 1e6, rel=1e-9)
        assert float(r["thickness"]) == rep["inputs"]["material"]["thickness"]
        w, h = (
            rep["inputs"]["sheet"]["rectangle"]["width"],
            rep["inputs"]["sheet"]["rectangle"]["height"],
        )
        assert (float(r["stock_width"]), float(r["stock_height"])) == pytest.approx((w, h))
        assert int(r["bends"]) == 2
        angles = [float(a) for a in r["bend_angles_deg"].split(";")]
        assert angles == pytest.approx(list(rep["fold_angles_deg"].values()), abs=1e-3)
        # the cut: the blank's outline and the relief hole's circle (the DXF's CUT layer)
        assert float(r["cut_length"]) > 2 * (w + h) * 0.99
    assert float(total["mass"]) == pytest.approx(sum(masses), rel=1e-9)
    assert total["mass_unit"] == "kg"


def test_the_plan_draws_footprints_contacts_names_and_neighbour_distances(built, assembly):
    import ezdxf

    doc = ezdxf.readfile(built / f"{STEM}-plan.dxf")
    assert not doc.audit().has_errors
    msp = doc.modelspace()
    assert len(msp.query("LWPOLYLINE[layer=='FOOTPRINT']")) == len(NAMES)
    texts = [t.dxf.text for t in msp.query("TEXT")]
    assert all(n in texts for n in NAMES)
    lines = msp.query("LINE[layer=='CLEARANCE']")
    labels = [t.dxf.text for t in msp.query("TEXT[layer=='CLEARANCE']")]
    assert len(lines) == len(labels) >= len(NAMES) - 1
    for line, label in zip(lines, labels, strict=True):
        pair, _, dist = label.partition(": ")
        a, b = pair.split(" - ")
        # the line joins ground projections of a point on each sheet: no longer than the
        # 3D distance it is labelled with, and each end lies over its sheet's footprint
        value = float(dist.split()[0])
        end = np.hypot(*(np.array(line.dxf.end)[:2] - np.array(line.dxf.start)[:2]))
        assert end <= value + 1.0
        for name, p in ((a, line.dxf.start), (b, line.dxf.end)):
            box = assembly[name].bounding_box()
            assert box.min.X - 1 <= p[0] <= box.max.X + 1 and box.min.Y - 1 <= p[1] <= box.max.Y + 1


def test_the_glb_has_one_node_per_sheet(built):
    import trimesh

    scene = trimesh.load(built / f"{STEM}.glb")
    names = " ".join(scene.graph.nodes)
    assert all(n in names for n in NAMES)
    assert len(scene.geometry) >= len(NAMES)


# -- refusals: one line on stderr naming what to change, exit 2, nothing written ---------
TWO = """
name = "two"
units = "mm"
[[sheet]]
name = "left"
template = "paper-square"
flags = { relief-hole = 4.0, thickness = 1.0 }
x = 0.0
y = 0.0
[[sheet]]
name = "right"
template = "paper-square"
flags = { relief-hole = 4.0, thickness = 1.0 }
x = 40.0
y = 0.0
rotation = 90
"""


@pytest.fixture
def site_cli(capfd, tmp_path):
    """``onefold site`` on a site file of ``text``, in this process: (status,
    stdout, stderr lines, the output folder)."""

    def call(text: str, *args: str) -> tuple[int, str, list[str], Path]:
        path = tmp_path / "site.toml"
        path.write_text(text, encoding="utf-8")
        out = tmp_path / "out"
        capfd.readouterr()
        rc = main(["site", str(path), "-o", str(out), *args])
        stdout, stderr = capfd.readouterr()
        return rc, stdout, stderr.splitlines(), out

    return call


def refused(result, *words: str) -> None:
    """Exit 2, one line on stderr holding ``words``, nothing written."""
    rc, stdout, lines, out = result
    lines = [x for x in lines if not x.startswith("[")]  # the progress lines
    assert rc == 2 and stdout == ""
    assert len(lines) == 1 and lines[0].startswith("onefold: error: "), lines
    assert all(w in lines[0] for w in words), lines[0]
    assert not out.exists()


@pytest.mark.parametrize(
    ("old", "new", "words"),
    [
        ('template = "paper-square"\nflags = { relief-hole = 4.0, thickness = 1.0 }\nx = 40.0',
         'template = "no-such-design"\nx = 40.0',
         ("sheet 2 'right': template", "no such file or shipped template: 'no-such-design'")),
        ("x = 40.0\n", "", ("sheet 2 'right': x", "missing")),
        ("x = 40.0", 'x = "forty"', ("sheet 2 'right': x", "must be a number")),
        ("rotation = 90", "rotation = 90\nheight = 2", ("sheet 2 'right': height", "unknown key")),
        ("thickness = 1.0 }\nx = 40.0", "thicknes = 1.0 }\nx = 40.0",
         ("sheet 2 'right': flags.thicknes", "unknown design flag")),
        ("thickness = 1.0 }\nx = 40.0", "thickness = -1.0 }\nx = 40.0",
         ("sheet 2 'right': flags.thickness",)),
        ('units = "mm"', 'units = "furlong"', ("site.toml: units", "mm, m, in, ft")),
    ],
)  # fmt: skip
def test_a_malformed_site_names_the_entry_and_the_key(site_cli, old, new, words):
    assert old in TWO
    refused(site_cli(TWO.replace(old, new, 1)), *words)


def test_bad_formats_and_jobs_are_named(site_cli):
    refused(site_cli(TWO, "--formats", "step,pdf"), "--formats", "unknown format 'pdf'")
    refused(site_cli(TWO, "--sheet-formats", "ifc"), "--sheet-formats", "unknown format 'ifc'")
    refused(site_cli(TWO, "-j", "0"), "--jobs", "must be >= 1")


def test_overlapping_sheets_are_refused_naming_both_and_their_overlap(site_cli):
    result = site_cli(TWO, "--formats", "order", "--sheet-formats", "none")
    refused(result, "'left' and 'right' touch or overlap", "distance 0 mm")
    # found from the folded surfaces before any sheet is built or measured
    # (the exact clearance of built sheets came first before: 78 s here)
    assert "found before building them" in result[2][-1]
    assert not any(" done in " in x or "clearance" in x for x in result[2][:-1])
    # the overlap said: their footprints' shared area, measured here on the reports
    line = result[2][-1]
    assert float(line.split("footprints overlap by ")[1].split()[0]) > 0.0


def test_allow_touching_writes_the_site_with_a_warning(site_cli):
    rc, stdout, lines, out = site_cli(
        TWO, "--formats", "order", "--sheet-formats", "none", "--allow-touching"
    )
    assert rc == 0 and stdout.split() == [str(out / "two-order.csv")]
    assert any("left and right touch or overlap (allowed" in w for w in lines)


def test_sheets_apart_pass_the_check_with_their_exact_distance(site_cli):
    # the two squares turned the same way, 400 mm apart along x: the gap is the
    # distance between the two resting forms' facing extremes, measured on the STEP parts
    text = TWO.replace("x = 40.0", "x = 400.0").replace("rotation = 90\n", "")
    rc, stdout, lines, out = site_cli(text, "--formats", "step", "--sheet-formats", "none")
    assert rc == 0
    left, right = (
        c for c in sorted(bd.import_step(out / "two.step").children, key=lambda c: c.label)
    )
    boxes = left.bounding_box(), right.bounding_box()
    assert boxes[1].min.X - boxes[0].min.X == pytest.approx(400.0, abs=1e-6)
    assert left.distance_to(right) > 0.0


def test_the_numbers_in_docs_site_md_are_the_built_site_s(built):
    import importlib.util

    docs = REPO / "docs"
    spec = importlib.util.spec_from_file_location("make_site_docs", docs / "make_site_docs.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    page = (docs / "site.md").read_text(encoding="utf-8")
    block = mod.read_block(page, "site-patkau")
    assert block == mod.site_block(built), "docs/site.md is stale: run docs/make_site_docs.py"


def test_site_help_has_its_usage_and_names_every_site_file(capsys):
    assert main(["site", "--help"]) == 0
    text = capsys.readouterr().out
    assert text.splitlines()[0] == "usage: onefold site SITE [-o DIR] [options]"
    files = text[text.index("site files (--formats") :].splitlines()[1:]
    assert len(files) == len(SUFFIXES)
    for suffix in SUFFIXES:
        (line,) = [ln for ln in files if f" SITE{suffix} " in ln]
        assert len(line.split(f"SITE{suffix}", 1)[1].strip()) > 20
    for flag in ("--formats", "--sheet-formats", "--jobs", "--allow-touching", "--outdir"):
        assert flag in text
    assert main(["--help"]) == 0
    assert "  site  " in capsys.readouterr().out


def test_a_sheet_with_compensated_cones_gets_its_forming_sheet_by_default(site_cli, built):
    # the DXF notes of such a sheet name NAME-cones.csv: `all` must write it, as
    # `onefold build` does; the shipped site's sheets, formed to the design, get none
    one = (
        'name = "one"\nunits = "mm"\n\n[[sheet]]\nname = "solo"\ntemplate = "patkau-one-fold"\n'
        'flags = { cone_forming = "compensated" }\nx = 0.0\ny = 0.0\n'
    )
    rc, stdout, lines, out = site_cli(one, "--formats", "order", "-q")
    assert rc == 0, lines
    assert str(out / "solo" / "solo-cones.csv") in stdout.split()
    assert main(["build", "patkau-one-fold", "--cone-forming", "compensated", "--formats",
                 "cones", "--name", "solo", "-o", str(out.parent / "b"), "-q"]) == 0  # fmt: skip
    built_alone = (out.parent / "b" / "solo-cones.csv").read_text(encoding="utf-8")
    assert (out / "solo" / "solo-cones.csv").read_text(encoding="utf-8") == built_alone
    for name in NAMES:
        assert not list((built / name).glob("*-cones.csv"))
