"""The --formats registry: names, order, refusals before writing, and a new writer."""

from __future__ import annotations

import json

import pytest

from onefold_cad import Design, FabricationError, FrameCurve, Material, Sheet, fold_design
from onefold_cad.errors import InvalidParameterError
from onefold_cad.export import writers
from onefold_cad.export.write_checks import check_before_writing
from onefold_cad.export.writers import (
    WRITERS,
    BuildContext,
    Writer,
    file_names,
    parse_formats,
    register,
    write_design,
)


def context(**material) -> BuildContext:
    d = Design(
        "w", FrameCurve(40, 40), Sheet.rectangle(300, 200, 0.5), material=Material(**material)
    )
    return BuildContext(d, fold_design(d))


def test_default_is_every_writer_with_the_report_last():
    every = ("step", "dxf", "cut", "bends", "fold", "glb", "3dm", "png", "svg", "json")
    assert parse_formats(None) == parse_formats("all") == every
    assert parse_formats("json, DXF") == ("dxf", "json")
    assert parse_formats("svg,step") == ("step", "svg")
    assert file_names("w", ("step", "png", "json")) == ["w.step", "w-3d.png", "w.json"]


@pytest.mark.parametrize(
    ("text", "words"),
    [
        (
            "step,pdf",
            "unknown format 'pdf' "
            "(allowed: step, dxf, cut, bends, cones, fold, glb, 3dm, png, svg, json, or all)",
        ),
        ("dxf,dxf", "'dxf' is named twice"),
        (" , ", "names no format"),
    ],
)
def test_bad_formats_name_the_flag_and_the_allowed_ones(text, words):
    with pytest.raises(InvalidParameterError) as exc:
        parse_formats(text)
    assert exc.value.parameter == "--formats" and words in str(exc.value)


def test_a_writer_whose_package_is_missing_is_left_out_of_all_and_refused_by_name(monkeypatch):
    """The .3dm needs rhino3dm (an optional extra): without it the default
    writes the rest, and naming it says what to install."""
    real = writers.find_spec
    monkeypatch.setattr(writers, "find_spec", lambda n: None if n == "rhino3dm" else real(n))
    assert "3dm" not in parse_formats(None) and "glb" in parse_formats("all")
    with pytest.raises(InvalidParameterError, match="'3dm' needs rhino3dm, which is not") as exc:
        parse_formats("step,3dm")
    assert exc.value.parameter == "--formats"


def test_a_relief_hole_that_does_not_fit_is_refused_by_the_cut_part_s_writers_only():
    ctx = context(relief_hole=500.0)  # the sheet's inradius about H is well below 250
    for fmt in ("step", "dxf", "cut", "fold", "3dm", "svg"):  # FOLD and 3DM cut the hole too
        with pytest.raises(FabricationError) as exc:
            check_before_writing(ctx, (fmt,))
        assert exc.value.parameter == "relief_hole"
    check_before_writing(ctx, ("png", "json"))  # previews of the form and the report: fine


def test_a_flat_pattern_that_cannot_be_made_is_refused_before_writing():
    d = Design(
        "corner", FrameCurve(60, 70), Sheet.rectangle(40, 100, 0.5),
        material=Material(thickness=3.57, bend_radius=6.0),
    )  # fmt: skip
    ctx = BuildContext(d, fold_design(d))
    with pytest.raises(FabricationError, match="^bend_radius: "):
        check_before_writing(ctx, ("dxf", "json"))
    with pytest.raises(FabricationError, match="^bend_radius: "):
        check_before_writing(ctx, ("step", "json"))  # the default body is the solid
    check_before_writing(ctx, ("png", "json"))
    ctx.compensation = "none"
    check_before_writing(ctx, ("dxf", "step", "json"))


def test_a_registered_writer_is_written_timed_and_listed_in_the_report(tmp_path, monkeypatch):
    monkeypatch.setattr(writers, "WRITERS", dict(WRITERS))
    calls = []

    def write_csv(ctx: BuildContext, path):
        path.write_text(f"{ctx.design.name},{len(ctx.folded.crease)}\n")

    register(Writer("csv", "-bends.csv", "bend table", write_csv))
    formats = parse_formats("csv,json")
    assert formats == ("csv", "json")
    ctx = context()
    files = write_design(ctx, tmp_path / "1", formats, lambda s, t: calls.append((s, t)))
    assert [f.name for f in files] == ["w-bends.csv", "w.json"]
    assert (tmp_path / "1" / "w-bends.csv").read_text() == "w,2\n"
    assert [c[0] for c in calls] == ["bend table", "report"]
    assert all(t >= 0 for _, t in calls)
    rep = json.loads((tmp_path / "1" / "w.json").read_text())
    assert rep["files"] == ["w-bends.csv", "w.json"]
    assert set(rep["timings_s"]) >= {"csv"}


def test_a_solid_past_the_bend_limits_is_refused_for_the_step_and_the_glb_alike():
    """The STEP and the GLB hold the same part: each alone is refused before writing,
    with the error the part's builder gives (--compensation none writes both)."""
    from onefold_cad.fabrication.rules import solid_bend_problem

    d = Design(
        "corner", FrameCurve(60, 70), Sheet.rectangle(40, 100, 0.5),
        material=Material(thickness=3.57, bend_radius=6.0),
    )  # fmt: skip
    ctx = BuildContext(d, fold_design(d))
    expected = str(solid_bend_problem(d, ctx.folded))
    for fmt in ("step", "glb"):
        with pytest.raises(FabricationError) as exc:
            check_before_writing(ctx, (fmt,))
        assert str(exc.value) == expected
    check_before_writing(BuildContext(d, ctx.folded, body="shell"), ("step", "glb"))
    ctx.compensation = "none"
    check_before_writing(ctx, ("step", "glb"))


@pytest.mark.parametrize("placement", ["rest", "frame"])
def test_the_step_and_the_glb_are_one_part_built_once_and_the_report_gives_its_fit(
    tmp_path, monkeypatch, placement
):
    """build_part runs once for both files; the GLB's mesh (metres, y up, turned back)
    fills the STEP's bounding box in the same placement; the report gives the part's
    fit deviation and tolerance, which the STEP's curves meet."""
    import build123d as bd
    import numpy as np
    import trimesh

    from onefold_cad.export.brep import part as step
    from onefold_cad.export.glb import LINEAR_DEFLECTION

    calls = []
    real = step.build_part

    def counted(*args, **kwargs):
        calls.append(kwargs)
        return real(*args, **kwargs)

    monkeypatch.setattr(step, "build_part", counted)
    ctx = context()
    ctx.placement = placement
    write_design(ctx, tmp_path / "1", ("step", "glb", "json"))
    assert len(calls) == 1 and calls[0]["placement"] == placement
    box = bd.import_step(tmp_path / "1" / "w.step").bounding_box(optimal=True)
    lo, hi = np.array(tuple(box.min)), np.array(tuple(box.max))
    x, y, z = trimesh.load(tmp_path / "1" / "w.glb", force="mesh").vertices.T * 1000.0
    mesh = np.stack([x, -z, y], axis=1)  # y up -> z up, mm
    size = ctx.design.sheet.size
    slack = 1e-6 * size
    assert np.all(mesh.min(axis=0) >= lo - slack) and np.all(mesh.max(axis=0) <= hi + slack)
    deflection = LINEAR_DEFLECTION * size
    assert np.all(mesh.min(axis=0) <= lo + deflection)
    assert np.all(mesh.max(axis=0) >= hi - deflection)
    if placement == "rest":
        assert abs(lo[2]) <= 1e-6 * size  # standing on the ground
    else:  # the fold frame: the apex is a vertex of the shell, above H
        verts = np.array([tuple(v) for v in bd.import_step(tmp_path / "1" / "w.step").vertices()])
        assert np.min(np.linalg.norm(verts - ctx.folded.apex, axis=1)) <= 1e-9 * size
    rep = json.loads((tmp_path / "1" / "w.json").read_text())
    part = ctx.part
    assert rep["step"] == {
        "body": "shell",
        "placement": placement,
        "fit_deviation": part.fit_deviation,
        "fit_tolerance": part.fit_tolerance,
        "volume": None,  # a shell
        "volume_over_blank": None,
    }
    assert 0.0 < rep["step"]["fit_deviation"] <= rep["step"]["fit_tolerance"]


def test_the_report_gives_the_solid_s_volume_against_the_blank_s(tmp_path):
    """The mass weighs the blank (flat_area x t); the STEP solid holds the
    mitre at the crease as well: the report gives both, measured apart."""
    import build123d as bd

    from onefold_cad.export.brep.measure import measure

    ctx = context(thickness=2.0)
    write_design(ctx, tmp_path / "1", parse_formats("step,json"))
    rep = json.loads((tmp_path / "1" / "w.json").read_text())
    # the file read back, integrated to 1e-6 (Gauss-Kronrod to 1e-7 on the
    # read-back faces did not finish in 5 minutes, measured; 1e-6 takes 0.4 s)
    volume = measure(bd.import_step(tmp_path / "1" / "w.step"), "volume", tol=1e-6)
    assert rep["step"]["body"] == "solid"
    assert rep["step"]["volume"] == pytest.approx(volume, rel=2e-6)
    blank = rep["flat_area"] * 2.0
    assert rep["step"]["volume_over_blank"] == pytest.approx(volume / blank - 1.0, abs=2e-6)
    assert 0.0 < rep["step"]["volume_over_blank"] < 0.05  # the mitre adds a little


@pytest.mark.parametrize("placement", ["rest", "frame"])
def test_the_3dm_holds_the_builds_placement_and_flat_pattern(tmp_path, placement):
    """``--formats 3dm`` writes NAME.3dm with the build's placement (the apex
    point where the fold or the resting placement puts it) and the build's
    flat pattern (its outline's corners, moved on the ground)."""
    import numpy as np
    import rhino3dm

    from onefold_cad.fabrication.rules import resting_placement

    ctx = context(thickness=1.0)
    ctx.placement = placement
    files = write_design(ctx, tmp_path / "1", parse_formats("3dm,json"))
    assert [f.name for f in files] == ["w.3dm", "w.json"]
    doc = rhino3dm.File3dm.Read(str(files[0]))
    path = {lay.Index: lay.FullPath for lay in doc.Layers}
    (apex,) = [o for o in doc.Objects if path[o.Attributes.LayerIndex] == "Folded::Apex"]
    want = ctx.folded.apex
    if placement == "rest":
        want = resting_placement(ctx.design, ctx.folded).apply(want[None, :])[0]
    p = apex.Geometry.Location
    assert np.allclose([p.X, p.Y, p.Z], want, rtol=0, atol=1e-9 * ctx.design.sheet.size)
    (outline,) = [o.Geometry for o in doc.Objects if o.Attributes.Name == "outline"]
    pts = np.array([[outline.Point(i).X, outline.Point(i).Y] for i in range(outline.PointCount)])
    blank = ctx.pattern.outline
    shift = pts[0] - blank[0]
    assert np.allclose(pts[:-1] - shift, blank, rtol=0, atol=1e-9 * ctx.design.sheet.size)
    rep = json.loads(files[1].read_text())
    assert "3dm" in rep["timings_s"]
    assert rep["rhino"]["placement"] == placement and rep["rhino"]["faces"] == 2  # one per side
    assert 0.0 < rep["rhino"]["fit_deviation"] <= rep["rhino"]["fit_tolerance"]
    assert rep["rhino"]["fit_tolerance"] == pytest.approx(1e-7 * ctx.design.sheet.size)
    # the file's key numbers are the numbers of the report the build writes
    from onefold_cad.export.rhino.strings import KEY_NUMBERS

    for key in KEY_NUMBERS:
        want = rep
        for part in key.split("."):
            want = None if want is None else want.get(part)
        text = doc.Strings[f"report.{key}"]
        assert (text if isinstance(want, str) else json.loads(text)) == want, key


def test_the_report_runs_no_cad_kernel_when_no_part_was_built(tmp_path):
    ctx = context()
    write_design(ctx, tmp_path / "1", ("json",))
    rep = json.loads((tmp_path / "1" / "w.json").read_text())
    assert rep["step"] is None and rep["rhino"] is None
    assert ctx.built_part is None


def test_the_blank_width_limit_refuses_the_flat_pattern_not_the_solid():
    """An asymmetric fold whose one rigid blank is off by more than 0.1 t across its
    halves: the flat pattern's writers refuse; the STEP solid (the designed part, no
    blank) does not."""
    d = Design(
        "asym", FrameCurve(5, 60, -60), Sheet.quadrilateral(3000, 1000, 2000, 1500),
        material=Material(thickness=10.0, bend_radius=10.0),
    )  # fmt: skip
    ctx = BuildContext(d, fold_design(d), body="solid")
    for fmt in ("dxf", "cut", "bends", "svg"):
        with pytest.raises(FabricationError, match="^hc: plus_x .* too wide across it"):
            check_before_writing(ctx, (fmt,))
    check_before_writing(ctx, ("step", "json"))


def test_the_compensations_the_command_offers_are_the_bend_model_s():
    from onefold_cad.choices import Compensation
    from onefold_cad.cli.main import main
    from onefold_cad.flags.design_flags import COMPENSATIONS

    assert COMPENSATIONS == tuple(c.value for c in Compensation)
    assert COMPENSATIONS[0] == BuildContext.compensation == "sharp"  # the default
    assert main(["build", "--compensation", "bent", "--formats", "json"]) == 2
