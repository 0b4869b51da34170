"""The one parser for expression strings: implicit surfaces, displacements, parametric
surfaces and live-parameter expressions in scene documents.

It never calls ``eval``, ``exec`` or ``sympify`` on a string. A small tokenizer and a
recursive-descent parser accept this grammar and nothing else::

    expr    := term (("+" | "-") term)*
    term    := unary (("*" | "/") unary)*
    unary   := ("+" | "-") unary | power
    power   := atom (("**" | "^") unary)?          (right-associative)
    atom    := NUMBER | NAME | NAME "(" expr ("," expr)* ")" | "(" expr ")"

NAME is a variable the caller allows (``x, y, z`` for fields, ``s, t`` for parametric
surfaces, parameter names for live expressions), a constant (``pi``, ``E``) or one of the
functions in :data:`FUNCTIONS`. Attribute access, subscripts, calls of anything else,
keywords, strings and lambdas are syntax errors here by construction.

Limits (each refused with a :class:`~sdfgl.errors.ParameterError` that says which, well
under 0.1 s): :data:`MAX_LENGTH` characters, :data:`MAX_DEPTH` levels of nesting,
:data:`MAX_DIGITS` digits in a number, integer exponents up to :data:`MAX_EXPONENT`, constant
powers and every other constant part up to 10**:data:`MAX_MAGNITUDE` (and real: ``sqrt(-1)`` and
``log(0)`` are refused), towers of exponentials up to :data:`MAX_TOWER` high, and
:func:`check_expansion` refuses an ``expand()``
that would make more than :data:`MAX_TERMS` terms (a 40th power of a sum, say) before
sympy starts on it.

The tree is plain tuples, built once and turned into sympy objects
(:func:`parse_sympy`) or live-parameter expressions (:func:`parse_live`) directly.
"""
from __future__ import annotations

import math
import re
from typing import Any, Callable, Iterable, Mapping

from .errors import ParameterError, SdfglError

MAX_LENGTH = 2000     # characters in one expression
MAX_DEPTH = 40        # nesting of parentheses, unary signs, powers and calls
MAX_DIGITS = 40       # digits in one number literal
MAX_EXPONENT = 64     # largest |integer exponent| of a non-constant base
MAX_MAGNITUDE = 300   # a constant power may reach 10**300
MAX_TERMS = 2000      # terms an expansion may produce
MAX_NODES = 5000      # operations in a sympy expression handed in directly
MAX_GRADIENT = 6000   # operations in one partial derivative of a field (estimated before sympy works)
MAX_TOWER = 4         # exponentials of a variable stacked at most this high (exp(exp(exp(exp(x)))))

# name in the string -> sympy class name (imported lazily) and the GLSL it prints to
FUNCTIONS = {
    "sin": "sin", "cos": "cos", "tan": "tan", "asin": "asin", "acos": "acos", "atan": "atan",
    "sinh": "sinh", "cosh": "cosh", "tanh": "tanh", "exp": "exp", "log": "log", "sqrt": "sqrt",
    "abs": "Abs",
}
CONSTANTS = {"pi": "pi", "E": "E"}

_TOKEN = re.compile(r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)|(?P<name>[A-Za-z_][A-Za-z_0-9]*)"
                    r"|(?P<op>\*\*|[-+*/^(),]))")

Tree = tuple  # ("num", text) | ("name", text) | ("call", name, [args]) | (op, a[, b])


def sympy_module(what: str = "expression") -> Any:
    """sympy, or a clear error saying which extra installs it (it is imported only here)."""
    try:
        import sympy
    except ImportError:
        raise SdfglError(f"{what} needs sympy: pip install 'sdfgl[implicit]'") from None
    return sympy


def _fail(what: str, text: str, msg: str) -> ParameterError:
    shown = text if len(text) <= 80 else text[:77] + "..."
    return ParameterError(f"{what}: {msg} in {shown!r}")


def tokenize(text: str, what: str = "expression") -> list[tuple[str, str, int]]:
    """(kind, text, position) tokens; anything outside the grammar's alphabet is refused."""
    if not isinstance(text, str):
        raise ParameterError(f"{what}: expected a string, got {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ParameterError(f"{what}: expression is {len(text)} characters long (limit {MAX_LENGTH})")
    out, pos = [], 0
    end = len(text.rstrip())
    while pos < end:
        m = _TOKEN.match(text, pos)
        if m is None:
            ch = text[pos:].lstrip()[:1]
            hint = " (attribute access is not allowed)" if ch == "." else ""
            raise _fail(what, text, f"unexpected character {ch!r} at position {pos}{hint}")
        kind = m.lastgroup or "op"
        out.append((kind, m.group(kind), m.start(kind)))
        pos = m.end()
    return out


class _Parser:
    def __init__(self, text: str, what: str) -> None:
        self.text, self.what = text, what
        self.toks = tokenize(text, what)
        self.i = 0
        self.depth = 0

    def peek(self) -> str | None:
        return self.toks[self.i][1] if self.i < len(self.toks) else None

    def take(self, want: str | None = None) -> tuple[str, str, int]:
        if self.i >= len(self.toks):
            raise _fail(self.what, self.text, "unexpected end of expression" + (f", expected {want!r}" if want else ""))
        tok = self.toks[self.i]
        if want is not None and tok[1] != want:
            raise _fail(self.what, self.text, f"expected {want!r} at position {tok[2]}, got {tok[1]!r}")
        self.i += 1
        return tok

    def nest(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise _fail(self.what, self.text, f"nesting deeper than {MAX_DEPTH} levels")

    def parse(self) -> Tree:
        if not self.toks:
            raise ParameterError(f"{self.what}: the expression is empty")
        tree = self.expr()
        if self.i < len(self.toks):
            tok = self.toks[self.i]
            raise _fail(self.what, self.text, f"unexpected {tok[1]!r} at position {tok[2]}")
        return tree

    def _left_assoc(self, ops: dict[str, str], operand: Callable[[], Tree]) -> Tree:
        node = operand()
        while self.peek() in ops:
            node = (ops[self.take()[1]], node, operand())
        return node

    def expr(self) -> Tree:
        return self._left_assoc({"+": "add", "-": "sub"}, self.term)

    def term(self) -> Tree:
        return self._left_assoc({"*": "mul", "/": "div"}, self.unary)

    def unary(self) -> Tree:
        if self.peek() in ("+", "-"):
            op = self.take()[1]
            self.nest()
            inner = self.unary()
            self.depth -= 1
            return ("neg", inner) if op == "-" else inner
        return self.power()

    def power(self) -> Tree:
        base = self.atom()
        if self.peek() in ("**", "^"):
            self.take()
            self.nest()
            exp = self.unary()
            self.depth -= 1
            return ("pow", base, exp)
        return base

    def atom(self) -> Tree:
        kind, tok, pos = self.take()
        if kind == "num":
            if len(re.sub(r"[^0-9]", "", tok)) > MAX_DIGITS:
                raise _fail(self.what, self.text, f"number at position {pos} has more than {MAX_DIGITS} digits")
            return ("num", tok)
        if kind == "name":
            if self.peek() == "(":
                self.take("(")
                self.nest()
                args = [self.expr()]
                while self.peek() == ",":
                    self.take(",")
                    args.append(self.expr())
                self.take(")")
                self.depth -= 1
                return ("call", tok, args)
            return ("name", tok)
        if tok == "(":
            self.nest()
            inner = self.expr()
            self.take(")")
            self.depth -= 1
            return inner
        raise _fail(self.what, self.text, f"unexpected {tok!r} at position {pos}")


def parse_tree(text: str, what: str = "expression") -> Tree:
    """The syntax tree of ``text`` (tuples), or ParameterError naming what is wrong."""
    return _Parser(text, what).parse()


def _postorder(tree: Tree) -> Iterable[Tree]:
    """Subtrees children-first, without recursion."""
    stack: list[tuple[Tree, bool]] = [(tree, False)]
    while stack:
        node, done = stack.pop()
        if done or node[0] in ("num", "name"):
            yield node
            continue
        stack.append((node, True))
        kids = node[2] if node[0] == "call" else node[1:]
        stack.extend((k, False) for k in reversed(kids))


def _check_calls(tree: Tree, what: str, text: str) -> None:
    for node in _postorder(tree):
        if node[0] == "call" and node[1] not in FUNCTIONS:
            raise _fail(what, text, f"unknown function {node[1]!r}; allowed: {', '.join(sorted(FUNCTIONS))}")


def _fold(tree: Tree, leaf: Callable[[Tree], Any], combine: Callable[[Tree, list], Any]) -> Any:
    values: dict[int, Any] = {}
    for node in _postorder(tree):
        if node[0] in ("num", "name"):
            values[id(node)] = leaf(node)
        else:
            kids = node[2] if node[0] == "call" else node[1:]
            values[id(node)] = combine(node, [values[id(k)] for k in kids])
    return values[id(tree)]


def parse_sympy(text: str, variables: Mapping[str, Any], what: str = "expression") -> Any:
    """``text`` as a sympy expression over ``variables`` (name -> sympy Symbol).

    Besides the grammar's limits, every constant part is evaluated in floats as it is built
    (:func:`constant_value`) and the result is held to :func:`check_sympy`'s bounds, so a
    value that is undefined, complex or past float range, and a tower of exponentials, are
    refused before sympy prints or differentiates anything."""
    sp = sympy_module(what)
    tree = parse_tree(text, what)
    _check_calls(tree, what, text)

    def leaf(node: Tree) -> tuple[Any, float | None]:
        if node[0] == "num":
            tok = node[1]
            value = sp.Integer(int(tok)) if tok.isdigit() else sp.Float(tok)
            return value, constant_value(node, [], what, text)
        name = node[1]
        if name in variables:
            return variables[name], None
        if name in CONSTANTS:
            return getattr(sp, CONSTANTS[name]), constant_value(node, [], what, text)
        if name in FUNCTIONS:
            raise _fail(what, text, f"function {name!r} needs arguments, e.g. {name}(x)")
        raise _fail(what, text, f"unknown symbol(s) {name}; use {', '.join(sorted(variables))} (and pi, E)")

    def combine(node: Tree, kids: list) -> tuple[Any, float | None]:
        op = node[0]
        a = [k[0] for k in kids]
        consts = [k[1] for k in kids]
        if op == "call":
            name = node[1]
            if name not in FUNCTIONS:
                raise _fail(what, text, f"unknown function {name!r}; allowed: {', '.join(sorted(FUNCTIONS))}")
            if len(a) != 1:
                raise _fail(what, text, f"{name}() takes one argument, got {len(a)}")
            value = getattr(sp, FUNCTIONS[name])(a[0])
        elif op == "neg":
            value = -a[0]
        elif op == "pow":
            value = _power(a[0], a[1], what, text)
        else:
            if op == "div" and consts[1] == 0:
                raise _fail(what, text, "division by zero")
            x, y = a
            value = {"add": lambda: x + y, "sub": lambda: x - y, "mul": lambda: x * y, "div": lambda: x / y}[op]()
        return value, constant_value(node, consts, what, text)

    result = _fold(tree, leaf, combine)[0]
    check_sympy(result, what)  # what sympy made of it: e.g. (x**60)**60 is x**3600
    return result


_FLOAT_FUNCTIONS: dict[str, Callable[[float], float]] = {
    "sin": math.sin, "cos": math.cos, "tan": math.tan, "asin": math.asin, "acos": math.acos, "atan": math.atan,
    "sinh": math.sinh, "cosh": math.cosh, "tanh": math.tanh, "exp": math.exp, "log": math.log,
    "sqrt": math.sqrt, "abs": abs,
}
_FLOAT_OPS: dict[str, Callable[..., float]] = {
    "neg": lambda a: -a, "add": lambda a, b: a + b, "sub": lambda a, b: a - b, "mul": lambda a, b: a * b,
    "div": lambda a, b: a / b, "pow": math.pow,
}


def constant_value(node: Tree, kids: list[float | None], what: str, text: str) -> float | None:
    """The float value of ``node`` when it and its operands ``kids`` (their values, None for
    a part that depends on a variable) are constant; None otherwise. A constant that is
    undefined or not real (``sqrt(-1)``, ``log(0)``, ``acos(2)``, ``(-1)**0.5``) or past
    10**MAX_MAGNITUDE (``E**E**E**E``) is refused, naming it."""
    if node[0] == "num":
        value = float(node[1])
    elif node[0] == "name":
        value = {"pi": math.pi, "E": math.e}[node[1]]
    elif any(k is None for k in kids):
        return None
    else:
        fn = _FLOAT_FUNCTIONS[node[1]] if node[0] == "call" else _FLOAT_OPS[node[0]]
        try:
            value = fn(*kids)
        except OverflowError:
            value = math.inf
        except (ValueError, ZeroDivisionError):  # math's domain errors: log(0), sqrt(-1), (-1)**0.5
            raise _fail(what, text, f"the constant {unparse(node)} is undefined or not a real number") from None
    if not abs(value) <= 10.0 ** MAX_MAGNITUDE:
        raise _fail(what, text, f"the constant {unparse(node)} is beyond 10**{MAX_MAGNITUDE}")
    return value


_SYMBOL = {"add": "+", "sub": "-", "mul": "*", "div": "/", "pow": "**"}


def unparse(tree: Tree) -> str:
    """``tree`` written back as text (for messages), parenthesised where it is not obvious."""
    def combine(node: Tree, kids: list[str]) -> str:
        if node[0] == "call":
            return f"{node[1]}({', '.join(_unwrap(k) for k in kids)})"
        if node[0] == "neg":
            return f"(-{kids[0]})"
        return f"({kids[0]}{_SYMBOL[node[0]]}{kids[1]})"
    return _unwrap(_fold(tree, lambda node: node[1], combine))


def _unwrap(text: str) -> str:
    """``text`` without one pair of parentheses around all of it."""
    if not text.startswith("("):
        return text
    depth = 0
    for i, ch in enumerate(text):
        depth += {"(": 1, ")": -1}.get(ch, 0)
        if depth == 0:
            return text[1:-1] if i == len(text) - 1 else text
    return text


def check_real(expr: Any, what: str) -> None:
    """Refuse a sympy expression that is complex or undefined (``I``, ``zoo``, ``nan``,
    ``oo``), which happens where sympy simplifies, e.g. ``sqrt(-x**2)`` to ``I*|x|``."""
    import sympy as sp
    bad = {sp.I: "not real-valued", sp.zoo: "undefined (a division by zero?)", sp.nan: "undefined",
           sp.oo: "infinite", -sp.oo: "infinite"}
    for atom in expr.atoms():
        if atom in bad:
            shown = str(expr)
            shown = shown if len(shown) <= 80 else shown[:77] + "..."
            raise ParameterError(f"{what}: the expression is {bad[atom]}: {shown}")


def _power(base: Any, exp: Any, what: str, text: str) -> Any:
    """base**exp within the exponent and magnitude limits (checked before sympy computes)."""
    if exp.is_Number:
        if exp.is_Integer and abs(int(exp)) > MAX_EXPONENT:
            raise _fail(what, text, f"exponent {exp} is larger than {MAX_EXPONENT}")
        if not exp.is_Integer and abs(float(exp)) > MAX_EXPONENT:
            raise _fail(what, text, f"exponent {float(exp):g} is larger than {MAX_EXPONENT}")
        if base.is_Number and base != 0:
            mag = abs(float(exp)) * abs(math.log10(abs(float(base))))
            if mag > MAX_MAGNITUDE:
                raise _fail(what, text, f"the constant {base}**{exp} is beyond 10**{MAX_MAGNITUDE}")
    elif base.is_Number and not exp.is_Number and abs(float(base)) > 1e6:
        raise _fail(what, text, f"the base {base} of a variable exponent is too large")
    return base ** exp


def parse_live(text: str, params: Mapping[str, Any], what: str = "expression") -> Any:
    """``text`` as a live-parameter expression over ``params`` (name -> sdfgl Param).

    The result computes with the parameters' current values and becomes GLSL over their
    uniforms; a function named in :data:`FUNCTIONS` works where sdfgl provides it for live
    values (``sdfgl.sin`` etc.)."""
    import sdfgl
    tree = parse_tree(text, what)
    _check_calls(tree, what, text)

    def leaf(node: Tree) -> Any:
        if node[0] == "num":
            tok = node[1]
            return float(tok)
        if node[1] in params:
            return params[node[1]]
        if node[1] == "pi":
            return math.pi
        raise _fail(what, text, f"unknown parameter {node[1]!r}; known: {', '.join(sorted(params)) or 'none'}")

    def combine(node: Tree, a: list) -> Any:
        op = node[0]
        if op == "call":
            fn = getattr(sdfgl, node[1], None) if node[1] in FUNCTIONS else None
            if fn is None:
                raise _fail(what, text, f"function {node[1]!r} is not available for live parameters")
            return fn(*a)
        if op == "neg":
            return -a[0]
        if op == "pow":
            if isinstance(a[1], float) and a[1] == int(a[1]) and 0 < a[1] <= 8:
                out = a[0]
                for _ in range(int(a[1]) - 1):
                    out = out * a[0]
                return out
            raise _fail(what, text, "live expressions take only small whole powers (1..8)")
        x, y = a
        if op == "div" and isinstance(y, float) and y == 0:
            raise _fail(what, text, "division by zero")
        return {"add": lambda: x + y, "sub": lambda: x - y, "mul": lambda: x * y, "div": lambda: x / y}[op]()

    return _fold(tree, leaf, combine)


def check_sympy(expr: Any, what: str) -> None:
    """Refuse a sympy expression given directly that is too big, complex or undefined, has
    a huge integer exponent or constant, a tower of exponentials higher than
    :data:`MAX_TOWER`, or uses a function outside :data:`FUNCTIONS` (naming it). Unknown
    symbols are left to the caller, which knows the names it allows."""
    import sympy as sp
    check_real(expr, what)
    allowed_fns = {getattr(sp, n) for n in FUNCTIONS.values()}
    for n, sub in enumerate(sp.preorder_traversal(expr)):
        if n > MAX_NODES:
            raise ParameterError(f"{what}: the expression has more than {MAX_NODES} operations")
        if isinstance(sub, (sp.Add, sp.Mul, sp.Pow, sp.Symbol, sp.Number, sp.NumberSymbol)):
            if isinstance(sub, sp.Pow) and sub.exp.is_Integer and abs(int(sub.exp)) > MAX_EXPONENT:
                raise ParameterError(f"{what}: exponent {sub.exp} is larger than {MAX_EXPONENT}")
            if isinstance(sub, sp.Number) and not abs(float(sub)) <= 10.0 ** MAX_MAGNITUDE:
                raise ParameterError(f"{what}: the constant {sub} is beyond 10**{MAX_MAGNITUDE}")
            continue
        if sub.func in allowed_fns:
            continue
        name = getattr(sub.func, "__name__", type(sub).__name__)
        raise ParameterError(f"{what}: function {name!r} is not supported; allowed: {', '.join(sorted(FUNCTIONS))}")
    height = tower_height(expr)
    if height > MAX_TOWER:
        raise ParameterError(f"{what}: a tower of {height} exponentials (exp, sinh, cosh or a power with a "
                             f"variable exponent; the limit is {MAX_TOWER})")


def tower_height(expr: Any) -> int:
    """How many exponentials of a variable (exp, sinh, cosh, powers with a variable
    exponent) are stacked in the sympy expression ``expr``, at most."""
    import sympy as sp
    heights: dict[Any, int] = {}
    for sub in sp.postorder_traversal(expr):
        if sub in heights:
            continue
        h = max((heights.get(a, 0) for a in sub.args), default=0)
        if isinstance(sub, (sp.exp, sp.sinh, sp.cosh)) and sub.free_symbols:
            h += 1
        elif isinstance(sub, sp.Pow) and sub.exp.free_symbols:
            h += 1
        heights[sub] = h
    return heights.get(expr, 0)


def expansion_terms(expr: Any) -> float:
    """An upper estimate of the number of terms ``sympy.expand(expr)`` makes, computed
    bottom-up without expanding (a power of a sum of n terms to e makes C(n+e-1, e))."""
    import sympy as sp
    sizes: dict[Any, float] = {}
    for sub in sp.postorder_traversal(expr):
        if sub in sizes:
            continue
        args = [sizes.get(a, 1.0) for a in sub.args]
        if isinstance(sub, sp.Add):
            n = sum(args)
        elif isinstance(sub, sp.Mul):
            n = math.prod(args)
        elif isinstance(sub, sp.Pow) and sub.exp.is_Integer and int(sub.exp) > 1:
            b, e = args[0], int(sub.exp)
            n = math.comb(int(min(b, 1e6)) + e - 1, e) if b > 1 else 1.0
        else:
            n = 1.0
        sizes[sub] = float(min(n, 1e30))
    return sizes.get(expr, 1.0)


def derivative_size(expr: Any) -> float:
    """An upper estimate of the operations in the largest partial derivative of ``expr`` as
    sympy writes it, computed bottom-up without differentiating (the derivative of a
    product of n factors in x is n products of n factors: it grows with the square)."""
    import sympy as sp
    size: dict[Any, float] = {}
    for sub in sp.postorder_traversal(expr):
        if sub not in size:
            size[sub] = 1.0 + sum(size[a] for a in sub.args)
    worst = 0.0
    for v in expr.free_symbols:
        deriv: dict[Any, float] = {}
        for sub in sp.postorder_traversal(expr):
            if sub in deriv:
                continue
            if v not in sub.free_symbols:
                deriv[sub] = 0.0
            elif not sub.args:
                deriv[sub] = 1.0
            elif isinstance(sub, sp.Add):
                deriv[sub] = sum(deriv[a] for a in sub.args)
            elif isinstance(sub, sp.Mul):  # one product per factor in v: that factor's derivative times the rest
                total = sum(size[a] for a in sub.args)
                deriv[sub] = sum(deriv[a] + total - size[a] + 1 for a in sub.args if deriv[a])
            else:  # a power or a function: the outer derivative times the inner one
                deriv[sub] = sum(deriv[a] for a in sub.args) + 2 * size[sub] + 2
        worst = max(worst, deriv[expr])
    return worst


def check_derivative_size(expr: Any, what: str) -> None:
    """Refuse (quickly) an expression whose gradient would exceed :data:`MAX_GRADIENT`
    operations, before sympy differentiates and prints it."""
    n = derivative_size(expr)
    if n > MAX_GRADIENT:
        raise ParameterError(f"{what}: the gradient of the expression would have about {n:.3g} operations "
                             f"(limit {MAX_GRADIENT}); write it in a smaller form")


def check_expansion(expr: Any, what: str) -> None:
    """Refuse (quickly) an expression whose expansion would exceed :data:`MAX_TERMS` terms."""
    n = expansion_terms(expr)
    if n > MAX_TERMS:
        raise ParameterError(f"{what}: expanding the expression would make about {n:.3g} terms "
                             f"(limit {MAX_TERMS}); write it in a smaller form")


def unsupported_function(expr: Any) -> str | None:
    """The name of the first function in ``expr`` outside :data:`FUNCTIONS`, if any
    (e.g. the ``Derivative`` a non-smooth function leaves in a gradient)."""
    import sympy as sp
    allowed_fns = {getattr(sp, n) for n in FUNCTIONS.values()}
    for sub in sp.preorder_traversal(expr):
        if isinstance(sub, (sp.Add, sp.Mul, sp.Pow, sp.Symbol, sp.Number, sp.NumberSymbol)):
            continue
        if sub.func not in allowed_fns:
            if isinstance(sub, sp.Derivative):
                return f"the derivative of {sub.expr}"
            return getattr(sub.func, "__name__", type(sub).__name__)
    return None
