"""SITE-order.csv: one row per sheet read off its report, and the total."""

from __future__ import annotations

import csv
import io

import pytest

from onefold_cad.export.site_order import ORDER_COLUMNS, order_csv


def report(name: str, mass: float | None, unit: str = "kg") -> dict:
    return {
        "name": name,
        "description": f"{name}'s design",
        "units": "mm",
        "inputs": {"material": {"name": "steel, 10 gauge", "thickness": 3.57}},
        "sheet": {"size": [3048.0, 7315.2]},
        "flat_size": [3045.5, 7314.1],
        "flat_area": 2.0e7,
        "flat_pattern": {"cut_length": 20000.5},
        "mass": None if mass is None else {"value": mass, "unit": unit, "density": 8000.0},
        "crease": {
            "plus_x": {"fold_angle_deg": 82.8, "bend": "UP"},
            "minus_x": {"fold_angle_deg": 70.25, "bend": "DOWN"},
        },
    }


def rows(text: str) -> list[dict]:
    return list(csv.DictReader(io.StringIO(text)))


def test_a_row_per_sheet_from_its_report_and_the_total():
    got = rows(order_csv([("a", report("a", 600.5)), ("b", report("b", 10.25))]))
    assert list(got[0]) == list(ORDER_COLUMNS)
    a, b, total = got
    assert (a["sheet"], a["mass"], a["mass_unit"], a["thickness"]) == ("a", "600.5", "kg", "3.57")
    assert (a["stock_width"], a["stock_height"]) == ("3048", "7315.2")
    assert a["bends"] == "2" and a["bend_angles_deg"] == "82.800;70.250"
    assert a["bend_directions"] == "plus_x:UP;minus_x:DOWN"
    assert total["sheet"] == "TOTAL" and float(total["mass"]) == pytest.approx(610.75)
    # ordered in m^2: 2.0e7 mm^2 a sheet is 20 m^2 (1 m^2 = 1e6 mm^2)
    assert (a["blank_area"], a["area_unit"]) == ("20", "m^2")
    assert float(total["blank_area"]) == pytest.approx(40.0) and total["area_unit"] == "m^2"
    assert float(total["cut_length"]) == pytest.approx(40001.0) and total["bends"] == "4"


def test_a_flat_crease_half_is_no_bend():
    r = report("a", 1.0)
    r["crease"]["minus_x"]["fold_angle_deg"] = 0.0
    (a, total) = rows(order_csv([("a", r)]))
    assert a["bends"] == "1" and a["bend_angles_deg"] == "82.800"


def test_no_total_mass_without_every_mass_or_across_units():
    (_, _, total) = rows(order_csv([("a", report("a", 1.0)), ("b", report("b", None))]))
    assert total["mass"] == ""
    (_, _, total) = rows(order_csv([("a", report("a", 1.0)), ("b", report("b", 1.0, "lb"))]))
    assert total["mass"] == "" and total["mass_unit"] == ""


def outdoors(pull: float, shear: float, ballast: float, feet: int = 3) -> dict:
    return {
        "governing": "EQU 0.9G + 1.5W-0",
        "totals": {"feet": feet, "anchored_feet": 2, "tension_N": pull, "shear_N": shear,
                   "ballast_kg": ballast},
    }  # fmt: skip


def test_the_anchors_of_each_sheet_and_their_total():
    """With the site's loads, each sheet's feet, anchors, pull, shear and
    ballast from its report's outdoors section, and their sums in the total."""
    a, b = report("a", 1.0), report("b", 1.0)
    a["outdoors"], b["outdoors"] = outdoors(4500.5, 20000.0, 1200.0), outdoors(100.0, 5.0, 3.0, 4)
    ra, rb, total = rows(order_csv([("a", a), ("b", b)]))
    assert (ra["feet"], ra["anchors"], ra["anchor_pull_N"]) == ("3", "2", "4500.5")
    assert ra["governing_case"] == "EQU 0.9G + 1.5W-0"
    assert total["feet"] == "7" and total["anchors"] == "4"
    assert float(total["anchor_pull_N"]) == pytest.approx(4600.5)
    assert float(total["anchor_shear_N"]) == pytest.approx(20005.0)
    assert float(total["ballast_kg"]) == pytest.approx(1203.0)


def test_no_anchor_columns_without_loads():
    (a, total) = rows(order_csv([("a", report("a", 1.0))]))
    assert a["feet"] == "" and total["anchor_pull_N"] == ""


def test_an_inch_site_orders_its_blanks_in_square_feet():
    r = report("a", 1.0, "lb")
    r["units"] = "in"
    r["flat_area"] = 288.0  # in^2: 2 ft^2 (144 in^2 a square foot)
    (a, total) = rows(order_csv([("a", r)]))
    assert (a["blank_area"], a["area_unit"]) == ("2", "ft^2")
    assert (total["blank_area"], total["area_unit"]) == ("2", "ft^2")
