"""The 3D preview PNG of the folded form."""

from __future__ import annotations

import struct
import subprocess
import sys

import numpy as np
import pytest

from onefold_cad import Design, ExportError, FrameCurve, Sheet, fold_design
from onefold_cad.export.preview import (
    render_folded_preview,
    resting_mesh,
    support_and_centre,
    thumbnail_png,
)
from onefold_cad.geometry.placement import rest_form


@pytest.fixture(scope="module")
def folded():
    return fold_design(Design("p", FrameCurve(40, 40), Sheet.rectangle(300, 200, 0.5)))


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_resting_mesh_stands_on_the_ground(folded):
    verts, faces = resting_mesh(folded, angular=30, radial=4)
    size = folded.sheet.size
    assert verts[:, 2].min() == pytest.approx(0.0, abs=1e-9 * size)
    assert faces.min() >= 0 and faces.max() < len(verts)
    # A rigid motion of the folded mesh: distances from the apex survive.
    raw, _ = folded.mesh(angular=30, radial=4)
    apex = rest_form(folded).apply(folded.apex[None, :])[0]
    np.testing.assert_allclose(
        np.linalg.norm(verts - apex, axis=1),
        np.linalg.norm(raw - folded.apex, axis=1),
        atol=1e-9 * size,
    )


def test_render_writes_a_png_of_the_requested_size(tmp_path, folded):
    out = render_folded_preview(folded, tmp_path / "p-3d.png", title="p", size_px=(400, 300))
    data = out.read_bytes()
    assert _png_size(data) == (400, 300)
    assert [p.name for p in tmp_path.iterdir()] == ["p-3d.png"]
    import matplotlib.image as mpimg

    img = mpimg.imread(out)[:, :, :3]
    # Not blank: the warm top face or the cool bottom face shows somewhere.
    warm = (img[:, :, 0] - img[:, :, 2]) > 0.15
    cool = (img[:, :, 2] - img[:, :, 0]) > 0.08
    assert warm.sum() + cool.sum() > 0.02 * img.shape[0] * img.shape[1]


def test_a_thumbnail_is_the_same_view_small_and_without_words(folded):
    import io

    import matplotlib.image as mpimg

    data = thumbnail_png(folded, size_px=(240, 180))
    assert _png_size(data) == (240, 180)
    img = mpimg.imread(io.BytesIO(data), format="png")[:, :, :3]
    warm = (img[:, :, 0] - img[:, :, 2]) > 0.15
    cool = (img[:, :, 2] - img[:, :, 0]) > 0.08
    assert warm.sum() + cool.sum() > 0.05 * img.shape[0] * img.shape[1]  # the form fills it
    assert thumbnail_png(folded, size_px=(240, 180)) == data  # the same picture every time


def test_render_failure_raises_export_error_and_leaves_nothing(tmp_path, folded):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ExportError):
        render_folded_preview(folded, blocker / "p.png")
    assert [p.name for p in tmp_path.iterdir()] == ["file"]


def test_matplotlib_is_imported_only_by_the_preview():
    code = (
        "import sys, onefold_cad, onefold_cad.cli.main, onefold_cad.export.preview, "
        "onefold_cad.fabrication.report; print('matplotlib' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


# -- the 3D preview's content ---------------------------------------------------


def test_mesh_faces_turn_their_normal_to_the_top_side(folded):
    """Every triangle's normal (by its vertex order) is the sheet's top-side
    normal there (the colours depend on it): compared with the fold's own
    normal at the triangle's centre, found by unfolding it."""
    raw, faces = folded.mesh(angular=30, radial=4)
    tri = raw[faces]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    flat, _ = folded.unfold(tri.mean(axis=1))
    top = folded.normals(flat)
    assert np.all(np.einsum("ij,ij->i", n, top) > 0.0)


def test_support_polygon_lies_on_the_ground_around_the_centre_of_mass(folded):
    poly, centre = support_and_centre(rest_form(folded))
    size = folded.sheet.size
    assert len(poly) >= 3
    np.testing.assert_allclose(poly[:, 2], 0.0, atol=1e-9 * size)
    # counter-clockwise and convex: every turn is to the left
    e = np.roll(poly[:, :2], -1, axis=0) - poly[:, :2]
    turn = e[:, 0] * np.roll(e[:, 1], -1) - e[:, 1] * np.roll(e[:, 0], -1)
    assert np.all(turn > 0.0)
    # its corners are the lowest points of the resting form (nothing below)
    low = rest_form(folded).apply(folded.map_points(folded.sheet.vertices))[:, 2].min()
    assert low >= -1e-9 * size
    # the form stands, so the centre of mass is above the polygon ...
    assert rest_form(folded).stable
    side = e[:, 0] * (centre[1] - poly[:, 1]) - e[:, 1] * (centre[0] - poly[:, 0])
    assert np.all(side > 0.0)
    assert centre[2] > 0.0


def test_centre_of_mass_is_the_area_centroid_of_the_folded_surface(folded):
    """Independently: the area-weighted centroid of a fine triangle mesh of
    the resting form (chords of the cone: the error falls as 1/angular^2)."""
    verts, faces = resting_mesh(folded, angular=720, radial=40)
    tri = verts[faces]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    expected = (area[:, None] * tri.mean(axis=1)).sum(axis=0) / area.sum()
    _, centre = support_and_centre(rest_form(folded))
    np.testing.assert_allclose(centre, expected, atol=1e-5 * folded.sheet.size)


def _colour_pixels(img: np.ndarray, hex_colour: str, tol: float = 0.06) -> int:
    rgb = np.array([int(hex_colour[i : i + 2], 16) for i in (1, 3, 5)]) / 255.0
    return int(np.sum(np.all(np.abs(img[:, :, :3] - rgb) < tol, axis=2)))


def test_preview_draws_apex_support_polygon_centre_and_legend(tmp_path, folded):
    import matplotlib.image as mpimg

    from onefold_cad.export import preview

    out = render_folded_preview(folded, tmp_path / "p.png", title="p", units="mm")
    img = mpimg.imread(out)
    assert _png_size(out.read_bytes()) == (900, 700)
    for colour in (preview._APEX, preview._COM, preview._CREASE):
        assert _colour_pixels(img, colour) > 20, colour
    # the support polygon is translucent green over the grey floor: greener than it is red
    green = (img[:, :, 1] - img[:, :, 0]) > 0.12
    assert green.sum() > 200
    # the legend (right of the view) shows both face colours as patches
    legend = img[: img.shape[0] // 4, int(img.shape[1] * 0.75) :]
    assert _colour_pixels(legend, "#dc9e4c", 0.04) > 30  # _TOP
    assert _colour_pixels(legend, "#8ca1b8", 0.04) > 30  # _BOTTOM


def test_caption_gives_fold_angles_height_and_footprint(folded):
    """The numbers written under the view, against the form measured here:
    the resting form's outline sampled finely and its apex."""
    from onefold_cad.export.preview import _caption

    text = _caption(folded, rest_form(folded), "mm")
    for half in folded.crease:
        assert f"{half.fold_angle_deg:.1f}\N{DEGREE SIGN} {half.bend}" in text
    pts, _ = folded.sheet.sample_boundary(folded.sheet.perimeter / 20000)
    form = rest_form(folded).apply(np.vstack([folded.map_points(pts), folded.apex]))
    ext = np.ptp(form, axis=0)
    height = f"height {ext[2]:.4g} mm"  # the form's extent, as `onefold solve` prints it
    footprint = f"footprint {ext[0]:.4g} x {ext[1]:.4g} mm"
    assert height in text and footprint in text
    margin = rest_form(folded).tipping_margin_deg
    assert margin > 5.0 and f"tipping margin of {margin:.1f}\N{DEGREE SIGN}" in text


def test_the_fold_frame_view_says_so_and_keeps_the_standing_numbers(folded, tmp_path):
    """frame=True (build --placement frame): drawn in the fold frame, a different
    picture; the caption says it is the fold frame and still gives how it stands."""
    from onefold_cad.export.preview import _caption

    standing = _caption(folded, rest_form(folded), "mm")
    text = _caption(folded, rest_form(folded), "mm", frame=True)
    assert "shown in the fold frame (apex above H)" in text
    assert "fold frame (apex" not in standing
    rest = rest_form(folded)
    for words in (
        f"height {rest.height:.4g} mm",
        f"tipping margin of {rest.tipping_margin_deg:.1f}",
    ):
        assert words in text and words in standing
    a = render_folded_preview(folded, tmp_path / "a.png", size_px=(300, 240))
    b = render_folded_preview(folded, tmp_path / "b.png", size_px=(300, 240), frame=True)
    assert _png_size(b.read_bytes()) == (300, 240)
    assert a.read_bytes() != b.read_bytes()


# -- the flat SVG: real units, true size, strokes that read -----------------------


def _flat_svg(tmp_path, units: str, size: tuple[float, float]):
    from onefold_cad import Units
    from onefold_cad.export.dxf import export_design_dxf
    from onefold_cad.export.dxf_preview import render_preview

    design = Design(
        "f", FrameCurve(40, 40), Sheet.rectangle(*size), units=Units(units), description=""
    )
    f = fold_design(design)
    dxf = export_design_dxf(design, tmp_path / "f.dxf", folded=f)
    return design, render_preview(dxf, tmp_path / "f-flat.svg")


def _svg_geometry(path):
    """Root width, height (with unit), viewBox, and per stroke class its width."""
    import re
    import xml.etree.ElementTree as ET

    root = ET.parse(path).getroot()
    box = [float(v) for v in root.get("viewBox").split()]
    css = "".join(el.text or "" for el in root.iter() if el.tag.endswith("style"))
    widths = {
        m.group(1): float(m.group(3))
        for m in re.finditer(r"\.(\w+) \{stroke: (#\w+); stroke-width: ([0-9.]+);", css)
    }
    colours = {
        m.group(1): m.group(2)
        for m in re.finditer(r"\.(\w+) \{stroke: (#\w+); stroke-width: ([0-9.]+);", css)
    }
    paths = [(el.get("class"), el.get("d")) for el in root.iter() if el.tag.endswith("path")]
    return root.get("width"), root.get("height"), box, widths, colours, paths


def _path_points(d: str) -> np.ndarray:
    """The points of an SVG path made of M/L/l commands (what ezdxf writes for
    polylines): absolute after a capital, relative to the last point otherwise."""
    import re

    out: list[np.ndarray] = []
    cur, cmd, nums = np.zeros(2), "M", []
    for tok in re.findall(r"[MLml]|-?[0-9.]+", d):
        if tok in "MLml":
            cmd = tok
            continue
        nums.append(float(tok))
        if len(nums) == 2:
            cur = np.array(nums) if cmd.isupper() else cur + nums
            out.append(cur)
            nums = []
    return np.array(out)


@pytest.mark.parametrize(
    ("units", "svg_unit", "per_unit"), [("mm", "mm", 1.0), ("in", "in", 1.0), ("ft", "in", 12.0)]
)
def test_flat_svg_is_in_the_designs_units_at_true_size(tmp_path, units, svg_unit, per_unit):
    """The sheet's outline (the CUT layer: the heaviest, black strokes) spans,
    at the SVG's stated size, the sheet's true width and height."""
    import re

    w_sheet, h_sheet = 60.0, 144.0
    design, svg = _flat_svg(tmp_path, units, (w_sheet, h_sheet))
    width, height, box, widths, colours, paths = _svg_geometry(svg)
    wm, hm = re.fullmatch(r"([0-9.]+)(\w+)", width), re.fullmatch(r"([0-9.]+)(\w+)", height)
    assert wm.group(2) == hm.group(2) == svg_unit
    scale = float(wm.group(1)) / box[2]  # svg units per viewBox unit
    assert float(hm.group(1)) / box[3] == pytest.approx(scale, rel=1e-3)
    cut = max(widths, key=widths.get)
    assert colours[cut] == "#000000"
    xy = np.vstack([_path_points(d) for cls, d in paths if cls == cut])
    ext = np.ptp(xy, axis=0) * scale / per_unit  # in the design's unit
    # the outline is the rectangle turned so its diagonal is the fold line:
    # drawn in the sheet's own frame, its sides on the axes
    np.testing.assert_allclose(sorted(ext), sorted([w_sheet, h_sheet]), rtol=2e-5)


@pytest.mark.parametrize("size", [(0.2, 0.3), (3000.0, 7000.0)])
def test_flat_svg_strokes_read_at_any_size(tmp_path, size):
    """Shown 1000 px on its longer side, every stroke is at least about one
    pixel wide and the cut outline about three, whatever the sheet's size."""
    _, svg = _flat_svg(tmp_path, "mm", size)
    _, _, box, widths, _, _ = _svg_geometry(svg)
    px = 1000.0 / max(box[2], box[3])
    strokes = np.array(list(widths.values())) * px
    assert strokes.min() >= 0.9 and strokes.max() >= 2.7


def _sides(png: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Pixels showing the top face's warm colour, and the bottom face's cool one."""
    import io

    from PIL import Image

    im = np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)
    r, b = im[..., 0], im[..., 2]
    return r > b + 40, b > r + 10


def test_the_underside_has_no_speckles_of_the_top_face(monkeypatch):
    """matplotlib paints by mean depth: the far side's top face must not show
    through the near underside (patkau-one-fold, where the sides overlap in
    the view). Against the same view on a 360 x 60 mesh, whose triangles are
    too small to sort wrong: at most 40 pixels of 900 x 700 differ (185 with
    the 6 points a ray drawn before)."""
    import onefold_cad.export.preview as preview
    from onefold_cad.templates import load_template
    from tests.shipped import REPO_TEMPLATES

    folded = fold_design(load_template(REPO_TEMPLATES / "patkau-one-fold.toml"))
    shown = _sides(thumbnail_png(folded, size_px=(900, 700)))
    monkeypatch.setattr(preview, "_ANGULAR", 360)
    monkeypatch.setattr(preview, "_RADIAL", 60)
    reference = _sides(thumbnail_png(folded, size_px=(900, 700)))
    assert reference[1].sum() > 50_000  # the underside is in view
    assert (shown[0] & reference[1]).sum() <= 40  # top colour where the underside is
