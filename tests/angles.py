"""The whole admissible range of the frame angles for property tests, and the
refusal that a design below the angle bound must get.

alpha and beta are admissible in (0, 90) deg open; below
:data:`~onefold_cad.geometry.frame_curve.MIN_ANGLE_DEG` (1e-100 deg: there their
squares in radians underflow) a frame is refused with an
``InvalidParameterError`` naming the angle and the bound. A property test
draws from the whole open interval and accepts that refusal, checked here,
as the answer for such a draw.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import pytest
from hypothesis import strategies as st

from onefold_cad import FrameCurve, InvalidParameterError
from onefold_cad.geometry.frame_curve import MIN_ANGLE_DEG

#: alpha or beta anywhere in (0, 90) deg, subnormal floats included.
OPEN_ANGLE = st.floats(0.0, 90.0, exclude_min=True, exclude_max=True)


def cos_deg(deg: float) -> float:
    """cos(deg) for deg in (0, 90), to a relative rounding error: from the
    complement, sin(90 - deg), which is exact above 45 deg (near 90 a double
    cos(radians(deg)) is off by up to 8 %, enough to put H past the f-line)."""
    return math.sin(math.radians(90.0 - deg))


def frame_unless_on_end(
    make: Callable[[], FrameCurve], h_c: float, half: float
) -> FrameCurve | None:
    """``make()``'s frame, or None when it refuses h_c with |h_c| within 4 ulps
    of ``half`` (R cos(alpha)): H on an end of the f-line up to rounding. Any
    other refusal is raised."""
    try:
        return make()
    except InvalidParameterError as err:
        if err.parameter != "h_c" or abs(abs(h_c) - half) > 4.0 * math.ulp(half):
            raise
        return None


def refused_below_bound(alpha: float, beta: float, make: Callable[[], object]) -> bool:
    """Whether alpha or beta lies below MIN_ANGLE_DEG; if so, after checking
    that ``make()`` (which builds the frame or design) refuses it with an
    InvalidParameterError naming that angle and the bound."""
    low = [name for name, value in (("alpha", alpha), ("beta", beta)) if value < MIN_ANGLE_DEG]
    if not low:
        return False
    with pytest.raises(InvalidParameterError) as err:
        make()
    assert err.value.parameter in low, str(err.value)
    assert f"at least {MIN_ANGLE_DEG:g} deg" in str(err.value), str(err.value)
    return True
