"""Axes as users write them: ``"x"``, ``"y"``, ``"z"``, ``sg.X`` or any vector.

Two kinds of parameter take an axis. A direction (``rotate``, ``orient``) may point
anywhere: :func:`direction`. A coordinate axis (``twist``, ``bend``, ``taper``,
``shear``) must be one of x, y, z, given by name or as a vector along it: :func:`coordinate`.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import ParameterError
from .live import LiveValue
from .validate import vector

NAMES = "xyz"


def shown(value: object) -> str:
    """``value`` as an error message quotes it (an array as a tuple of its numbers)."""
    return repr(tuple(value.tolist())) if isinstance(value, np.ndarray) else repr(value)


def _named(node: str, name: str, value: str) -> int:
    i = NAMES.find(value.strip().lower()) if len(value.strip()) == 1 else -1
    if i < 0:
        raise ParameterError(f"{node}: parameter '{name}' must be 'x', 'y', 'z' or a vector, got {value!r}")
    return i


def direction(node: str, name: str, value: object) -> Any:
    """A nonzero direction as a float64 3-vector (not normalised), or a live 3-vector.

    ``value`` is an axis name ("x", "y", "z", any case) or three numbers (``sg.X``,
    ``(1, 1, 0)``); ParameterError naming ``node.name`` otherwise."""
    if isinstance(value, str):
        out = np.zeros(3)
        out[_named(node, name, value)] = 1.0
        return out
    return vector(node, name, value, nonzero=True)


def coordinate(node: str, name: str, value: object) -> int:
    """The index (0, 1, 2) of a coordinate axis named "x", "y" or "z" (any case) or given
    as a vector along it in the positive sense (``sg.X``, ``(0, 2, 0)``).

    Any other direction, and a live value, is a ParameterError naming ``node.name``."""
    if isinstance(value, str):
        return _named(node, name, value)
    if isinstance(value, LiveValue):
        raise ParameterError(f"{node}: parameter '{name}' cannot be a live parameter (it selects a coordinate axis)")
    a = vector(node, name, value, nonzero=True)
    nz = np.flatnonzero(a)
    if len(nz) != 1 or a[nz[0]] <= 0:
        raise ParameterError(f"{node}: parameter '{name}' must be 'x', 'y', 'z' or a vector along the positive "
                             f"x, y or z axis, got {shown(value)}")
    return int(nz[0])


def coordinate_name(node: str, name: str, value: object) -> str:
    """The name ("x", "y" or "z") of the coordinate axis :func:`coordinate` reads in ``value``."""
    return NAMES[coordinate(node, name, value)]
