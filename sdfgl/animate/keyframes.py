"""Keyframed values: a live expression of the clock that passes through given values.

    r = sg.keyframes({0: 1.0, 1.5: 1.4, 3: 1.0}, ease="smooth")   # over a new sg.time()
    scene = sg.sphere(r)

The expression is closed-form (``v0 + sum_i (v[i+1] - v[i]) * w_i(t)`` with ``w_i`` a
clamped ramp or a smoothstep between key i and i+1), so the shader evaluates it from the
time uniform and numpy from the same ops table: no recompile between frames, and every
node that reads it checks its value at each new time.
"""
from __future__ import annotations

from typing import Any, Mapping, Sequence

import numpy as np

from ..errors import ParameterError
from ..params import Live, Time

EASES = ("linear", "smooth", "step")


def keyframe_list(keys: Mapping[float, Any] | Sequence[tuple[float, Any]], what: str) -> list[tuple[float, Any]]:
    """Keyframes given as a mapping or (time, value) pairs, as a list sorted by time (``what`` names them in errors)."""
    if isinstance(keys, Mapping):
        items = list(keys.items())
    elif isinstance(keys, (Sequence, np.ndarray)) and not isinstance(keys, (str, bytes)):
        items = list(keys)
    else:
        raise ParameterError(f"{what}: 'keys' must be a dict {{seconds: value}} or a list of (seconds, value) pairs, "
                             f"got {type(keys).__name__} {keys!r}")
    if not items:
        raise ParameterError(f"{what}: needs at least one (time, value) key")
    out: list[tuple[float, Any]] = []
    for i, item in enumerate(items):
        try:
            t, v = item
            t = float(t)
        except (TypeError, ValueError):
            raise ParameterError(f"{what}: key {i} must be (time, value), got {item!r}") from None
        if not np.isfinite(t):
            raise ParameterError(f"{what}: key {i} has a time that is not finite ({t})")
        if out and t <= out[-1][0]:
            raise ParameterError(f"{what}: key times must increase, key {i} is at {t:g} after {out[-1][0]:g}")
        out.append((t, v))
    return out


def _value(v: Any, what: str, i: int, shape: tuple | None) -> np.ndarray:
    try:
        arr = np.asarray(v, dtype=np.float64)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.shape not in ((), (3,)) or not np.all(np.isfinite(arr)):
        raise ParameterError(f"{what}: key {i} value must be a finite number or 3 finite numbers, got {v!r}")
    if shape is not None and arr.shape != shape:
        raise ParameterError(f"{what}: key {i} value {v!r} does not match the shape of key 0")
    return arr


def _weight(t: Live, t0: float, t1: float, ease: str) -> Live:
    if ease == "smooth":
        return Live("smoothstep", t0, t1, t)
    if ease == "step":
        return Live("step", t1, t)
    return Live("clamp", Live("mul", Live("sub", t, t0), 1.0 / (t1 - t0)), 0.0, 1.0)


def keyframes(keys: Mapping[float, Any] | Sequence[tuple[float, Any]], ease: str = "linear",
              time: Live | None = None) -> Live:
    """A live value through ``keys``, held before the first key and after the last.

    Args:
        keys: ``{seconds: value}`` or a list of ``(seconds, value)`` pairs, times strictly
            increasing; every value a finite number, or every value 3 finite numbers (a
            position, size or colour).
        ease: "linear" (constant speed between keys), "smooth" (smoothstep: eases in and
            out of every key) or "step" (jumps to each key's value at its time).
        time: the clock it follows, in seconds (default: a new ``sg.time()``, which
            ``sg.animate`` sets); any live scalar works, e.g. ``2 * sg.time()``.

    Returns a live expression (closed-form over the clock: one uniform in the shader, no
    recompile between frames) that nodes take wherever they take a number or 3-vector.

    Example:
        >>> t = sg.time()
        >>> r = sg.keyframes({0: 1.0, 2: 2.0, 3: 1.0}, time=t)
        >>> t.value = 1.0
        >>> float(r), float(sg.sphere(r).distance((3, 0, 0)))
        (1.5, 1.5)
    """
    what = "keyframes"
    if ease not in EASES:
        raise ParameterError(f"{what}: ease must be one of {', '.join(EASES)}, got {ease!r}")
    clock = time if time is not None else Time()
    if not isinstance(clock, Live) or clock.dims != 1:
        raise ParameterError(f"{what}: 'time' must be a live scalar such as sg.time(), got {clock!r}")
    ks = keyframe_list(keys, what)
    vals: list[np.ndarray] = []
    for i, (_, v) in enumerate(ks):
        vals.append(_value(v, what, i, vals[0].shape if vals else None))
    lit = (lambda a: float(a)) if vals[0].ndim == 0 else (lambda a: a)
    expr: Any = lit(vals[0])
    for (t0, _), (t1, _), v0, v1 in zip(ks, ks[1:], vals, vals[1:]):
        if np.any(v1 != v0):
            expr = Live("add", expr, Live("mul", _weight(clock, t0, t1, ease), lit(v1 - v0)))
    return expr if isinstance(expr, Live) else Live("add", expr, Live("mul", 0.0, clock))  # live even if constant

