"""Parameter checks shared by every node constructor: each error names node and parameter."""
from __future__ import annotations

import math
from numbers import Real
from typing import Sequence

import numpy as np

from ..errors import ParameterError


def scalar(node: str, name: str, value: object, *, positive: bool = False,
           nonnegative: bool = False) -> float:
    """Return ``value`` as a finite float, or raise ParameterError naming ``node.name``."""
    if isinstance(value, bool) or not isinstance(value, (Real, np.floating, np.integer)):
        raise ParameterError(f"{node}: parameter '{name}' must be a number, got {type(value).__name__} {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise ParameterError(f"{node}: parameter '{name}' must be finite, got {v}")
    if positive and v <= 0:
        raise ParameterError(f"{node}: parameter '{name}' must be > 0, got {v}")
    if nonnegative and v < 0:
        raise ParameterError(f"{node}: parameter '{name}' must be >= 0, got {v}")
    return v


def vector(node: str, name: str, value: object, n: int = 3, *, positive: bool = False,
           nonzero: bool = False) -> np.ndarray:
    """Return ``value`` as a float64 vector of length n (a scalar is broadcast)."""
    if isinstance(value, (Real, np.floating, np.integer)) and not isinstance(value, bool):
        value = [value] * n
    if isinstance(value, (str, bytes)) or not isinstance(value, (Sequence, np.ndarray)):
        raise ParameterError(f"{node}: parameter '{name}' must be {n} numbers, got {type(value).__name__} {value!r}")
    items = list(value)
    if len(items) != n:
        raise ParameterError(f"{node}: parameter '{name}' must have {n} components, got {len(items)}")
    out = np.array([scalar(node, f"{name}[{i}]", x, positive=positive) for i, x in enumerate(items)],
                   dtype=np.float64)
    if nonzero and not np.any(out):
        raise ParameterError(f"{node}: parameter '{name}' must not be the zero vector")
    return out


def color(node: str, value: object) -> tuple[float, float, float]:
    """Return an RGB triple with components in [0, 1]."""
    rgb = vector(node, "color", value)
    if np.any(rgb < 0) or np.any(rgb > 1):
        raise ParameterError(f"{node}: colour components must lie in [0, 1], got {tuple(rgb)}")
    return tuple(float(c) for c in rgb)
