"""``onefold loads`` as a user runs it: the files of ``-o``, the text and the
JSON agreeing, bad input (exit 2, one line naming it, no file)."""

from __future__ import annotations

import csv
import io
import json

import pytest

from tests.cli.test_main import refused, run

NAME = "patkau-one-fold"
FAST = ["--mesh", "coarse", "--directions", "2", "--person-grid", "2", "--strength-cases", "1"]


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    out = tmp_path_factory.mktemp("loads") / "out"
    proc = run("loads", NAME, "--wind-speed", "25", "--snow", "1", *FAST, "-o", str(out), "--json")
    assert proc.returncode == 0, proc.stderr
    return out, proc


def test_o_writes_the_report_the_cases_and_the_picture(written):
    out, proc = written
    assert {p.name for p in out.iterdir()} == {
        f"{NAME}-loads{s}" for s in (".json", ".csv", ".png")
    }
    report = json.loads((out / f"{NAME}-loads.json").read_text())
    assert report == json.loads(proc.stdout), "the file is what --json prints"
    data = report["outdoors"]
    rows = list(csv.DictReader(io.StringIO((out / f"{NAME}-loads.csv").read_text())))
    assert [r["case"] for r in rows] == [c["name"] for c in data["cases"]]
    k = len(data["feet"])
    for row, case in zip(rows, data["cases"], strict=True):
        assert float(row[f"foot{k}_z_N"]) == pytest.approx(case["reactions_N"][k - 1][2])
    assert (out / f"{NAME}-loads.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert data["governing"] in [c["name"] for c in data["cases"]]
    # the STR verdict is the J2 load path's: its ratio in the JSON and the CSV
    (row,) = [r for r in rows if r["case"] == "STR 1.35G"]
    (case,) = [c for c in data["cases"] if c["name"] == "STR 1.35G"]
    assert float(row["load_ratio"]) == pytest.approx(case["strength"]["load_ratio"])
    assert case["stands"] is (case["strength"]["load_ratio"] >= 1.1)
    assert data["strength"]["cases_checked"] == ["STR 1.35G"]


def test_text_names_every_foot_and_case(tmp_path):
    proc = run("loads", NAME, "--wind-speed", "25", *FAST, "-q")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].startswith(f"{NAME}  outdoors on anchored feet")
    assert any(ln.strip().startswith("total:") for ln in lines)
    assert any("EQU 0.9G + 1.5W-0" in ln for ln in lines)
    (j2,) = [ln for ln in lines if ln.strip().startswith("STR 1.35G: r_R")]
    assert "peak elastic stress" in j2 and "(information)" in j2
    assert "not checked by a J2 load path" in proc.stderr


BAD = [
    (["--wind-speed", "-3"], "wind_speed", "0 to 100 m/s"),
    ([], "wind_speed", "--wind-speed"),
    (["--wind-speed", "25", "--terrain", "V"], "terrain", "0, I, II, III, IV"),
    (["--wind-speed", "25", "--person-at", "9000,0"], "person_at", "must lie on the flat sheet"),
    (["--wind-speed", "25", "--snow", "-1"], "snow_kPa", "--snow"),
    (["--wind-speed", "25", "--supports", "glue"], "--supports", "anchored, friction, ballast"),
    (["--wind-speed", "25", "--friction", "0"], "friction", "0.01 to 2"),
    (["--wind-speed", "x"], "--wind-speed", "not a number"),
    (["--wind-speed", "25", "--strength-cases", "-1"], "--strength-cases", "[0, 100] or 'all'"),
    (["--wind-speed", "25", "--strength-cases", "some"], "--strength-cases", "[0, 100] or 'all'"),
]


@pytest.mark.parametrize(("args", "param", "words"), BAD, ids=[" ".join(b[0]) for b in BAD])
def test_bad_input_exits_2_with_one_line_and_no_file(tmp_path, args, param, words):
    out = str(tmp_path / "out")
    proc = run("loads", NAME, "--mesh", "coarse", "-o", out, *args, cwd=tmp_path)
    refused(proc, param, words, tmp_path)
