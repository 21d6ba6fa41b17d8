"""The forming stage with J2 sections on a real design, against the cones'
closed form: the surfaces yield where the cone's curvature k / r passes the
plane-strain first yield, inside r = |k| E' t sqrt(1 - nu + nu^2) / (2 sigma_y)
(the formed plastic share, mesh-converged within 2 %); no stress above the
flow stress."""

from __future__ import annotations

import math

import numpy as np
import pytest

from onefold_cad.design import fold_design
from onefold_cad.mechanics.j2 import stages as j2_stages
from onefold_cad.mechanics.model import sheet_model
from onefold_cad.templates import load_template
from tests.mechanics.test_simulate import _cone_integrals


@pytest.fixture(scope="module")
def formed():
    design = load_template("patkau-one-fold")
    folded = fold_design(design)
    model = sheet_model(design, folded, h_max=0.3)
    shell = j2_stages.j2_shell(model)
    return design, folded, shell, j2_stages.form(model, shell)


def test_the_formed_plastic_share_is_the_area_inside_the_plane_strain_yield_radius(formed):
    design, folded, shell, stage = formed
    m = design.material
    nu = m.poisson
    e_plane = m.youngs_modulus * 1e9 / (1 - nu**2)
    r_per_k = e_plane * m.thickness * 1e-3 * math.sqrt(1 - nu + nu**2) / (2 * m.yield_stress * 1e6)
    _, area_mm2, _ = _cone_integrals(design, folded, k_scale=r_per_k * 1e3)
    yielded = shell.ref_area[stage.surface_plastic_strain() > 0].sum()  # m^2
    assert yielded / (area_mm2 * 1e-6) == pytest.approx(1.0, abs=0.02)


def test_no_stress_above_the_flow_stress(formed):
    """patkau's 304 hardens linearly and isotropically (H from its template): the
    surfaces' von Mises stress is at most sigma_y + H alpha, equal to it where
    they flowed, below sigma_y where they did not."""
    design, _, _, stage = formed
    m = design.material
    sy, h = m.yield_stress * 1e6, m.hardening_modulus * 1e6
    assert h > 0 and not m.kinematic_hardening
    alpha = stage.plasticity.state.equivalent[:, [0, -1]]
    stress = np.maximum(
        *(np.sqrt(np.maximum(s[:, 0] ** 2 - s[:, 0] * s[:, 1] + s[:, 1] ** 2 + 3 * s[:, 2] ** 2, 0))
          for s in (stage.response.stress[:, 0], stage.response.stress[:, -1]))
    )  # fmt: skip
    flow = sy + h * alpha.max(axis=1)
    assert np.all(stage.surface_stress() <= flow * (1 + 1e-9))
    assert np.all(stress <= flow * (1 + 1e-9))
    flowed = stage.response.plastic[:, [0, -1]].any(axis=1)
    assert np.all(flowed | (stage.surface_stress() < sy))


class _Stop(Exception):
    """Ends the standing path at its first call."""


def _path_options(monkeypatch, run) -> dict[str, object]:
    """The options ``run()`` gives its stage's ``solve_path`` (stopped there)."""
    seen: dict[str, object] = {}

    def first_call(shell_at, q0, **options):
        seen.update(options)
        raise _Stop

    monkeypatch.setattr(j2_stages, "solve_path", first_call)
    with pytest.raises(_Stop):
        run()
    return seen


def test_the_stand_starts_its_weight_ramp_at_a_quarter(formed, monkeypatch):
    """The J2 stand carries a quarter of the weight first (a whole first step
    spends the path's iteration budget and is halved twice on patkau)."""
    from onefold_cad.mechanics.stages import place

    design, folded, shell, stage = formed
    model = sheet_model(design, folded, h_max=0.3)
    seen = _path_options(
        monkeypatch,
        lambda: j2_stages.stand(model, shell, place(model, stage.q), stage.plasticity, "anchored"),
    )
    assert seen["first_step"] == pytest.approx(0.25)


def test_the_release_gives_its_eighth_steps_the_iterations_they_take(formed, monkeypatch):
    """The release's ramp starts at steps of 1/8 with a budget of 16 Newton
    iterations: on patkau's normal mesh those steps take 10 to 15, and a
    budget of 12 halved one and sent the rest of the ramp at 1/16 (126
    iterations in all against 100)."""
    design, folded, shell, stage = formed
    model = sheet_model(design, folded, h_max=0.3)
    seen = _path_options(monkeypatch, lambda: j2_stages.release(model, shell, stage))
    assert seen["first_step"] == pytest.approx(0.125)
    assert seen["step_iter"] >= 15


def test_the_stand_s_steps_are_predicted_as_the_release_s(formed, monkeypatch):
    """The stand's load steps start from the polynomial through the last
    equilibria and grow as the release's do (``RELEASE_PREDICTOR``,
    ``RELEASE_GROW``): on patkau (coarse) its steps of 1/4 then take 4 to 6
    Newton iterations."""
    from onefold_cad.mechanics.stages import place

    design, folded, shell, stage = formed
    model = sheet_model(design, folded, h_max=0.3)
    monkeypatch.setattr(j2_stages, "RELEASE_PREDICTOR", 2)
    monkeypatch.setattr(j2_stages, "RELEASE_GROW", 5)
    seen = _path_options(
        monkeypatch,
        lambda: j2_stages.stand(model, shell, place(model, stage.q), stage.plasticity, "anchored"),
    )
    assert (seen["predict"], seen["grow_iter"]) == (2, 5)
