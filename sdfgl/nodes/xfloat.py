"""Implicit fields that overflow float32: when to evaluate them in extended range, and the
GLSL that does (``shaders/lib/xfloat.glsl``: a value is m * 2^e with e an integer float).

``x**64 + y**64 + z**64 - 1`` overflows float32 beyond |x| = 4 and its gradient a little
earlier, so f / |grad f| is inf / inf = NaN exactly where a ray starts. Written with
extended-range floats, f and grad f keep their float32 rounding at any magnitude and the
ratio (a first-order distance, about |x| / 64 there) is finite: the marcher sees a field.
Fields whose values stay far below the float32 limit keep the plain code (it is cheaper).
"""
from __future__ import annotations

import math
from typing import Any

# |x|, |y|, |z| up to this are assumed when judging whether a field can overflow: about
# the largest scene coordinate relative to the shader origin a float32 scene resolves
REACH = 1e4
LIMIT_LOG10 = 36.0  # a field whose magnitude may pass 1e36 at REACH is written in extended range


def magnitude_log10(expr: Any, reach: float = REACH) -> float:
    """An upper estimate of log10 |expr| for |x|, |y|, |z| <= ``reach`` (inf when unbounded,
    e.g. a negative power or a division that may blow up)."""
    import sympy as sp
    memo: dict[Any, float] = {}

    def mag(e: Any) -> float:
        if e in memo:
            return memo[e]
        if e.is_Symbol:
            v = math.log10(reach)
        elif e.is_Number or isinstance(e, sp.NumberSymbol):
            c = abs(float(e))
            v = math.log10(c) if c > 0 else -math.inf
        elif isinstance(e, sp.Add):
            v = max(mag(a) for a in e.args) + math.log10(len(e.args))
        elif isinstance(e, sp.Mul):
            v = sum(mag(a) for a in e.args)
        elif isinstance(e, sp.Pow):
            b, x = e.as_base_exp()
            if x.is_Number and float(x) >= 0:
                v = float(x) * max(mag(b), 0.0)
            else:
                v = math.inf  # a negative or symbolic exponent: a pole may be anywhere
        elif isinstance(e, (sp.sin, sp.cos, sp.tanh, sp.atan, sp.asin, sp.acos)):
            v = 0.5
        elif isinstance(e, (sp.exp, sp.sinh, sp.cosh)):
            v = 10 ** min(mag(e.args[0]), 300) * math.log10(math.e)
        elif isinstance(e, sp.log):
            v = math.log10(max(abs(mag(e.args[0])) * math.log(10), 1.0)) + 1
        elif isinstance(e, sp.Abs):
            v = mag(e.args[0])
        else:  # tan and anything else: no bound
            v = math.inf
        memo[e] = v
        return v

    return mag(expr)


def needs_extended(f: Any, grad: list) -> bool:
    """Whether f or a gradient component may pass float32's comfortable range within REACH."""
    return max(magnitude_log10(e) for e in (f, *grad)) > LIMIT_LOG10


def _number(x: float) -> str:
    """The extended-range literal of a constant."""
    if x == 0 or not math.isfinite(x):
        return "vec2(0.0, XF_ZERO)" if x == 0 else f"vec2({x}, 0.0)"
    m, e = math.frexp(x)  # x = m 2^e, 0.5 <= |m| < 1
    return f"vec2({m * 2!r}, {float(e - 1)!r})"


_FUNCTIONS = {"sin": "sin", "cos": "cos", "tan": "tan", "asin": "asin", "acos": "acos", "atan": "atan",
              "tanh": "tanh"}


def glsl(expr: Any) -> str:
    """A GLSL vec2 expression (extended range) of a sympy expression in x, y and z (the
    GLSL scope must hold ``vec2 X, Y, Z``: the coordinates in extended range)."""
    import sympy as sp

    def emit(e: Any) -> str:
        if e.is_Symbol:
            return e.name.upper()
        if e.is_Number or isinstance(e, sp.NumberSymbol):
            return _number(float(e))
        if isinstance(e, sp.Add):
            return _fold("xfAdd", [emit(a) for a in e.args])
        if isinstance(e, sp.Mul):
            return _fold("xfMul", [emit(a) for a in e.args])
        if isinstance(e, sp.Pow):
            b, x = e.as_base_exp()
            if x == sp.Rational(1, 2):
                return f"xfSqrt({emit(b)})"
            if x.is_Integer:
                n = abs(int(x))
                if n <= 2 or (n <= 8 and b.is_Symbol):
                    v = _fold("xfMul", [emit(b)] * n)
                else:  # chunks of at most 32 (|m|^32 stays a float); the sign is kept
                    base = emit(b)
                    chunks = [32] * (n // 32) + ([n % 32] if n % 32 else [])
                    v = _fold("xfMul", [f"xfPowi({base}, {float(k)!r})" for k in chunks])
                return v if int(x) > 0 else f"xfDiv(vec2(1.0, 0.0), {v})"
            if not x.is_number:  # b**x = exp(x log b), meant for b > 0 (as GLSL's pow)
                return f"xfExp(xfMul({emit(x)}, xfLog({emit(b)})))"
            return f"xfPow({emit(b)}, {float(x)!r})"
        name = type(e).__name__
        if name in _FUNCTIONS:
            return f"xfNorm({_FUNCTIONS[name]}(xfVal({emit(e.args[0])})), 0.0)"
        if isinstance(e, sp.exp):
            return f"xfExp({emit(e.args[0])})"
        if isinstance(e, sp.log):
            return f"xfLog({emit(e.args[0])})"
        if isinstance(e, sp.Abs):
            return f"xfAbs({emit(e.args[0])})"
        if isinstance(e, sp.sign):  # the derivative of an abs(): the sign of the mantissa
            return f"xfNorm(sign({emit(e.args[0])}.x), 0.0)"
        if isinstance(e, (sp.sinh, sp.cosh)):
            a = emit(e.args[0])
            other = f"xfExp(xfNeg({a}))"
            half = f"xfAdd(xfExp({a}), {other if isinstance(e, sp.cosh) else f'xfNeg({other})'})"
            return f"xfMul(vec2(1.0, -1.0), {half})"
        raise ValueError(f"cannot write {name} in extended range")

    return emit(expr)


def _fold(fn: str, parts: list[str]) -> str:
    """``fn`` applied pairwise over ``parts`` as a balanced tree (shallow nesting)."""
    while len(parts) > 1:
        parts = [f"{fn}({parts[i]}, {parts[i + 1]})" if i + 1 < len(parts) else parts[i]
                 for i in range(0, len(parts), 2)]
    return parts[0]
