"""Parameter checks shared by every node constructor: each error names node and parameter.

A live parameter (sdfgl.param) is checked now and again whenever its value changes, so a
later ``p.value = -1`` fails with the same message as ``sphere(-1)``.
"""
from __future__ import annotations

import math
import os
from numbers import Real
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np

from ..errors import ParameterError
from .colors import parse
from .float32 import FLOAT32_MAX
from .live import LiveValue


def _roots(values: Sequence[Any]) -> list:
    out = []
    for x in values:
        if isinstance(x, LiveValue):
            out += [p for p in x.roots() if p not in out]
    return out


def watch(check: Callable[[], None], *values: Any) -> None:
    """Run ``check()`` now and whenever a live parameter among ``values`` changes."""
    roots = _roots(values)
    if not roots:
        check()
        return
    for p in roots:
        p.add_check(lambda _v: check())


def as_float(node: str, name: str, value: Any) -> float:
    """``float(value)``, or ParameterError naming ``node.name`` for an integer too large for a float."""
    try:
        return float(value)
    except OverflowError:
        raise ParameterError(f"{node}: parameter '{name}' is too large for a number the shader can hold "
                             f"(|value| <= {FLOAT32_MAX:.3g}), got an integer of {len(str(abs(int(value))))} digits") \
            from None


def check_float32(node: str, name: str, v: float) -> None:
    """Refuse a finite ``v`` past float32's range: it would reach the shader as infinity."""
    if abs(v) > FLOAT32_MAX:
        raise ParameterError(f"{node}: parameter '{name}' must be at most {FLOAT32_MAX:.3g} in magnitude "
                             f"(the shader computes in float32), got {v:g}")


def _check_scalar(node: str, name: str, v: float, positive: bool, nonnegative: bool) -> float:
    if not math.isfinite(v):
        raise ParameterError(f"{node}: parameter '{name}' must be finite, got {v}")
    check_float32(node, name, v)
    if positive and v <= 0:
        raise ParameterError(f"{node}: parameter '{name}' must be > 0, got {v}")
    if nonnegative and v < 0:
        raise ParameterError(f"{node}: parameter '{name}' must be >= 0, got {v}")
    return v


_PLAIN = (float, int)  # exactly these types (bool is not one of them)


def scalar(node: str, name: str, value: object, *, positive: bool = False,
           nonnegative: bool = False) -> Any:
    """``value`` as a finite float (or a live scalar), else ParameterError naming ``node.name``."""
    if type(value) is float and -FLOAT32_MAX <= value <= FLOAT32_MAX \
            and not (positive and value <= 0) and not (nonnegative and value < 0):
        return value  # the most common call: a plain float in range (NaN fails the comparisons)
    if type(value) in _PLAIN:  # checked without the ABC test of numbers.Real
        return _check_scalar(node, name, as_float(node, name, value), positive, nonnegative)
    if isinstance(value, LiveValue):
        if value.dims != 1:
            raise ParameterError(f"{node}: parameter '{name}' must be a scalar, got a 3-vector parameter")
        watch(lambda: _check_scalar(node, name, float(value.value), positive, nonnegative), value)
        return value
    if isinstance(value, bool) or not isinstance(value, (Real, np.floating, np.integer)):
        raise ParameterError(f"{node}: parameter '{name}' must be a number, got {type(value).__name__} {value!r}")
    return _check_scalar(node, name, as_float(node, name, value), positive, nonnegative)


def _check_vector(node: str, name: str, arr: np.ndarray, positive: bool, nonzero: bool) -> None:
    for i, x in enumerate(arr):
        _check_scalar(node, f"{name}[{i}]", float(x), positive, False)
    if nonzero and not np.any(arr):
        raise ParameterError(f"{node}: parameter '{name}' must not be the zero vector")


def vector(node: str, name: str, value: object, n: int = 3, *, positive: bool = False,
           nonzero: bool = False) -> Any:
    """``value`` as a float64 vector of length n (a scalar is broadcast), or a live value."""
    if n == 3 and type(value) in (tuple, list) and len(value) == 3:
        x, y, z = value  # the most common call: three plain Python numbers
        if type(x) in _PLAIN and type(y) in _PLAIN and type(z) in _PLAIN:
            # NaN, infinity and an int too big for a float fail here; the checks below name them
            if (-FLOAT32_MAX <= x <= FLOAT32_MAX and -FLOAT32_MAX <= y <= FLOAT32_MAX
                    and -FLOAT32_MAX <= z <= FLOAT32_MAX
                    and not (positive and (x <= 0 or y <= 0 or z <= 0)) and not (nonzero and not (x or y or z))):
                return np.array(value, dtype=np.float64)
    if isinstance(value, LiveValue):
        watch(lambda: _check_vector(node, name, np.broadcast_to(np.asarray(value.value, float), (n,)),
                                    positive, nonzero), value)
        return value
    if isinstance(value, (Real, np.floating, np.integer)) and not isinstance(value, bool):
        value = [value] * n
    if isinstance(value, (tuple, list, np.ndarray)) and len(value) == n:
        try:  # fast path: n plain finite numbers (everything else takes the checks below)
            fast = np.array(value, dtype=np.float64)
        except (TypeError, ValueError, OverflowError):
            fast = None
        if (fast is not None and fast.shape == (n,) and (np.abs(fast) <= FLOAT32_MAX).all()
                and not (positive and fast.min() <= 0)
                and not (nonzero and not fast.any())
                and all(type(x) in (int, float) or isinstance(x, (np.floating, np.integer)) for x in value)):
            return fast
    if isinstance(value, (str, bytes)) or not isinstance(value, (Sequence, np.ndarray)):
        raise ParameterError(f"{node}: parameter '{name}' must be {n} numbers, got {type(value).__name__} {value!r}")
    items = list(value)
    if len(items) != n:
        raise ParameterError(f"{node}: parameter '{name}' must have {n} components, got {len(items)}")
    out = np.array([scalar(node, f"{name}[{i}]", x, positive=positive) for i, x in enumerate(items)],
                   dtype=np.float64)
    _check_vector(node, name, out, positive, nonzero)
    return out


def color(node: str, value: object, name: str = "color") -> Any:
    """A linear RGB triple (see :mod:`sdfgl.values.colors`: names, hex, 0..255 or 0..1), or a
    live 3-vector whose components must stay in [0, 1]."""
    if not isinstance(value, LiveValue):
        return parse(node, name, value)
    rgb = vector(node, name, value)

    def check() -> None:
        c = np.broadcast_to(np.asarray(rgb.value if isinstance(rgb, LiveValue) else rgb, float), (3,))
        if np.any(c < 0) or np.any(c > 1):
            raise ParameterError(f"{node}: colour components must lie in [0, 1], got {tuple(c)}")
    watch(check, rgb)
    return rgb if isinstance(rgb, LiveValue) else tuple(float(c) for c in rgb)


def fixed(node: str, reason: str, **values: object) -> None:
    """Refuse live parameters for values that shape the generated code (``reason`` says how)."""
    for name, val in values.items():
        if isinstance(val, LiveValue):
            raise ParameterError(f"{node}: '{name}' cannot be a live parameter ({reason})")


def at_most_half_edge(node: str, name: str, value: Any, size: Any, edge: str = "edge") -> None:
    """Check (now and on every live change) that ``value`` <= half the smallest of ``size``."""
    def check() -> None:
        if float(value) > np.min(np.asarray(size, dtype=float)) / 2:
            raise ParameterError(f"{node}: parameter '{name}' ({float(value):g}) must be at most half the smallest "
                                 f"{edge} ({np.min(np.asarray(size, dtype=float)) / 2:g})")
    watch(check, size, value)


def file_path(node: str, name: str, value: object) -> Path:
    """``value`` as a filesystem path (a str or os.PathLike), or an error naming the parameter."""
    if isinstance(value, (str, os.PathLike)) and str(value):
        return Path(value)
    raise ParameterError(f"{node}: '{name}' must be a file path (a string or pathlib.Path), got {value!r}")
