"""benchmarks/forming_path.py: ``simulate``'s proportional forming against the
path of One-Fold forms (beta scaled by s) that a fold is closed along, with
the same J2 sections. The fold path's curvature at each point turns by at
most a few percent of its size and grows monotonically, so the two formed
states agree: the same faces yield, the largest plastic strain within 1e-4.
A path that turned the curvature would not pass."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))

import forming_path as fp  # noqa: E402

from onefold_cad.design import fold_design  # noqa: E402
from onefold_cad.mechanics.j2 import stages as j2_stages  # noqa: E402
from onefold_cad.mechanics.model import sheet_model  # noqa: E402
from onefold_cad.templates import load_template  # noqa: E402


@pytest.fixture(scope="module")
def patkau():
    design = load_template("patkau-one-fold")
    model = sheet_model(design, fold_design(design), level="coarse")
    return design, model, j2_stages.j2_shell(model)


def test_the_fold_path_ends_on_the_designed_curvature_growing_without_turning(patkau):
    design, model, shell = patkau
    designed = np.einsum("mij,mj->mi", shell.cartesian, model.shell.rest_curvature)
    end = fp._curvature_at(model, shell, design, 1.0)
    assert np.abs(end - designed).max() <= 1e-9 * np.abs(designed).max()
    size = np.linalg.norm(end, axis=1)
    last = np.zeros_like(size)
    for s in (0.25, 0.5, 0.75):
        k = fp._curvature_at(model, shell, design, s)
        norm = np.linalg.norm(k, axis=1)
        turned = np.linalg.norm(k / norm[:, None] - end / size[:, None], axis=1)
        assert turned.max() < 0.03  # nearly radial: the rulings stay on the material
        assert np.all(norm > last) and np.all(norm < size)  # monotonic, short of the end
        last = norm


def test_the_fold_path_forms_what_the_proportional_forming_does(patkau):
    out = fp.run("patkau-one-fold", "coarse", [8])
    p, f = out["proportional"], out["fold_path"][0]
    assert f["plastic_area_share"] == pytest.approx(p["plastic_area_share"], rel=1e-9)
    assert f["max_plastic_strain"] == pytest.approx(p["max_plastic_strain"], rel=1e-4)
    shares = [v for _, v in f["share_by_s"]]
    assert shares == sorted(shares) and shares[0] < 0.2 * shares[-1]  # yields as it folds
