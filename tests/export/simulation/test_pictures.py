"""NAME-deviation.png and NAME-stress.png of a coarse simulation (one per module)."""

from __future__ import annotations

import struct
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest

from onefold_cad.design import fold_design
from onefold_cad.errors import ExportError
from onefold_cad.export.simulation.colour_scale import DEVIATION_STOPS
from onefold_cad.export.simulation.pictures import render_deviation, render_stress
from onefold_cad.export.simulation.stress_scale import ABOVE_CAP, PERCENTILE, stress_scale
from onefold_cad.mechanics.simulate import simulate
from onefold_cad.templates import load_template
from tests.export.simulation.simulations import stalled_copy


@pytest.fixture(scope="module")
def sim():
    design = load_template("patkau-one-fold")
    return simulate(design, fold_design(design), level="coarse", convergence=False)


def _png(path):
    import matplotlib.image as mpimg

    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24]), mpimg.imread(path)[:, :, :3]


def _near(img: np.ndarray, hex_colour: str, tol: float = 0.05) -> int:
    rgb = np.array([int(hex_colour[i : i + 2], 16) for i in (1, 3, 5)]) / 255.0
    return int(np.sum(np.all(np.abs(img - rgb) < tol, axis=2)))


def test_the_deviation_picture_colours_the_form_and_names_the_unit(sim, tmp_path):
    from onefold_cad.export.simulation.pictures import _deviation_caption

    out = render_deviation(sim, tmp_path / "p-deviation.png", title="p")
    size, img = _png(out)
    assert size == (900, 700)
    assert [p.name for p in tmp_path.iterdir()] == ["p-deviation.png"]  # no temporary left
    # the colour bar runs from the scale's first colour to its last
    bar = img[:, int(0.85 * 900) :]
    assert _near(bar, DEVIATION_STOPS[0]) > 50 and _near(bar, DEVIATION_STOPS[-1]) > 50
    # the form shows many colours of the scale, not one
    form = img[60:600, : int(0.78 * 900)]
    assert sum(_near(form, c, 0.08) > 30 for c in DEVIATION_STOPS) >= 4
    s = sim.standing
    text = _deviation_caption(sim)
    for words in (
        f"deviation max {s.max_deviation:.4g} mm, rms {s.rms_deviation:.4g} mm",
        f"height {s.height:.4g} mm, span {s.span:.4g} mm",
        "it stands" if s.stands else "does NOT stand",
        f"springback alone: max deviation {sim.released.max_deviation:.4g} mm",
    ):
        assert words in text


def test_the_stress_picture_marks_yield_the_cap_and_the_largest_stress(sim, tmp_path):
    from onefold_cad.export.simulation.pictures import _flat_areas, _stress_caption

    out = render_stress(sim, tmp_path / "p-stress.png", title="p", size_px=(800, 600))
    size, img = _png(out)
    assert size == (800, 600)
    stress = sim.face_stress_MPa
    scale = stress_scale(stress, _flat_areas(sim), sim.yield_stress_MPa)
    # the formed sheet yields over part of its area and a few faces by H far more
    assert scale.kind == "yield" and scale.over and scale.top < stress.max()
    assert _near(img, ABOVE_CAP, 0.08) > 10  # the over-cap colour: its bar triangle at least
    text = _stress_caption(sim, scale)
    assert f"largest {sim.standing.max_stress_MPa:.4g} MPa" in text
    assert f"yield stress {sim.yield_stress_MPa:.4g} MPa" in text
    assert f"{PERCENTILE:.0f}th percentile by area" in text
    assert _near(img, "#111111", 0.06) > 5  # the largest stress's mark


def test_the_stress_scale_keeps_the_bulk_readable():
    areas = np.ones(1000)
    calm = np.linspace(0.0, 100.0, 1000)
    assert stress_scale(calm, areas, 215.0).kind == "below"
    spiky = np.concatenate([calm[:-3], [500.0, 900.0, 5000.0]])
    capped = stress_scale(spiky, areas, 215.0)
    assert capped.kind == "capped" and capped.top == 215.0 and capped.over
    low = stress_scale(np.concatenate([np.full(990, 5.0), np.full(10, 100.0)]), areas, 215.0)
    assert low.kind == "below" and low.gamma == 0.5  # the low stresses spread by a root scale
    hot = np.concatenate([np.linspace(0.0, 400.0, 995), np.full(5, 5000.0)])
    yielded = stress_scale(hot, areas, 215.0)
    assert yielded.kind == "yield" and 215.0 < yielded.top < 400.0 and yielded.over
    # by area: the same stresses on small faces do not set the cap
    weights = np.where(hot > 300.0, 1e-6, 1.0)
    assert stress_scale(hot, weights, 215.0).top <= 300.0


def test_without_a_standing_equilibrium_both_pictures_draw_the_released_form(sim, tmp_path):
    from onefold_cad.export.simulation.pictures import _deviation_caption

    none = stalled_copy(sim)
    for render, name in ((render_deviation, "d.png"), (render_stress, "s.png")):
        size, img = _png(render(none, tmp_path / name))
        assert size == (900, 700)
        assert _near(img, "#b91c1c", 0.08) > 100  # the notice, in its red
        assert _near(img, DEVIATION_STOPS[-1], 0.03) == 0  # no colour scale
    assert "does NOT stand" in _deviation_caption(none)
    # reference 'designed' has no released form either: the designed form is drawn
    bare = replace(none, released_positions=None, released=None, formed=None)
    assert _png(render_deviation(bare, tmp_path / "bare.png"))[0] == (900, 700)


def test_a_failed_write_raises_export_error_and_leaves_nothing(sim, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ExportError):
        render_deviation(sim, blocker / "p.png")
    assert [p.name for p in tmp_path.iterdir()] == ["file"]


def test_importing_the_pictures_imports_no_matplotlib():
    code = "import sys, onefold_cad.export.simulation.pictures; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_a_hardened_j2_stress_above_yield_is_called_the_flow_stress(sim):
    """Under the J2 law with hardening the surfaces reach the flow stress,
    yield + H x plastic strain: the caption says so rather than leave a
    stress above the yield stress unexplained; without hardening or under
    the moment law it says nothing of it."""
    from dataclasses import replace

    from onefold_cad.export.simulation.pictures import _flat_areas, _stress_caption

    scale = stress_scale(sim.face_stress_MPa, _flat_areas(sim), sim.yield_stress_MPa)
    above = replace(sim, standing=replace(sim.standing, utilisation=1.7))
    j2 = replace(above, law="j2", hardening_modulus_MPa=507.0)
    assert "at most the flow stress, yield + 507 MPa x plastic strain" in _stress_caption(j2, scale)
    for other in (above, replace(j2, hardening_modulus_MPa=0.0)):
        assert "flow stress" not in _stress_caption(other, scale)


def test_the_moment_law_s_stress_past_yield_is_called_an_estimate(sim):
    """The moment law takes the membrane and the unloading elastic, so its
    stress past yield (patkau's coarse run: some 25 times it by H) is one
    no steel can be in: the picture's caption says so and names the law
    that gives the stress the steel can be in; below yield, or under J2,
    it says nothing of it."""
    from dataclasses import replace

    from onefold_cad.export.simulation.pictures import _flat_areas, _stress_caption

    assert sim.law == "moment" and sim.standing.utilisation > 1.0
    scale = stress_scale(sim.face_stress_MPa, _flat_areas(sim), sim.yield_stress_MPa)
    said = "past yield the moment law's elastic estimate, a stress the steel cannot be in"
    assert said in _stress_caption(sim, scale)
    below = replace(sim, standing=replace(sim.standing, utilisation=0.9))
    for other in (below, replace(sim, law="j2")):
        assert "estimate" not in _stress_caption(other, scale)


def test_a_coarse_preview_s_uncertain_standing_is_not_captioned_as_standing(sim):
    """The caption says what the report's verdict says: a coarse 'stands'
    that its reserve check leaves uncertain is no 'it stands'."""
    from onefold_cad.export.simulation.pictures import _deviation_caption
    from onefold_cad.mechanics.verdicts import with_reserve

    assert sim.standing.stands
    doubt = replace(sim, standing=with_reserve(replace(sim.standing, uncertain=""), 1.0))
    assert doubt.standing.verdict == "uncertain"
    text = _deviation_caption(doubt)
    assert "whether it stands is uncertain: run --mesh normal" in text
    assert "it stands (" not in text and "; it stands" not in text
    sure = replace(sim, standing=with_reserve(replace(sim.standing, uncertain=""), 3.0))
    assert "; it stands" in _deviation_caption(sure)
