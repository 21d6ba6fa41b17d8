"""The plan: every value checked against the design before any design runs,
stable keys, the designs and columns of a sweep."""

from __future__ import annotations

import shutil

import pytest

from onefold_cad.flags.parser import UsageError
from onefold_cad.sweep.plan import make_plan


def test_a_grid_plan_has_its_designs_keys_and_columns():
    plan = make_plan(
        "table1-row1",
        ["alpha=30:50:3", "rectangle=400x300,500x300"],
        measures=["mass", "bends", "mass"],
    )
    assert len(plan.points) == len(set(plan.keys)) == 6
    assert plan.measures == ("rest", "mass", "bends")
    assert plan.points[0] == {"alpha": 30.0, "rectangle": "400x300"}
    assert [c.name for c in plan.input_columns] == [
        "alpha",
        "rectangle",
        "rectangle_width",
        "rectangle_height",
    ]
    assert {c.name for c in plan.output_columns} >= {"height", "tipping_margin_deg", "mass"}
    assert plan.images  # 6 designs: thumbnails by default


def test_keys_are_stable_and_follow_the_inputs(tmp_path):
    a = make_plan("table1-row1", ["alpha=30,40"])
    assert a.keys == make_plan("table1-row1", ["alpha=30.0,40"]).keys
    assert a.keys != make_plan("table1-row1", ["alpha=30,40"], fixed={"thickness": 1.0}).keys
    copy = tmp_path / "t.toml"
    shutil.copy(a.template, copy)
    assert make_plan(str(copy), ["alpha=30,40"]).keys == a.keys  # the data, not the path
    copy.write_text(copy.read_text().replace("radius = 100.0", "radius = 101.0"))
    assert not set(make_plan(str(copy), ["alpha=30,40"]).keys) & set(a.keys)


def test_repeated_points_are_one_design_where_first_made():
    plan = make_plan("table1-row1", ["divisions=10:12"], sampler="lhs", samples=20)
    assert len(plan.points) == len(plan.keys) == 3
    grid = make_plan("table1-row1", ["divisions=1:3:5", "alpha=30,40"])
    assert [(p["divisions"], p["alpha"]) for p in grid.points] == [
        (1, 30.0),
        (1, 40.0),
        (2, 30.0),
        (2, 40.0),
        (3, 30.0),
        (3, 40.0),
    ]


@pytest.mark.parametrize(
    ("template", "vary", "kw", "says"),
    [
        (
            None,
            ["alpha=0:90:10"],
            {},
            "--vary alpha=0:90:10: --alpha: must be in (0, 90) deg, got 0",
        ),
        (None, ["hc=-50,0,95"], {}, "--hc: H must lie strictly inside the f-line"),
        (
            None,
            ["apex-fraction=0.2:1.5"],
            {"sampler": "sobol", "samples": 8},
            "--apex-fraction: must be in [1e-09, 1 - 1e-09]",
        ),
        (None, ["rectangle=3x"], {}, "--rectangle: must be WIDTHxHEIGHT"),
        (None, [], {}, "--vary: at least one NAME=SPEC"),
        (None, ["alpha=30,40", "alpha=50"], {}, "alpha is varied twice"),
        (
            None,
            ["alpha=30,40"],
            {"fixed": {"alpha": 20.0}},
            "--alpha is also given as a fixed flag",
        ),
        (None, ["alpha=30:40"], {}, "a grid range needs a count (LO:HI:N) or --samples N"),
        (
            None,
            ["alpha=30:40:3"],
            {"sampler": "lhs", "samples": 4},
            "the count N is for --sampler grid",
        ),
        (None, ["alpha=30,40"], {"sampler": "lhs", "samples": 4}, "no --vary is LO:HI"),
        (None, ["alpha=30:40"], {"sampler": "sobol"}, "needs --samples N"),
        (None, ["alpha=30:40"], {"sampler": "grid", "samples": 0}, "--samples: must be in [1, "),
        (None, ["alpha=1:89:5000", "beta=1:89:5000"], {}, "25000000 designs; a sweep has at most"),
        (None, ["alpha=30,40"], {"measures": ["volume"]}, "--measure: 'volume' is not a measure"),
        (None, ["alpha=30,40"], {"objectives": "min:mass"}, "it needs --measure mass"),
        ("no-such-template", ["alpha=30,40"], {}, "no such file or shipped template"),
        (None, ["alpha=30,40"], {"fixed": {"thickness": -1.0}}, "--thickness"),
    ],
)
def test_a_bad_sweep_is_refused_before_any_design_runs(template, vary, kw, says):
    with pytest.raises(UsageError) as err:
        make_plan(template, vary, **kw)
    assert says in str(err.value) and "\n" not in str(err.value)
