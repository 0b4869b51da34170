"""Implicit surfaces from an expression, and rational parametric surfaces implicitized
with a Groebner basis (sympy).

An implicit f(x, y, z) = 0 is rendered through f / |grad f|, a first-order distance
estimate with the gradient derived symbolically (in extended-range floats where f may
overflow float32, see :mod:`.xfloat`). It is no guaranteed bound (exactness
"implicit"), so the Newton methods or the reference march render it.
"""
from __future__ import annotations

import functools
import time
import zlib
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from .. import expr as ex
from ..errors import ParameterError
from ..values.float32 import FLOAT32_MAX
from . import xfloat
from .base import IMPLICIT, Node

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

MAX_TERMS = 400  # an implicit equation bigger than this is refused as too large


@functools.lru_cache(maxsize=None)
def _xyz() -> tuple[Any, Any, Any]:
    """The real symbols x, y, z (sympy is imported only when an expression node is built)."""
    return ex.sympy_module("implicit surfaces").symbols("x y z", real=True)


@functools.lru_cache(maxsize=None)
def _printer_class() -> type:
    from sympy.printing.glsl import GLSLPrinter

    class _Printer(GLSLPrinter):
        """sympy's GLSL printer, but integer powers become products, or pow() of the absolute
        value with the sign restored for odd powers (GLSL's pow(x, y) is undefined for
        negative x), and every number is a float literal."""

        def _print_Pow(self, expr: Any) -> str:  # noqa: N802 - sympy's naming
            import sympy as sp
            base, exp = expr.as_base_exp()
            if exp.is_Integer and 0 < abs(int(exp)) <= 8:
                prod = " * ".join([f"({self._print(base)})"] * abs(int(exp)))
                return f"({prod})" if exp > 0 else f"(1.0 / ({prod}))"
            if exp.is_Integer and int(exp) != 0:
                b, n = self._print(base), abs(int(exp))
                mag = f"pow(abs({b}), {float(n)!r})"
                val = mag if n % 2 == 0 else f"(sign({b}) * {mag})"
                return val if exp > 0 else f"(1.0 / {val})"
            if exp == sp.Rational(1, 2):
                return f"sqrt({self._print(base)})"
            if not exp.is_number:  # a variable exponent (GLSL's pow, meant for a base > 0)
                return f"pow({self._print(base)}, {self._print(exp)})"
            return f"pow({self._print(base)}, {self._print(sp.Float(exp))})"

        def _print_Integer(self, expr: Any) -> str:  # noqa: N802
            return f"{int(expr)}.0"

        def _print_Rational(self, expr: Any) -> str:  # noqa: N802
            return repr(float(expr))

        def _print_Exp1(self, expr: Any) -> str:  # noqa: N802 - the constant E
            return repr(float(expr))

        # GLSL (3.30 and ES 3.00) has the hyperbolic functions; sympy's printer does not know it
        def _print_sinh(self, expr: Any) -> str:
            return f"sinh({self._print(expr.args[0])})"

        def _print_cosh(self, expr: Any) -> str:
            return f"cosh({self._print(expr.args[0])})"

        def _print_tanh(self, expr: Any) -> str:
            return f"tanh({self._print(expr.args[0])})"

    return _Printer


def glsl(expr: Any, what: str) -> str:
    """GLSL for a sympy expression; a printer failure names the unsupported function."""
    try:
        return _printer_class()().doprint(expr)
    except Exception as exc:  # sympy raises several kinds here; all mean "cannot print"
        name = ex.unsupported_function(expr) or type(exc).__name__
        raise ParameterError(f"{what}: cannot write {name} in GLSL; use only "
                             f"{', '.join(sorted(ex.FUNCTIONS))} and + - * / **") from None


def _extended_glsl(exprs: list) -> list[str]:
    """The extended-range GLSL of f and its gradient, or ParameterError naming what cannot be written."""
    try:
        return [xfloat.glsl(e) for e in exprs]
    except ValueError as exc:
        raise ParameterError(f"implicit: {exc}; use only {', '.join(sorted(ex.FUNCTIONS))} and + - * / **") from None


def _check_float32(g: Any, what: str) -> None:
    """Refuse a constant of ``g`` that float32 (the shader's arithmetic) cannot hold."""
    import sympy as sp
    for atom in g.atoms(sp.Number):
        if not abs(float(atom)) <= FLOAT32_MAX:
            raise ParameterError(f"{what}: the constant {float(atom):.6g} does not fit in float32 "
                                 f"(at most {FLOAT32_MAX:.3g}), in which the shader computes")


def _stable_name(prefix: str, key: tuple) -> str:
    """A helper-function name that is the same in every process (hash() is salted)."""
    return f"{prefix}{zlib.crc32(repr(key).encode()) % 10**8}"


def _param_symbols(names: Sequence[str]) -> dict[str, Any]:
    """The sympy symbols of named parameters (by name; distinct from x, y, z)."""
    import sympy as sp
    return {n: sp.Symbol(n, real=True, finite=True) for n in names}


def _parse(expr: Any, what: str = "implicit", params: dict[str, Any] | None = None) -> Any:
    X, Y, Z = _xyz()
    import sympy as sp
    names = {"x": X, "y": Y, "z": Z, **(params or {})}
    if isinstance(expr, str):
        e = ex.parse_sympy(expr, names, what)
    elif isinstance(expr, sp.Expr):
        ex.check_sympy(expr, what)
        e = expr.subs({s: names[s.name] for s in expr.free_symbols if s.name in names})
        if params:  # a saved parametric's equation names its parameters as plain symbols
            e = e.subs({s: params[s.name] for s in e.free_symbols if s.name in params and s not in params.values()})
    else:
        raise ParameterError(f"{what}: expected a string or a sympy expression, got {type(expr).__name__}")
    extra = sorted(s.name for s in e.free_symbols if s not in (X, Y, Z, *(params or {}).values()))
    if extra:
        named = f" and the named parameters {', '.join(params)}" if params else ""
        raise ParameterError(f"{what}: unknown symbol(s) {', '.join(extra)} in {expr!r}; use x, y and z{named}")
    ex.check_derivative_size(e, what)
    return e


class Implicit(Node):
    """The surface f(x, y, z) = 0 (solid where f < 0), as f / |grad f|."""

    kind = "implicit"

    def __init__(self, expr: Any, bounds: tuple[Sequence[float], Sequence[float]] | None = None,
                 params: Any = None) -> None:
        X, Y, Z = _xyz()
        import sympy as sp
        from .named_params import named_params
        named = named_params(self.kind, params)
        syms = _param_symbols([n for n, _ in named])
        f = _parse(expr, params=syms)
        grad = [sp.diff(f, s) for s in (X, Y, Z)]
        if all(g == 0 for g in grad):
            raise ParameterError(f"implicit: {f} does not depend on x, y or z")
        lo, hi = _box("implicit", bounds)
        # in the GLSL a named parameter is an argument of the node's function: par0, par1, ...
        glsl_names = {syms[n]: sp.Symbol(f"par{i}", real=True) for i, (n, _) in enumerate(named)}
        fg = f.subs(glsl_names) if named else f
        gradg = [g.subs(glsl_names) for g in grad] if named else grad
        self._glsl = (glsl(fg, "implicit"), [glsl(g, "implicit: the gradient") for g in gradg])
        super().__init__((), expr=str(f), **{f"param {n}": val for n, val in named})
        self.f, self.grad, self.lo, self.hi = f, grad, lo, hi
        self.named = named
        self._np = sp.lambdify((X, Y, Z, *syms.values()), [f, *grad], "numpy")
        # written with extended-range floats where f or grad f may overflow float32
        self.extended = xfloat.needs_extended(f, grad)
        self._xglsl = _extended_glsl([fg, *gradg]) if self.extended else None

    @property
    def exactness(self) -> str:
        return IMPLICIT

    def label(self) -> str:
        text = str(self.f)
        return f"implicit({text if len(text) < 60 else text[:57] + '...'})"

    def _emit(self, em: "Emitter", p: str) -> str:
        # with named parameters the function is the same for every value (live or not): its
        # name follows the expression and the names, not the values
        names = [n for n, _ in self.named]
        name = _stable_name("implicit", (str(self.f), tuple(names))) if names else _stable_name("implicit", self.key)
        args = "".join(f", float par{i}" for i in range(len(names)))
        what_params = f"; {', '.join(f'par{i} = {n}' for i, n in enumerate(names))}" if names else ""
        if self.extended:
            em.require("xfloat")
            f, gx, gy, gz = self._xglsl
            pars = "".join(f"    vec2 PAR{i} = xfNorm(par{i}, 0.0);\n" for i in range(len(names)))
            body = (f"float {name}(vec3 p{args}) {{\n    vec2 X = xfNorm(p.x, 0.0);\n    vec2 Y = xfNorm(p.y, 0.0);\n"
                    f"    vec2 Z = xfNorm(p.z, 0.0);\n{pars}    return xfRatio({f},\n        {gx},\n        {gy},\n"
                    f"        {gz});\n}}")
            what = "in extended range: its values overflow float32"
        else:
            body = (f"float {name}(vec3 p{args}) {{\n    float x = p.x;\n    float y = p.y;\n    float z = p.z;\n"
                    f"    float f = {self._glsl[0]};\n"
                    f"    vec3 g = vec3({', '.join(self._glsl[1])});\n"
                    f"    return f / max(length(g), 1e-12);\n}}")
            what = "an implicit surface"
        em.helper(name, f"// f = {em.comment(self.f)}  ({what}, as f / |grad f|{what_params})\n{body}")
        values = "".join(f", {em.num(val)}" for _, val in self.named)
        return em.with_color(em.assign("float", f"{name}({em.point(p)}{values})"))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        with np.errstate(over="ignore", invalid="ignore"):
            d = self._ratio(p, np.float64)
            bad = ~np.isfinite(d) & np.all(np.isfinite(p), axis=-1)
            if bad.any():  # f or grad f overflows float64 (x**64 beyond 6e4): again in long double
                d[bad] = self._ratio(p[bad].astype(np.longdouble), np.longdouble)
        return d

    def _ratio(self, p: np.ndarray, dtype: type) -> np.ndarray:
        """f / |grad f| at ``p`` computed in ``dtype``, as float64."""
        named = [dtype(float(val)) for _, val in self.named]
        vals = [np.array(np.broadcast_to(np.asarray(v, dtype=dtype), p.shape[:-1]))
                for v in self._np(p[..., 0], p[..., 1], p[..., 2], *named)]
        big = np.maximum(np.maximum(np.abs(vals[1]), np.abs(vals[2])), np.abs(vals[3]))
        unit = np.where(big > 0, big, 1.0)  # |grad f| without squaring it (no overflow)
        g = big * np.sqrt((vals[1] / unit) ** 2 + (vals[2] / unit) ** 2 + (vals[3] / unit) ** 2)
        return np.asarray(vals[0] / np.maximum(g, 1e-12), dtype=np.float64)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.lo, self.hi


def implicit(expr: Any, bounds: tuple[Sequence[float], Sequence[float]] | None = None,
             params: Any = None) -> Implicit:
    """The surface ``expr`` = 0 in x, y, z (solid where ``expr`` < 0), rendered as f / |grad f|.

    Args:
        expr: a string in the safe expression grammar (:mod:`sdfgl.expr`: numbers, x, y, z,
            pi, E, + - * / ** ^ and sin cos tan asin acos atan sinh cosh tanh exp log sqrt abs)
            or a sympy expression over those. Nothing in it is run as code.
        bounds: (lo, hi) corners of a box that clips the rays (strongly advised), or None.
        params: named parameters the expression may use besides x, y, z: (name, value)
            pairs or a dict, each value a number or a live scalar (``sg.param``: moving it
            needs no recompile). Names are identifiers other than x, y, z, s, t, u, p, pi,
            E and the function names (:mod:`sdfgl.nodes.named_params`).

    Implicit: no distance guarantee; the default method ("auto") renders it with
    ``"newton"`` (or pass ``"forward_newton"``). A field that may overflow float32 (a high
    power such as ``x**64``, an ``exp``) is evaluated in extended range (``node.extended``;
    :mod:`sdfgl.nodes.xfloat`). Needs the ``implicit`` extra (sympy).

    Example:
        >>> s = sg.implicit("x**2 + y**2 + z**2 - 1", bounds=((-1, -1, -1), (1, 1, 1)))
        >>> float(s.distance((2, 0, 0)))
        0.75
        >>> r = sg.param(1.0, "r", range=(0.5, 2.0))
        >>> ball = sg.implicit("x^2 + y^2 + z^2 - r^2", params={"r": r})
        >>> r.value = 2.0
        >>> float(ball.distance((3, 0, 0)))
        0.8333333333333334
    """
    if params is None:
        return Implicit(expr, bounds)
    return Implicit(expr, bounds, _pairs(params))


def _pairs(params: Any) -> Any:
    """A dict of named parameters as [name, value] pairs (what a scene document holds)."""
    return [[k, val] for k, val in params.items()] if isinstance(params, dict) else params


def _box(what: str, bounds: Any) -> tuple[np.ndarray, np.ndarray]:
    """``bounds`` (lo, hi) as two float 3-vectors with lo < hi (None: unbounded)."""
    if bounds is None:
        return np.full(3, -np.inf), np.full(3, np.inf)
    try:
        lo, hi = (np.asarray(b, dtype=float) for b in bounds)
        ok = lo.shape == (3,) and hi.shape == (3,) and not np.isnan(lo).any() and not np.isnan(hi).any() \
            and bool(np.all(lo < hi))
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ParameterError(f"{what}: 'bounds' must be two 3-vectors (lo, hi) with lo < hi, got {bounds!r}")
    return lo, hi


def _groebner_worker(gens: list, syms: tuple, out: Any) -> None:
    import sympy as sp
    basis = sp.groebner(gens, *syms, order="lex")
    elim = set(syms[:3])
    out.put([g for g in basis.exprs if not (elim & g.free_symbols)])


def implicitize(x: Any, y: Any, z: Any, timeout: float = 20.0, params: Sequence[str] = ()) -> tuple[Any, float]:
    """The implicit equation F(x, y, z) = 0 of the rational surface (x(s, t), y(s, t), z(s, t)).

    Eliminates s and t from <D x - Nx, D y - Ny, D z - Nz, 1 - u D> (D the common
    denominator) with a lex Groebner basis. Returns (F, seconds). Raises ParameterError
    if it does not finish within ``timeout`` seconds, finds no surface equation, or the
    equation has more than MAX_TERMS terms. ``params`` names parameters the components may
    use (kept as symbols: the equation holds for their values)."""
    X, Y, Z = _xyz()
    import sympy as sp
    s, t, u = sp.symbols("s t u")
    syms = _param_symbols(list(params))
    if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not 0 < timeout <= 3600:
        raise ParameterError(f"parametric: 'timeout' must be a number of seconds in (0, 3600], got {timeout!r}")
    comps = []
    for name, e in (("x", x), ("y", y), ("z", z)):
        what = f"parametric: {name}"
        if isinstance(e, str):
            c = ex.parse_sympy(e, {"s": s, "t": t, **syms}, what)
        elif isinstance(e, (int, float)) and not isinstance(e, bool):
            c = sp.Float(e) if isinstance(e, float) else sp.Integer(e)
        elif isinstance(e, sp.Expr):
            ex.check_sympy(e, what)
            c = e
        else:
            raise ParameterError(f"{what}: expected a string, number or sympy expression, got {type(e).__name__}")
        extra = sorted(v.name for v in c.free_symbols if v.name not in ("s", "t", *syms))
        if extra:
            named = f" and the named parameters {', '.join(syms)}" if syms else ""
            raise ParameterError(f"parametric: {name} uses unknown symbol(s) {', '.join(extra)}; use s and t{named}")
        c = c.subs({v: {"s": s, "t": t, **syms}[v.name] for v in c.free_symbols})
        num, den = sp.fraction(sp.together(c))
        if not (num.is_polynomial(s, t) and den.is_polynomial(s, t)):
            raise ParameterError(f"parametric: {name} = {c} is not a rational function of s and t")
        comps.append((num, den))
    d = sp.lcm_list([den for _, den in comps])
    parts = [d * c - sp.cancel(num * d / den) for c, (num, den) in zip((X, Y, Z), comps)] + [1 - u * d]
    for part in parts:
        ex.check_expansion(part, "parametric")
    gens = [sp.expand(g) for g in parts]
    import multiprocessing as mp
    ctx = mp.get_context("fork")
    out = ctx.Queue()
    proc = ctx.Process(target=_groebner_worker, args=(gens, (u, s, t, X, Y, Z, *syms.values()), out), daemon=True)
    t0 = time.perf_counter()
    proc.start()
    proc.join(timeout)
    if proc.is_alive():
        proc.kill()
        proc.join()
        raise ParameterError(f"parametric: implicitization did not finish within {timeout:g} s "
                             f"(the Groebner basis is too large); pass a larger timeout or an implicit form")
    elapsed = time.perf_counter() - t0
    found = out.get() if not out.empty() else None
    if found is None:
        raise ParameterError("parametric: the Groebner computation failed")
    if len(found) != 1:
        # a rational surface's elimination ideal is principal: one equation; several (or
        # none) mean the image is a curve or a point
        raise ParameterError(f"parametric: the elimination gave {len(found)} equations in x, y, z, not one: "
                             f"the parametrization does not describe a surface (a curve or a point?)")
    found = [g for g in found if g.free_symbols & {X, Y, Z}]  # none holds of the parameters alone
    if len(found) != 1:
        raise ParameterError(f"parametric: the elimination gave {len(found)} equations in x, y, z, not one: "
                             f"the parametrization does not describe a surface for every parameter value")
    eq = found[0]
    if ex.expansion_terms(eq) > MAX_TERMS or len(sp.Add.make_args(sp.expand(eq))) > MAX_TERMS:
        raise ParameterError(f"parametric: the implicit equation has more than {MAX_TERMS} terms; too large to render")
    return eq, elapsed


def parametric(x: Any, y: Any, z: Any, bounds: tuple[Sequence[float], Sequence[float]] | None = None,
               timeout: float = 20.0, params: Any = None) -> Implicit:
    """The rational parametric surface (x(s, t), y(s, t), z(s, t)), implicitized with a Groebner
    basis (in a subprocess, so a basis that blows up ends with an error after ``timeout``).

    Args:
        x: x as a rational function of s and t (a string in the safe grammar, a number or a sympy expression).
        y: likewise.
        z: likewise.
        bounds: (lo, hi) box that clips the rays, or None.
        timeout: seconds the implicitization may take, in (0, 3600].
        params: named parameters the components may use besides s and t (as for
            :func:`implicit`); they stay symbols in the implicit equation, so a live one
            moves the surface without a new implicitization or recompile.

    Implicit (see :func:`implicit`). ``node.implicitization_s`` keeps the time it took.

    Example:
        >>> sg.parametric("s", "t", "s**2 + t**2").label()
        'implicit(x**2 + y**2 - z)'
    """
    from .named_params import named_params
    names = [n for n, _ in named_params("parametric", params)]
    eq, seconds = implicitize(x, y, z, timeout, names)
    node = Implicit(eq, bounds) if params is None else Implicit(eq, bounds, _pairs(params))
    node.implicitization_s = seconds  # type: ignore[attr-defined]
    return node


class DisplaceExpr(Node):
    """child + g(x, y, z) for a displacement function g given as an expression.

    ``lipschitz`` is a bound of |grad g| that the caller vouches for; without it the bound
    is taken from sympy's maximum of |grad g| over the child's bounding box when sympy can
    find one in closed form, else the node is refused. The field is divided by
    1 + lipschitz, in this subtree only."""

    kind = "displace_expr"

    def __init__(self, child: Node, expr: Any, lipschitz: float | None = None) -> None:
        if not isinstance(child, Node):
            raise ParameterError(f"{self.kind}: the operand must be an sdfgl node, got {type(child).__name__}")
        if child.exactness == IMPLICIT:
            raise ParameterError(f"{self.kind}: the child {child.label()} is implicit (no distance bound)")
        X, Y, Z = _xyz()
        import sympy as sp
        if isinstance(expr, bool):
            raise ParameterError(f"{self.kind}: expected an expression string, got {expr!r}")
        g = _parse(expr, self.kind) if not isinstance(expr, (int, float)) else sp.Float(expr)
        _check_float32(g, self.kind)
        grad = [sp.diff(g, s) for s in (X, Y, Z)]
        if lipschitz is None:
            lipschitz = _gradient_bound(grad)
            if lipschitz is None:
                raise ParameterError(f"{self.kind}: cannot bound the gradient of {g} in closed form; pass "
                                     f"lipschitz= (a bound of |grad g| you vouch for)")
        elif (isinstance(lipschitz, bool) or not isinstance(lipschitz, (int, float))
              or not 0 <= lipschitz <= FLOAT32_MAX):
            raise ParameterError(f"{self.kind}: 'lipschitz' must be a number in [0, {FLOAT32_MAX:.3g}], "
                                 f"got {lipschitz!r}")
        super().__init__((child,), expr=str(g), lipschitz=float(lipschitz))
        if not np.isfinite(float(lipschitz)):
            raise ParameterError(f"{self.kind}: 'lipschitz' must be finite, got {lipschitz!r}")
        self._glsl = glsl(g, self.kind)
        self.child, self.g, self.factor = child, g, 1.0 + float(lipschitz)
        self._np = sp.lambdify((X, Y, Z), g, "numpy")
        self._grow = _abs_bound(g)

    @property
    def exactness(self) -> str:
        return "bound"

    def label(self) -> str:
        return f"displace_expr({self.g})"

    def _emit(self, em: "Emitter", p: str) -> str:
        pt = em.point(p)
        name = _stable_name("displacement", self.key)
        em.helper(name, f"float {name}(vec3 p) {{\n    float x = p.x;\n    float y = p.y;\n    float z = p.z;\n"
                        f"    return {self._glsl};\n}}")
        r = self.child.emit(em, p)
        scale = em.num(1.0 / self.factor)
        if em.mode == "dist":
            return em.assign("float", f"({r} + {name}({pt})) * {scale}")
        return em.assign("vec4", f"vec4({r}.rgb, ({r}.w + {name}({pt})) * {scale})")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        g = np.broadcast_to(np.asarray(self._np(p[..., 0], p[..., 1], p[..., 2]), dtype=np.float64), p.shape[:-1])
        return (self.child._distance(p) + g) / self.factor

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        if self._grow is None:
            return np.full(3, -np.inf), np.full(3, np.inf)
        return lo - self._grow, hi + self._grow


def _abs_bound(g: Any) -> float | None:
    """A bound of |g| when g is built from sin, cos, numbers, products and sums."""
    import sympy as sp
    if g.is_number:
        return abs(float(g))
    if isinstance(g, (sp.sin, sp.cos)):
        return 1.0
    if isinstance(g, sp.Mul):
        parts = [_abs_bound(a) for a in g.args]
        return None if any(x is None for x in parts) else float(np.prod(parts))
    if isinstance(g, sp.Add):
        parts = [_abs_bound(a) for a in g.args]
        return None if any(x is None for x in parts) else float(sum(parts))
    return None


def _gradient_bound(grad: list) -> float | None:
    """|grad g| <= sqrt(sum of squared component bounds), when each component is bounded."""
    import sympy as sp
    parts = []
    for comp in grad:
        ex.check_expansion(comp, "displace_expr")
        b = _abs_bound(sp.expand(comp))
        if b is None:
            return None
        parts.append(b)
    return float(np.sqrt(sum(x * x for x in parts)))


def displace_expr(node: Node, expr: Any, lipschitz: float | None = None) -> DisplaceExpr:
    """Displace ``node`` by a function g(x, y, z) given as an expression: the field f + g.

    Args:
        node: a node with a distance bound (not implicit).
        expr: g as a string in the safe grammar (see :func:`implicit`) or a sympy expression.
        lipschitz: a bound of |grad g| you vouch for; None derives one in closed form for
            sums and products of sin, cos and numbers (else it is refused).

    A bound: the field is divided by 1 + lipschitz, in this subtree only.

    Example:
        >>> s = sg.displace_expr(sg.sphere(1), "0.05*sin(8*x)")
        >>> s.exactness
        'bound'
    """
    return DisplaceExpr(node, expr, lipschitz)
