"""Functions over live parameters: ``sg.sin(t)``, ``sg.clamp(x, 0, 1)``, ``sg.mix(a, b, t)``, ...

Each takes numbers, 3-vectors or live values (``sg.param``, ``sg.time()`` and expressions
over them). With a live argument the result is a live expression: the code generator
writes it over uniforms (the same GLSL function) and numpy evaluates it in float64, both
from one table (``sdfgl.params.OPS``). With plain numbers the result is a number now.
This module shadows ``min``, ``max``, ``abs`` and ``pow`` on purpose (as ``sg.min`` ...).
"""
from __future__ import annotations

from typing import Any, Callable

from .errors import ParameterError
from .params import apply


def _function(op: str, arity: int, doc: str) -> Callable[..., Any]:
    def f(*args: Any) -> Any:
        if len(args) != arity:
            raise ParameterError(f"sg.{op}: takes {arity} argument{'s' if arity > 1 else ''}, got {len(args)}")
        return apply(op, *args)
    f.__name__ = f.__qualname__ = op
    f.__doc__ = doc + " Live arguments give a live expression (a uniform in GLSL, float64 in numpy)."
    return f


sin = _function("sin", 1, "Sine of radians.")
cos = _function("cos", 1, "Cosine of radians.")
tan = _function("tan", 1, "Tangent of radians.")
abs = _function("abs", 1, "Absolute value.")  # noqa: A001 - sg.abs mirrors GLSL
sqrt = _function("sqrt", 1, "Square root.")
exp = _function("exp", 1, "e to the power x.")
log = _function("log", 1, "Natural logarithm.")
sign = _function("sign", 1, "-1, 0 or 1.")
floor = _function("floor", 1, "Largest integer not above x.")
fract = _function("fract", 1, "x - floor(x).")
radians = _function("radians", 1, "Degrees to radians.")
min = _function("min", 2, "The smaller of two values (per component).")  # noqa: A001
max = _function("max", 2, "The larger of two values (per component).")  # noqa: A001
pow = _function("pow", 2, "x to the power y (x >= 0, as in GLSL).")  # noqa: A001
mod = _function("mod", 2, "x - y * floor(x / y), as GLSL's mod.")
step = _function("step", 2, "0 where x < edge, else 1: step(edge, x).")
clamp = _function("clamp", 3, "x limited to [lo, hi]: clamp(x, lo, hi).")
mix = _function("mix", 3, "Linear blend a * (1 - t) + b * t: mix(a, b, t).")
smoothstep = _function("smoothstep", 3, "Hermite step from e0 to e1: smoothstep(e0, e1, x).")
FUNCTIONS = ("sin", "cos", "tan", "abs", "sqrt", "exp", "log", "sign", "floor", "fract", "radians", "min", "max",
             "pow", "mod", "step", "clamp", "mix", "smoothstep")
