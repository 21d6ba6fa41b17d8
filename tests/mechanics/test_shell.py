"""The shell model (mechanics/shell.py): copies keep what their reference derives."""

from __future__ import annotations

from dataclasses import replace
from functools import cached_property

import numpy as np

from onefold_cad.mechanics.shell import REFERENCE_CACHES, Shell
from tests.mechanics.helpers import cantilever, rectangle
from tests.mechanics.test_equilibrium import STEEL0


def _derived(shell: Shell) -> dict[str, object]:
    """Every cached quantity of ``shell``, computed."""
    return {name: getattr(shell, name) for name in REFERENCE_CACHES}


def _same(a, b) -> bool:
    if isinstance(a, tuple):
        return all(np.array_equal(x, y) for x, y in zip(a, b, strict=True))
    return np.array_equal(a, b)


def test_every_cached_property_is_a_reference_cache():
    cached = {n for n, v in vars(Shell).items() if isinstance(v, cached_property)}
    assert cached == set(REFERENCE_CACHES)


def test_a_copy_keeps_the_reference_caches_while_the_reference_stays():
    """A copy with a new rest form, gravity or crease angle shares the derived
    arrays (the same objects); a copy with a moved reference derives its own,
    equal to a fresh shell's (dataclasses.replace keeps no cache)."""
    mesh = rectangle(1.0, 0.2, 0.05)
    shell, _ = cantilever(mesh, STEEL0, 9.81)
    before = _derived(shell)
    kept = shell.with_changes(
        rest_curvature=shell.rest_curvature + 0.1, gravity=2 * shell.gravity,
        crease_angle=shell.crease_angle + 0.2,
    )  # fmt: skip
    for name in REFERENCE_CACHES:
        assert kept.__dict__[name] is before[name], name
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    moved = shell.with_changes(reference=shell.reference @ turn.T + [1.0, 2.0, 3.0])
    assert not any(name in moved.__dict__ for name in REFERENCE_CACHES)
    fresh = replace(shell, reference=moved.reference)
    for name, value in _derived(moved).items():
        assert _same(value, getattr(fresh, name)), name
    t0, _ = moved.edge_frames
    np.testing.assert_allclose(t0, shell.edge_frames[0] @ turn.T, atol=1e-15)
    heavier = shell.with_changes(material=replace(STEEL0, density=2 * STEEL0.density))
    np.testing.assert_allclose(heavier.node_mass, 2 * shell.node_mass, rtol=1e-15)
