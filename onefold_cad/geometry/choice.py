"""The design's named options (model, units, sheet surface, compensation):
one way to read them from text and one error for a name that is not one."""

from __future__ import annotations

import re
from enum import StrEnum
from typing import Self

from onefold_cad.errors import InvalidParameterError

__all__ = ["Choice"]


class Choice(StrEnum):
    """A string enum whose members a user names in any case.

    The parameter a bad name is reported against is the class name in
    snake case: ``Model`` -> ``model``, ``SheetSurface`` -> ``sheet_surface``.
    """

    @classmethod
    def parse(cls, value: object) -> Self:
        """The member named by ``value`` (a member, or its value in any case).

        Raises:
            InvalidParameterError: naming the parameter and the allowed names.
        """
        if isinstance(value, cls):
            return value
        text = str(value).casefold()
        for member in cls:
            if member.value.casefold() == text:
                return member
        names = ", ".join(member.value for member in cls)
        parameter = re.sub(r"(?<!^)(?=[A-Z])", "_", cls.__name__).lower()
        raise InvalidParameterError(parameter, f"must be one of {names}, got {value!r}")
