"""Functions over live parameters: ``sg.sin(t)``, ``sg.clamp(x, 0, 1)``, ``sg.mix(a, b, t)``, ...

Each takes numbers, 3-vectors or live values (``sg.param``, ``sg.time()`` and expressions
over them). With a live argument the result is a live expression: the code generator
writes it over uniforms (the same GLSL function) and numpy evaluates it in float64, both
from one table (``sdfgl.params.OPS``). With plain numbers the result is a number now.
This module shadows ``min``, ``max``, ``abs`` and ``pow`` on purpose (as ``sg.min`` ...).
"""
from __future__ import annotations

import inspect
from typing import Any, Callable

from .errors import ParameterError
from .params import apply

VALUE = "a number, 3 numbers (per component) or a live value"
LIVE = ("Returns a float (or float64 array) for plain arguments; with any live argument, a live\n"
        "expression the shader evaluates from uniforms (no recompile when the parameters change).")


def _function(op: str, params: dict[str, str], summary: str, example: str) -> Callable[..., Any]:
    """sg.<op>: ``params`` maps each parameter name to its description; ``example`` is
    doctest text (``>>>`` lines with their output)."""
    sig = inspect.Signature([inspect.Parameter(n, inspect.Parameter.POSITIONAL_OR_KEYWORD) for n in params])
    names = tuple(params)

    def f(*args: Any, **kwargs: Any) -> Any:
        try:
            bound = sig.bind(*args, **kwargs)
        except TypeError as exc:
            given = len(args) + len(kwargs)
            if given != len(names):
                raise ParameterError(f"sg.{op}: takes {len(names)} argument{'s' if len(names) > 1 else ''}, "
                                     f"got {given} (sg.{op}({', '.join(names)}))") from None
            raise ParameterError(f"sg.{op}({', '.join(names)}): {exc}") from None
        return apply(op, *bound.args, names=names)

    f.__name__ = f.__qualname__ = op
    f.__signature__ = sig  # type: ignore[attr-defined]
    lines = "\n".join(f"    {n}: {d}" for n, d in params.items())
    f.__doc__ = f"{summary}\n\nArgs:\n{lines}\n\n{LIVE}\n\nExample:\n{example}\n"
    return f


sin = _function("sin", {"x": f"an angle in radians: {VALUE}"}, "Sine of ``x`` (radians), as GLSL's sin.",
                "    >>> float(sg.sin(0.5 * sg.param(1.0)))\n    0.479425538604203")
cos = _function("cos", {"x": f"an angle in radians: {VALUE}"}, "Cosine of ``x`` (radians), as GLSL's cos.",
                "    >>> round(sg.cos(sg.radians(60.0)), 12)\n    0.5")
tan = _function("tan", {"x": f"an angle in radians: {VALUE}"},
                "Tangent of ``x`` (radians), as GLSL's tan (unbounded near odd multiples of pi/2).",
                "    >>> round(float(sg.tan(sg.param(0.25) * 3.141592653589793)), 12)\n    1.0")
abs = _function("abs", {"x": VALUE}, "Absolute value of ``x`` (per component).",  # noqa: A001 - mirrors GLSL
                "    >>> sg.abs(-2.5)\n    2.5")
sqrt = _function("sqrt", {"x": f"{VALUE}; must stay >= 0 (NaN otherwise)"}, "Square root of ``x``.",
                 "    >>> float(sg.sqrt(sg.param(9.0)))\n    3.0")
exp = _function("exp", {"x": VALUE}, "e to the power ``x``.",
                "    >>> sg.exp(0.0)\n    1.0")
log = _function("log", {"x": f"{VALUE}; must stay > 0"}, "Natural logarithm of ``x``.",
                "    >>> round(sg.log(2.718281828459045), 12)\n    1.0")
sign = _function("sign", {"x": VALUE}, "-1, 0 or 1 by the sign of ``x`` (per component).",
                 "    >>> sg.sign(-0.3), sg.sign(0.0)\n    (-1.0, 0.0)")
floor = _function("floor", {"x": VALUE}, "The largest whole number not above ``x``.",
                  "    >>> sg.floor(-1.5)\n    -2.0")
fract = _function("fract", {"x": VALUE}, "``x - floor(x)``, in [0, 1): a sawtooth of period 1 (GLSL's fract).",
                  "    >>> t = sg.time(2.25)\n    >>> float(sg.fract(t))\n    0.25")
radians = _function("radians", {"degrees": f"an angle in degrees: {VALUE}"}, "Degrees to radians.",
                    "    >>> round(sg.radians(180.0), 6)\n    3.141593")
min = _function("min", {"a": VALUE, "b": VALUE},  # noqa: A001 - mirrors GLSL
                "The smaller of ``a`` and ``b``, per component (a number with a 3-vector compares each).",
                "    >>> float(sg.min(sg.param(0.7), 0.5))\n    0.5")
max = _function("max", {"a": VALUE, "b": VALUE},  # noqa: A001 - mirrors GLSL
                "The larger of ``a`` and ``b``, per component (a number with a 3-vector compares each).",
                "    >>> sg.max((0.0, 2.0, -1.0), 0.5)\n    array([0.5, 2. , 0.5])")
pow = _function("pow", {"x": f"the base, {VALUE}; must stay >= 0 (as in GLSL)", "y": f"the exponent, {VALUE}"},
                "``x`` to the power ``y``.",  # noqa: A001 - mirrors GLSL
                "    >>> sg.pow(2.0, 3.0)\n    8.0")
mod = _function("mod", {"x": VALUE, "y": f"the period, {VALUE}; non-zero"},
                "``x - y * floor(x / y)``, as GLSL's mod (the result takes the sign of ``y``, unlike C's fmod).",
                "    >>> sg.mod(-1.0, 3.0)\n    2.0")
step = _function("step", {"edge": f"the threshold, {VALUE}", "x": VALUE},
                 "0 where ``x < edge``, else 1 (GLSL's step; note the argument order).",
                 "    >>> t = sg.time(1.5)\n    >>> float(sg.step(1.0, t))\n    1.0")
clamp = _function("clamp", {"x": VALUE, "lo": f"the lower limit, {VALUE}", "hi": f"the upper limit, {VALUE}"},
                  "``x`` limited to [``lo``, ``hi``].",
                  "    >>> sg.clamp(1.5, 0.0, 1.0)\n    1.0")
mix = _function("mix", {"a": f"the value at t = 0, {VALUE}", "b": f"the value at t = 1, {VALUE}",
                        "t": f"the blend weight, {VALUE} (not limited to [0, 1])"},
                "Linear blend ``a * (1 - t) + b * t``, as GLSL's mix.",
                "    >>> sg.mix((0, 0, 0), (2, 4, 6), 0.5)\n    array([1., 2., 3.])")
smoothstep = _function("smoothstep", {"e0": f"where the step starts (result 0), {VALUE}",
                                      "e1": f"where it ends (result 1), {VALUE}; e0 != e1", "x": VALUE},
                       "Hermite step: 0 below ``e0``, 1 above ``e1``, ``3s^2 - 2s^3`` between (GLSL's smoothstep).",
                       "    >>> t = sg.time(0.5)\n    >>> float(sg.smoothstep(0.0, 1.0, t))\n    0.5")
FUNCTIONS = ("sin", "cos", "tan", "abs", "sqrt", "exp", "log", "sign", "floor", "fract", "radians", "min", "max",
             "pow", "mod", "step", "clamp", "mix", "smoothstep")
