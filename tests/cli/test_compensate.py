"""``onefold compensate`` as a user runs it, on a stand-in steel whose answer is
known (tests/compensate/fake_steel.py: no simulation runs, the tests stay
fast): the files of ``-o`` (the compensated template every command takes, the
build files with the springback columns, the standing form, the picture),
bad input refused in one line before any simulation, and an interrupted run
that leaves nothing behind."""

from __future__ import annotations

import csv
import json

import pytest
import trimesh

from onefold_cad.compensate import parallel
from onefold_cad.templates import find_template, load_template
from tests.compensate.fake_steel import LAWS, SPRING, fake_standing, fake_warning

NAME = "broken-vault"


def _never(*args: object, **kwargs: object) -> None:
    raise AssertionError("a simulation ran before the input was checked")


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--height", "-5", "--span", "100"], "--height: must be a finite length > 0, got -5"),
        (["--height", "500", "--span", "100"], "target: height 500, span 100 in is out of reach"),
        (["--span", "100"], "--height: a size target needs both --height and --span"),
        (["--target", "design", "--height", "50", "--span", "100"], "--target: design takes no"),
        (["--youngs-modulus", "nan"], "--youngs-modulus"),
        (["-j", "0"], "--jobs: must be >= 1, got 0"),
        (["--law", "plastic"], "--law"),
        (["--knobs", "alpha,cones", "--law", "moment"], "knobs: 'cones' forms the cones past"),
        (["--cone-forming", "compensated", "--law", "moment"], "cone_forming: 'compensated'"),
        (["--knobs", "alpha,cones,Alpha"], "--knobs: 'alpha' is named twice"),
    ],
)
def test_bad_input_exits_2_in_one_line_before_any_simulation(
    cli, monkeypatch, tmp_path, args, words
) -> None:
    monkeypatch.setattr(parallel, "simulate_standing", _never)
    rc, out, err = cli("compensate", NAME, "-o", str(tmp_path / "out"), *args)
    assert rc == 2
    assert err.count("\n") == 1 and err.startswith("onefold: error: ")
    assert words in err
    assert out == "" and not (tmp_path / "out").exists()


def test_with_o_a_design_build_would_refuse_is_refused_before_any_simulation(
    cli, monkeypatch, tmp_path
) -> None:
    """-o writes build's files: a design whose bends build refuses (patkau's
    blank too wide across one half with these flags, as `onefold build`
    says) exits 2 at once, not after the search."""
    monkeypatch.setattr(parallel, "simulate_standing", _never)
    flags = ("--alpha", "36.86", "--beta", "36.68", "--hc", "58.02")
    rc, _, built = cli("build", "patkau-one-fold", *flags, "-o", str(tmp_path / "b"))
    assert rc == 2 and "too wide across it" in built  # the premise
    rc, out, err = cli("compensate", "patkau-one-fold", *flags, "-o", str(tmp_path / "out"))
    assert rc == 2 and err == built and out == ""
    assert not (tmp_path / "out").exists()


def test_a_design_without_steel_data_is_refused_naming_the_value(cli, monkeypatch) -> None:
    monkeypatch.setattr(parallel, "simulate_standing", _never)
    rc, _, err = cli("compensate", "paper-square")
    assert rc == 2 and err.count("\n") == 1
    assert "youngs_modulus" in err and "--youngs-modulus" in err


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    from onefold_cad.cli.main import main

    mp = pytest.MonkeyPatch()
    mp.setattr(parallel, "simulate_standing", fake_standing)
    out = tmp_path_factory.mktemp("comp") / "out"
    try:
        import contextlib
        import io

        text = io.StringIO()
        with contextlib.redirect_stdout(text):
            rc = main(
                [
                    "compensate",
                    NAME,
                    "-j",
                    "1",
                    "-q",
                    "-o",
                    str(out),
                    "--json",
                    "--knobs",
                    "alpha,beta,h_c",
                ]
            )
    finally:
        mp.undo()
    assert rc == 0
    return out, json.loads(text.getvalue())


def test_o_writes_the_compensated_template_and_its_files(written) -> None:
    out, report = written
    stem = f"{NAME}-compensated"
    names = {p.name for p in out.iterdir()}
    own = {f"{stem}.toml", f"{stem}-standing.glb", f"{stem}-standing.step",
           f"{NAME}-compensation.png", f"{NAME}-compensation.json"}  # fmt: skip
    assert own <= names
    assert {f"{stem}.step", f"{stem}.dxf", f"{stem}-bends.csv"} <= names
    # the template is what every other command takes: the fold formed SPRING more
    design = load_template(out / f"{stem}.toml")
    base = load_template(find_template(NAME))
    assert design.frame.alpha == pytest.approx(base.frame.alpha + SPRING[0], abs=0.05)
    assert design.frame.beta == pytest.approx(base.frame.beta + SPRING[1], abs=0.05)
    assert json.loads((out / f"{NAME}-compensation.json").read_text()) == report
    c = report["compensation"]
    assert c["reached"] and c["simulations"] >= 3
    assert c["compensated"]["alpha"] == design.frame.alpha


def test_the_bend_sheet_gives_the_angle_to_fold_to_and_after_springback(written) -> None:
    # the stand-in steel stands as the template's own fold: after springback the
    # crease is at the template's angle, and it is formed to the compensated one's
    from onefold_cad.design import fold_design

    out, report = written
    rows = list(csv.DictReader((out / f"{NAME}-compensated-bends.csv").open()))
    rows = [{k.split(" [")[0]: v for k, v in r.items()} for r in rows]  # "fold_to_deg [0.01 deg]"
    assert len(rows) == 2
    comp = fold_design(load_template(out / f"{NAME}-compensated.toml")).crease
    base = fold_design(load_template(find_template(NAME))).crease
    fold_to = sorted(float(r["fold_to_deg"]) for r in rows)
    after = sorted(float(r["after_springback_deg"]) for r in rows)
    assert fold_to == pytest.approx(sorted(c.fold_angle_deg for c in comp), abs=0.005 + 1e-9)
    assert after == pytest.approx(sorted(c.fold_angle_deg for c in base), abs=0.5)
    assert min(fold_to) > max(after)  # formed past the angle it springs back to


def test_the_dxf_notes_give_the_angle_to_fold_to_and_after_springback(written) -> None:
    import ezdxf

    from onefold_cad.design import fold_design

    out, report = written
    doc = ezdxf.readfile(out / f"{NAME}-compensated.dxf")
    assert not doc.audit().has_errors
    notes = [e.dxf.text for e in doc.modelspace().query("TEXT") if e.dxf.layer == "NOTES"]
    comp = fold_design(load_template(out / f"{NAME}-compensated.toml")).crease
    for c, r in zip(comp, report["compensation"]["crease"], strict=True):
        line = next(n for n in notes if n.startswith(f"fold half {c.name} to "))
        assert f"to {c.fold_angle_deg:.2f} deg" in line
        assert f"stands at {r['after_springback_deg']:.2f} deg" in line


def test_the_standing_form_is_written_in_metres_on_the_target(written) -> None:
    # the stand-in steel of the compensated fold is the template's own form: the
    # GLB's vertices (metres, y up), brought back to inches and z up, lie on it
    import numpy as np

    from onefold_cad.design import fold_design, rest_once
    from onefold_cad.mechanics.deviation import surface_distance

    out, report = written
    scene = trimesh.load(out / f"{NAME}-compensated-standing.glb")
    v = next(iter(scene.geometry.values())).vertices / 0.0254
    pts = np.column_stack([v[:, 0], -v[:, 2], v[:, 1]])
    folded = fold_design(load_template(find_template(NAME)))
    rest = rest_once(folded)
    d = surface_distance(folded, (pts - rest.translation) @ rest.rotation)
    assert d.max() < 1e-3  # in
    assert np.ptp(pts[:, 2]) == pytest.approx(report["compensation"]["after"]["height"], rel=0.01)


def test_an_interrupted_run_leaves_nothing(cli, monkeypatch, tmp_path) -> None:
    from onefold_cad.export import standing_form

    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)

    def interrupted(*args: object, **kwargs: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(standing_form, "write_form_step", interrupted)
    out = tmp_path / "out"
    rc, _, _ = cli("compensate", NAME, "-j", "1", "-q", "-o", str(out))
    assert rc == 130
    assert not out.exists() or not any(out.iterdir())


def _descendants(pid: int) -> set[int]:
    """The processes below ``pid`` (Linux /proc)."""
    import os

    parent: dict[int, int] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as fh:
                    parent[int(entry)] = int(fh.read().rsplit(")", 1)[1].split()[1])
            except OSError:
                continue
    found, todo = set(), [pid]
    while todo:
        p = todo.pop()
        kids = {c for c, pp in parent.items() if pp == p}
        found |= kids
        todo += list(kids)
    return found


def _running(pid: int) -> bool:
    """``pid`` exists and is no zombie."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_a_killed_run_leaves_no_file_and_no_worker(tmp_path) -> None:
    import signal
    import subprocess
    import sys
    import time

    out = tmp_path / "out"
    proc = subprocess.Popen(
        [sys.executable, "-m", "onefold_cad", "compensate", NAME, "-j", "2", "-o", str(out)],
        stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        line = proc.stderr.readline()  # the first simulation is done: the pool works
        assert "simulations" in line, line
        workers = _descendants(proc.pid)
        assert workers
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert not out.exists() or [p.name for p in out.iterdir() if not p.name.startswith(".")] == []
    for _ in range(100):  # each worker sees its parent gone within half a second
        alive = [p for p in workers if _running(p)]
        if not alive:
            break
        time.sleep(0.1)
    assert alive == []


def test_the_text_report_says_before_after_the_fold_and_the_creases(cli, monkeypatch) -> None:
    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)
    rc, out, err = cli("compensate", NAME, "-j", "1")
    assert rc == 0, err
    lines = out.splitlines()
    assert lines[0].startswith(
        f"{NAME}  compensated for springback and weight (J2 through the thickness): target its own"
    )
    assert lines[1].startswith("  uncompensated    deviation max")
    assert lines[2].startswith("  compensated      deviation max")
    base = load_template(find_template(NAME)).frame
    assert f"(was {base.alpha:.5g})" in lines[3] and lines[3].lstrip().startswith("fold to")
    assert "crease overbend" in lines[3] and lines[3].endswith("deg (was 0)")
    assert sum(line.lstrip().startswith("crease ") for line in lines) == 2
    # one column for every label, the longest ("per deg overbend") included
    assert any(line.startswith("  per deg overbend ") for line in lines)
    assert all(line[18] == " " and line[19] != " " for line in lines[1:])
    assert "ETA" in err  # progress on stderr
    assert lines[-1].lstrip().startswith("simulations") and "met:" in lines[-1]


def test_law_j2_reaches_every_simulation_and_the_report(cli, monkeypatch) -> None:
    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)
    LAWS.clear()
    rc, out, err = cli("compensate", NAME, "--law", "j2", "-j", "1", "--json")
    assert rc == 0, err
    assert json.loads(out)["compensation"]["law"] == "j2"
    assert LAWS and set(LAWS) == {"j2"}
    rc, out, err = cli("compensate", NAME, "--law", "j2", "-j", "1")
    assert out.splitlines()[0].startswith(
        f"{NAME}  compensated for springback and weight (J2 through the thickness): target"
    )


@pytest.mark.parametrize("law", ["moment", "j2"])
def test_what_simulate_says_of_the_compensated_steel_is_said_again(cli, monkeypatch, law) -> None:
    """The compensated steel's simulation warnings (the moment law's: its
    springback is short) reach stderr and the report, once each."""
    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)
    rc, out, err = cli("compensate", NAME, "--law", law, "-j", "1", "--json")
    assert rc == 0, err
    said = f"onefold: warning: compensate: the compensated steel: {fake_warning(law)}"
    assert err.splitlines().count(said) == 1
    assert json.loads(out)["compensation"]["warnings"] == [fake_warning(law)]


def test_the_picture_names_the_law_it_was_compensated_by(cli, monkeypatch, tmp_path) -> None:
    from onefold_cad.export import compensation_picture

    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)
    titles: list[str] = []
    real = compensation_picture.render_compensation

    def seen(*args, **kwargs):
        titles.append(kwargs["title"])
        return real(*args, **kwargs)

    monkeypatch.setattr(compensation_picture, "render_compensation", seen)
    for law, words in (("j2", "(J2 through the thickness)"), ("moment", "(the moment law)")):
        rc, _, err = cli("compensate", NAME, "--law", law, "-j", "1", "-q", "-o",
                         str(tmp_path / law))  # fmt: skip
        assert rc == 0, err
        assert titles[-1] == f"{NAME}: springback and weight compensated {words}"
    assert len(titles) == 2


def test_the_pool_hands_the_law_to_its_workers(monkeypatch) -> None:
    from concurrent.futures import ThreadPoolExecutor
    from dataclasses import replace

    monkeypatch.setattr(
        parallel, "simulate_standing", lambda *a: replace(fake_standing(*a), cpu_s=1.5)
    )
    design = load_template(find_template(NAME))
    LAWS.clear()
    with parallel.Evaluator(2, law="j2") as ev:
        ev._pool.shutdown()
        ev._pool = ThreadPoolExecutor(2)  # the pool's own map, in this process
        out = ev.map([design, design], "coarse")
        assert ev.worker_cpu_s == 3.0  # two run elsewhere: counted
        ev.map([design], "coarse")  # one design runs in this process: not counted again
        assert ev.worker_cpu_s == 3.0
    assert len(out) == 2 and LAWS == ["j2", "j2", "j2"]


def test_an_overbend_answer_reaches_the_template_and_the_bend_sheet(cli, monkeypatch, tmp_path):
    from onefold_cad.design import fold_design
    from tests.compensate.fake_steel import OVERBEND

    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)
    out = tmp_path / "out"
    rc, _, err = cli("compensate", NAME, "--knobs", "overbend", "-j", "1", "-q", "-o", str(out))
    assert rc == 0, err
    stem = f"{NAME}-compensated"
    design = load_template(out / f"{stem}.toml")  # every other command takes it
    assert design.material.crease_overbend == pytest.approx(OVERBEND, abs=0.05)
    assert design.frame == load_template(find_template(NAME)).frame
    rows = [{k.split(" [")[0]: v for k, v in r.items()}
            for r in csv.DictReader((out / f"{stem}-bends.csv").open())]  # fmt: skip
    folds = {c.name: c.fold_angle_deg for c in fold_design(design).crease}
    for r in rows:
        assert float(r["fold_angle_deg"]) == pytest.approx(folds[r["half"]], abs=0.005 + 1e-9)
        want = folds[r["half"]] + design.material.crease_overbend
        assert float(r["fold_to_deg"]) == pytest.approx(want, abs=0.005 + 1e-9)


def test_the_cones_knob_forms_past_the_springback_and_writes_the_forming_sheet(
    cli, monkeypatch, tmp_path
) -> None:
    """With J2 (the default) and every knob, the compensated template's cones
    are formed past their springback; -o writes its forming sheet and the DXF
    says so. With the moment law, the cones stay as designed."""
    monkeypatch.setattr(parallel, "simulate_standing", fake_standing)
    out = tmp_path / "out"
    rc, text, err = cli("compensate", NAME, "-j", "1", "-q", "-o", str(out), "--json")
    assert rc == 0, err
    c = json.loads(text)["compensation"]
    assert c["cone_forming"] == {"start": "design", "compensated": "compensated"}
    assert "cones" in c["knobs"]
    stem = f"{NAME}-compensated"
    assert load_template(out / f"{stem}.toml").material.cones_compensated
    rows = list(csv.DictReader((out / f"{stem}-cones.csv").open()))
    assert rows and all(float(r["form_radius [0.001 in]"]) < float(r["cone_radius [0.001 in]"])
                        for r in rows)  # fmt: skip
    assert f"{stem}-cones.csv" in (out / f"{stem}.dxf").read_text(encoding="utf-8")
    rc, text, err = cli("compensate", NAME, "-j", "1", "-q", "--json", "--law", "moment")
    assert rc == 0, err
    c = json.loads(text)["compensation"]
    assert c["cone_forming"]["compensated"] == "design" and "cones" not in c["knobs"]


@pytest.mark.parametrize(
    ("knobs", "law", "cones"),
    [(None, "j2", True), (None, "moment", False), (("alpha",), "j2", False),
     (("cones",), "j2", True), (("alpha", "cones"), "j2", True)],
)  # fmt: skip
def test_the_cones_knob_is_on_by_default_with_j2_alone(knobs, law, cones) -> None:
    from onefold_cad.compensate.run import cones_knob

    assert cones_knob(knobs, law) is cones
