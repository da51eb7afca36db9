"""The checks of an argument's type that every rtw function makes the same
way, before the library checks its value: a yes/no argument is a bool, a
number is a number. Each names the argument and shows what was given."""

from __future__ import annotations

import numbers
from typing import Any


def flag(name: str, value: Any) -> bool:
    """`value`, a bool; anything else raises: Python would take ``"no"`` or
    ``[False]`` for true, and a yes/no argument such as ``force`` must
    never be said by accident."""
    if isinstance(value, bool):
        return value
    raise ValueError(f"{name}: {value!r} is invalid: must be True or False")


def number(name: str, value: Any) -> float:
    """`value` as a float, if it is a real number (int, float, numpy's; not
    a bool); anything else raises: ``float("0.05")`` would take text, which
    no rtw function does. Its range is the library's to check."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name}: {value!r} is invalid: must be a number")
    return float(value)
