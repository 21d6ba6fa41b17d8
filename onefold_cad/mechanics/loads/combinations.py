"""EN 1990's combinations of actions as named load cases.

Actions: ``G`` the sheet's weight (permanent), ``W+D`` / ``W-D`` the wind
towards D deg pushing down / lifting (:mod:`.wind`), ``S`` the snow, ``P``
the person (EN 1991-1-1's roof of category H).

- ``EQU`` (rigid-body equilibrium: sliding, a foot lifting, tipping, the
  ballast; Table A1.2(A)): ``0.9 G + 1.5 W`` (the weight favourable);
- ``STR`` (the sheet's strength and the anchors; Table A1.2(B), Eq. 6.10):
  ``1.35 G + 1.5 Q_1 + 1.5 psi_0 Q_2``, or ``1.0 G + 1.5 W`` where the wind
  lifts (the weight favourable);
- ``SLS`` (deflection; the characteristic combination, Eq. 6.14b):
  ``G + Q_1 + psi_0 Q_2``.

``psi_0`` (Table A1.1): wind 0.6, snow 0.5 (sites below 1000 m), roofs of
category H 0: the person is never combined with snow or wind (EN 1991-1-1
3.3.2(1)), and snow never with a lifting wind (it would be favourable).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["GAMMA", "PSI0", "Case", "combinations"]

#: Partial factors (EN 1990 Table A1.2(A) and (B), recommended values).
GAMMA = {
    "EQU": {"G_sup": 1.1, "G_inf": 0.9, "Q": 1.5},
    "STR": {"G_sup": 1.35, "G_inf": 1.0, "Q": 1.5},
}
#: Combination factors psi_0 (EN 1990 Table A1.1).
PSI0 = {"W": 0.6, "S": 0.5, "P": 0.0}


@dataclass(frozen=True)
class Case:
    """A named combination.

    Attributes:
        name: e.g. ``STR 1.35G + 1.5W+45 + 0.75S``.
        kind: ``EQU``, ``STR`` or ``SLS``.
        factors: the actions' factors (``G``, ``W+45``, ``S``, ``P``).
    """

    name: str
    kind: str
    factors: tuple[tuple[str, float], ...]

    @property
    def factor(self) -> dict[str, float]:
        """The factors as a dict."""
        return dict(self.factors)


def _case(kind: str, factors: dict[str, float]) -> Case:
    terms = []
    for k, v in factors.items():
        terms.append(f"{v:g}{k}" if v != 1.0 else k)
    return Case(f"{kind} " + " + ".join(terms), kind, tuple(factors.items()))


def combinations(directions: list[float], snow: bool, person: bool) -> list[Case]:
    """The cases for wind towards ``directions`` (deg), with snow and the person
    when they are given (see the module docstring)."""
    e, s = GAMMA["EQU"], GAMMA["STR"]
    q = s["Q"]
    out = [_case("STR", {"G": s["G_sup"]}), _case("SLS", {"G": 1.0})]
    for d in directions:
        up, down = f"W-{d:g}", f"W+{d:g}"
        out += [
            _case("EQU", {"G": e["G_inf"], up: e["Q"]}),
            _case("STR", {"G": s["G_inf"], up: q}),
            _case("SLS", {"G": 1.0, up: 1.0}),
            _case("EQU", {"G": e["G_inf"], down: e["Q"]}),
            _case("STR", {"G": s["G_sup"], down: q}),
            _case("SLS", {"G": 1.0, down: 1.0}),
        ]
        if snow:
            out += [
                _case("STR", {"G": s["G_sup"], down: q, "S": q * PSI0["S"]}),
                _case("STR", {"G": s["G_sup"], "S": q, down: q * PSI0["W"]}),
                _case("SLS", {"G": 1.0, "S": 1.0, down: PSI0["W"]}),
            ]
    if snow:
        out += [_case("STR", {"G": s["G_sup"], "S": q}), _case("SLS", {"G": 1.0, "S": 1.0})]
    if person:
        out += [_case("STR", {"G": s["G_sup"], "P": q}), _case("SLS", {"G": 1.0, "P": 1.0})]
    return out
