"""The site's overlap check from the cheap geometry (before any sheet is built)."""

from __future__ import annotations

import numpy as np
import pytest

from onefold_cad import InvalidParameterError
from onefold_cad.flags.site_jobs import site_jobs
from onefold_cad.site.overlap import check_plan, crossing
from onefold_cad.site.placement import SitePlacement
from onefold_cad.site.spec import read_site
from onefold_cad.templates import load_template
from tests.shipped import REPO_TEMPLATES

SQUARE = np.array([[0, 1, 2], [0, 2, 3]])


def _square(corners) -> tuple[np.ndarray, np.ndarray]:
    return np.asarray(corners, dtype=float), SQUARE


FLAT = _square([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]])


def test_a_square_through_another_crosses_it_where_their_planes_meet():
    upright = _square([[0, -0.5, -1], [0, 0.5, -1], [0, 0.5, 1], [0, -0.5, 1]])
    p = crossing(upright, FLAT, 0.01)
    assert p is not None
    assert abs(p[0]) < 1e-12 and abs(p[2]) < 1e-12 and abs(p[1]) <= 0.5  # on x = 0, z = 0


@pytest.mark.parametrize(
    "other",
    [
        [[0, -0.5, 0.2], [0, 0.5, 0.2], [0, 0.5, 1], [0, -0.5, 1]],  # above: apart
        [[0, -0.5, -0.005], [0, 0.5, -0.005], [0, 0.5, 1], [0, -0.5, 1]],  # within the gap
        [[3, -0.5, -1], [3, 0.5, -1], [3, 0.5, 1], [3, -0.5, 1]],  # beside it
    ],
)
def test_no_crossing_when_apart_or_within_the_margin(other):
    assert crossing(_square(other), FLAT, 0.01) is None  # its edges end within the gap
    if other[0][2] > 0.0 or other[0][0] > 2:  # apart: neither passes through the other
        assert crossing(FLAT, _square(other), 0.01) is None


def _paper(x: float, rotation: float = 90.0):
    design = load_template(REPO_TEMPLATES / "paper-square.toml")
    design = design.with_changes(
        material=design.material.with_changes(thickness=1.0, relief_hole=4.0)
    )
    return [
        ("left", design, SitePlacement(0.0, 0.0, 0.0)),
        ("right", design, SitePlacement(x, 0.0, rotation)),
    ]


def test_sheets_whose_surfaces_cross_are_refused_naming_both():
    with pytest.raises(InvalidParameterError) as err:
        check_plan(_paper(40.0), "mm")
    text = str(err.value)
    assert text.startswith("sheets: 'left' and 'right' touch or overlap (distance 0 mm")
    assert "found before building them" in text and "\n" not in text
    overlap = float(text.split("footprints overlap by ")[1].split()[0])
    assert overlap > 0.0
    found = check_plan(_paper(40.0), "mm", allow_touching=True)  # allowed: said, not raised
    assert found is not None and (found.a, found.b) == ("left", "right")


def test_sheets_far_apart_and_the_shipped_site_pass():
    assert check_plan(_paper(1000.0), "mm") is None
    spec = read_site(REPO_TEMPLATES / "site-patkau-three.toml")
    sheets = [
        (s.name, j.design, SitePlacement(s.x, s.y, s.rotation_deg))
        for s, j in zip(spec.sheets, site_jobs(spec), strict=True)
    ]
    assert check_plan(sheets, spec.units) is None
