"""``onefold simulate`` as a user runs it: the files of ``-o``, the text and the
JSON agreeing, bad input (exit 2, one line naming the parameter, no file), a
Newton that cannot converge reported with its residual and no file."""

from __future__ import annotations

import json
import struct

import numpy as np
import pytest
import trimesh

from onefold_cad.cli.main import main
from onefold_cad.mechanics import equilibrium
from tests.cli.test_main import refused, run

NAME = "patkau-one-fold"


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("sim") / "out"
    proc = run("simulate", NAME, "--mesh", "coarse", "-o", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    return out, proc


def test_o_writes_the_report_the_forms_and_the_pictures(written):
    out, proc = written
    names = {f"{NAME}{s}" for s in (".json", "-deviation.png", "-stress.png", ".inp", ".vtu")}
    names |= {f"{NAME}-standing.glb", f"{NAME}-released.glb"}
    assert {p.name for p in out.iterdir()} == names
    report = json.loads((out / f"{NAME}.json").read_text())
    assert report == json.loads(proc.stdout), "the file is what --json prints"
    sim = report["simulation"]
    for png in ("-deviation.png", "-stress.png"):
        head = (out / f"{NAME}{png}").read_bytes()[:24]
        assert head[:8] == b"\x89PNG\r\n\x1a\n"
        assert struct.unpack(">II", head[16:24]) == (900, 700)
    for form in ("standing", "released"):
        scene = trimesh.load(out / f"{NAME}-{form}.glb")
        (mesh,) = scene.geometry.values()
        assert len(mesh.faces) == sim["mesh"]["triangles"]
        assert len(mesh.vertices) == sim["mesh"]["nodes"]
        # glTF is metres, y up, on the ground: the height is the report's (mm)
        ys = np.asarray(mesh.vertices)[:, 1]
        assert ys.min() == pytest.approx(0.0, abs=1e-6)
        assert 1000 * ys.max() == pytest.approx(sim[form]["height"], rel=1e-6)


def test_progress_is_one_line_per_stage_and_the_stages_go_to_the_report(written):
    _, proc = written
    progress = [ln for ln in proc.stderr.splitlines() if ln.startswith(f"onefold: simulate {NAME}")]
    stages = [ln.split(": ")[2].split(" done (")[0] for ln in progress]
    assert stages == ["mesh", "formed", "released", "standing"], proc.stderr
    assert all(ln.endswith(" s CPU)") for ln in progress)
    assert "Newton step" not in proc.stderr  # only with -v
    sim = json.loads(proc.stdout)["simulation"]
    assert set(sim) >= {"weight_N", "mesh", "formed", "released", "standing"}
    assert sim["standing"]["reactions_total_N"] == pytest.approx(sim["weight_N"], rel=1e-6)


BAD = [
    (["--youngs-modulus", "-193"], "youngs-modulus", "in [1e-06, 10000] GPa"),
    (["--poisson", "0.5"], "poisson", "< 0.5"),
    (["--poisson", "-1.2"], "poisson", "> -1"),
    (["--thickness", "0"], "thickness", "thickness > 0"),
    (["--yield-stress", "0"], "yield-stress", "in [0.001, "),
    (["--hardening-modulus", "-5"], "hardening-modulus", ">= 0 and below Young's modulus"),
    (["--hardening-modulus", "200000"], "hardening-modulus", "below Young's modulus"),
    (["--kinematic-hardening", "2"], "kinematic-hardening", "[0, 1]"),
    (["--law", "tresca"], "law", "j2, moment"),
    (["--supports", "floor"], "supports", "anchored, frictionless"),
    (["--reference", "built"], "reference", "flat, designed"),
    (["--mesh", "huge"], "mesh", "coarse, normal, fine"),
    (["--check-mesh", "coarsest"], "check-mesh", "finer, coarser"),
    # the coarse mesh has no coarser level to check against
    (["--check-mesh", "coarser"], "check_mesh", "'coarser' checks a normal or fine mesh"),
    (["--cone-forming", "tight"], "cone-forming", "design, compensated"),
    # only the J2 section's springback is inverted
    (["--cone-forming", "compensated", "--law", "moment"], "cone_forming", "use --law j2"),
]
TEMPLATES = [
    ("star-polygon", "thickness", "thickness > 0"),  # a paper design: no solid to bend
    ("paper-square", "youngs_modulus", "--youngs-modulus"),
    ("table1-row1", "model", "--model exact"),
]
CASES = [([NAME, *a], p, w) for a, p, w in BAD] + [([t], p, w) for t, p, w in TEMPLATES]


@pytest.mark.parametrize(("args", "param", "words"), CASES, ids=[" ".join(c[0]) for c in CASES])
def test_bad_input_exits_2_with_one_line_and_no_file(tmp_path, args, param, words):
    # the case's flags come last: its own --mesh wins over the coarse default
    out = str(tmp_path / "out")
    proc = run("simulate", args[0], "--mesh", "coarse", "-o", out, *args[1:], cwd=tmp_path)
    refused(proc, param, words, tmp_path)


def test_a_newton_that_cannot_converge_is_an_error_with_its_residual(tmp_path, monkeypatch, capfd):
    real = equilibrium.minimize
    monkeypatch.setattr(equilibrium, "minimize", lambda *a, **k: real(*a, **{**k, "max_iter": 1}))
    rc = main(["simulate", NAME, "--mesh", "coarse", "-q", "-o", str(tmp_path / "out")])
    out, err = capfd.readouterr()
    assert rc == 2 and out == ""
    lines = [ln for ln in err.splitlines() if not ln.startswith("onefold: warning: ")]
    assert len(lines) == 1 and "residual" in lines[0], err
    assert list(tmp_path.iterdir()) == []


def test_verbose_adds_newton_s_iterations_and_the_check_is_named():
    proc = run("simulate", NAME, "--mesh", "coarse", "--check", "-v", "--json")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stderr.splitlines()
    assert any("released: Newton step 0, residual" in ln for ln in lines)
    assert any(": convergence check: standing done (" in ln for ln in lines), proc.stderr


def test_crease_overbend_reaches_the_model_and_is_echoed(cli) -> None:
    rc, out, err = cli("simulate", NAME, "--mesh", "coarse", "--crease-overbend", "6", "-q")
    assert rc == 0, err
    assert out.splitlines()[0].endswith("crease held, set 6 deg past its fold)")
    rc, out, err = cli("simulate", NAME, "--mesh", "coarse", "--crease-overbend", "6", "-q",
                       "--json")  # fmt: skip
    report = json.loads(out)
    assert report["simulation"]["crease_overbend_deg"] == 6.0
    assert report["inputs"]["material"]["crease_overbend"] == 6.0
    # the crease set further closes the released fold: less springback than as designed
    rc, plain, _ = cli("simulate", NAME, "--mesh", "coarse", "-q", "--json")
    assert (report["simulation"]["released"]["max_deviation"]
            < json.loads(plain)["simulation"]["released"]["max_deviation"])  # fmt: skip


def test_an_overbend_out_of_range_exits_2_in_one_line(cli) -> None:
    rc, out, err = cli("simulate", NAME, "--mesh", "coarse", "--crease-overbend", "60")
    assert rc == 2 and out == ""
    assert err == "onefold: error: --crease-overbend: must be in [-45, 45] deg, got 60\n"


def test_cones_formed_past_their_springback_are_echoed_and_reported(cli) -> None:
    rc, out, err = cli("simulate", NAME, "--mesh", "coarse", "--cone-forming", "compensated",
                       "-q", "--json")  # fmt: skip
    assert rc == 0, err
    report = json.loads(out)
    assert report["simulation"]["cone_forming"] == "compensated"
    assert report["inputs"]["material"]["cone_forming"] == "compensated"
    rc, out, err = cli("simulate", NAME, "--mesh", "coarse", "--cone-forming", "compensated", "-q")
    assert "crease held, cones formed past their springback)" in out.splitlines()[0]
