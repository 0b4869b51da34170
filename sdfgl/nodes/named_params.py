"""Named parameters of the primitives a user writes (``implicit``, ``parametric``, ``glsl``).

Such a primitive takes ``params``: (name, value) pairs (or a dict), each value a number or
a live scalar (``sg.param``, so a slider moves it without a recompile). In a scene document
they are an array of ``[name, value]`` pairs. Names are plain identifiers that cannot be
mistaken for what the expression or code already means: not a coordinate or surface
variable (x, y, z, s, t, u, p), not a constant or a function of the expression grammar and,
for GLSL, not a GLSL keyword, type or built-in function.

:func:`parse_declarations` reads the primitives panel's declarations, one a line::

    r = 0.5 in [0.1, 2]
    k = 3
"""
from __future__ import annotations

import math
import re
from typing import Any

from ..errors import ParameterError
from ..values import validate as v

MAX_NAMED = 16  # named parameters of one primitive
MAX_NAME = 32   # characters of a name
NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
VARIABLES = frozenset({"x", "y", "z", "s", "t", "u", "p"})
GLSL_WORDS = frozenset("""
    attribute const uniform varying layout centroid flat smooth noperspective break continue do for while switch case
    default if else in out inout float int uint void bool true false invariant discard return mat2 mat3 mat4 vec2
    vec3 vec4 ivec2 ivec3 ivec4 bvec2 bvec3 bvec4 uvec2 uvec3 uvec4 lowp mediump highp precision sampler2D sampler3D
    struct main radians degrees sin cos tan asin acos atan sinh cosh tanh asinh acosh atanh pow exp log exp2 log2
    sqrt inversesqrt abs sign floor trunc round roundEven ceil fract mod modf min max clamp mix step smoothstep isnan
    isinf length distance dot cross normalize faceforward reflect refract matrixCompMult transpose determinant
    inverse texture dFdx dFdy fwidth""".split())


def _reserved(glsl: bool) -> frozenset[str]:
    from ..expr import CONSTANTS, FUNCTIONS
    words = VARIABLES | set(FUNCTIONS) | set(CONSTANTS)
    return frozenset(words | GLSL_WORDS) if glsl else frozenset(words)


def check_name(kind: str, name: Any, glsl: bool = False) -> str:
    """``name`` if it can name a parameter of a ``kind`` primitive, else ParameterError naming it."""
    if not isinstance(name, str) or not NAME.fullmatch(name) or len(name) > MAX_NAME:
        raise ParameterError(f"{kind}: parameter name {name!r} must be an identifier (a letter, then letters, digits "
                             f"or _; at most {MAX_NAME} characters)")
    if name.startswith("gl_") or "__" in name:
        raise ParameterError(f"{kind}: parameter name {name!r} is reserved (GLSL keeps names that start with gl_ "
                             f"or hold __); choose another")
    if name in _reserved(glsl):
        what = "GLSL keyword, type or function" if glsl and name in GLSL_WORDS else \
            "variable, constant or function of the expression"
        raise ParameterError(f"{kind}: parameter name {name!r} is taken (a {what}); choose another")
    return name


def named_params(kind: str, params: Any, glsl: bool = False) -> tuple[tuple[str, Any], ...]:
    """``params`` ((name, value) pairs, a dict or None) as checked pairs: names by
    :func:`check_name`, distinct; values finite numbers or live scalars."""
    if params is None:
        return ()
    if isinstance(params, dict):
        items = list(params.items())
    elif isinstance(params, (list, tuple)):
        items = list(params)
    else:
        raise ParameterError(f"{kind}: 'params' must be (name, value) pairs or a dict, got {type(params).__name__}")
    if len(items) > MAX_NAMED:
        raise ParameterError(f"{kind}: {len(items)} named parameters (at most {MAX_NAMED})")
    out: list[tuple[str, Any]] = []
    for item in items:
        if not isinstance(item, (list, tuple)) or len(item) != 2:
            raise ParameterError(f"{kind}: each of 'params' must be a (name, value) pair, got {item!r}")
        name = check_name(kind, item[0], glsl)
        if any(name == n for n, _ in out):
            raise ParameterError(f"{kind}: parameter {name!r} is named twice")
        out.append((name, v.scalar(kind, name, item[1])))
    return tuple(out)


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_DECLARATION = re.compile(rf"\s*(?P<name>[^=\s]+)\s*=\s*(?P<value>{_NUMBER})\s*"
                          rf"(?:in\s*\[\s*(?P<lo>{_NUMBER})\s*,\s*(?P<hi>{_NUMBER})\s*\])?\s*")


def default_range(value: float) -> tuple[float, float]:
    """The slider range of a parameter declared without one (that of the studio's number fields)."""
    from ..studio.palette import slider_range
    return slider_range(value)


def parse_declarations(text: Any, kind: str, glsl: bool = False) -> list[tuple[str, float, tuple[float, float]]]:
    """The named parameters declared in ``text``: one ``name = default`` or ``name = default in
    [lo, hi]`` a line (or separated by ``;``); lo < hi and the default inside are checked, and
    every error names the parameter. Returns (name, default, (lo, hi)) in order."""
    if text is None:
        return []
    if not isinstance(text, str):
        raise ParameterError(f"{kind}: parameter declarations must be text, got {type(text).__name__}")
    out: list[tuple[str, float, tuple[float, float]]] = []
    for line in re.split(r"[;\n]", text):
        if not line.strip():
            continue
        m = _DECLARATION.fullmatch(line)
        if m is None:
            raise ParameterError(f"{kind}: cannot read the parameter declaration {line.strip()!r}; write "
                                 f"'name = default' or 'name = default in [low, high]'")
        name = check_name(kind, m["name"], glsl)
        if any(name == n for n, _, _ in out):
            raise ParameterError(f"{kind}: parameter {name!r} is declared twice")
        value = float(m["value"])
        if m["lo"] is None:
            lo, hi = default_range(value)
            lo, hi = min(lo, value), max(hi, value)
        else:
            lo, hi = float(m["lo"]), float(m["hi"])
            if not lo < hi:
                raise ParameterError(f"{kind}: parameter {name!r}: its range [{lo:g}, {hi:g}] must have low < high")
            if not lo <= value <= hi:
                raise ParameterError(f"{kind}: parameter {name!r}: its default {value:g} is outside its range "
                                     f"[{lo:g}, {hi:g}]")
        if not all(math.isfinite(x) for x in (value, lo, hi)):
            raise ParameterError(f"{kind}: parameter {name!r}: its default and range must be finite numbers")
        out.append((name, value, (lo, hi)))
    if len(out) > MAX_NAMED:
        raise ParameterError(f"{kind}: {len(out)} named parameters (at most {MAX_NAMED})")
    return out
