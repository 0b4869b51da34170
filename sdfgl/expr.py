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
powers up to 10**:data:`MAX_MAGNITUDE`, and :func:`check_expansion` refuses an ``expand()``
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
    """``text`` as a sympy expression over ``variables`` (name -> sympy Symbol)."""
    sp = sympy_module(what)
    tree = parse_tree(text, what)
    _check_calls(tree, what, text)

    def leaf(node: Tree) -> Any:
        if node[0] == "num":
            tok = node[1]
            return sp.Integer(int(tok)) if tok.isdigit() else sp.Float(tok)
        name = node[1]
        if name in variables:
            return variables[name]
        if name in CONSTANTS:
            return getattr(sp, CONSTANTS[name])
        if name in FUNCTIONS:
            raise _fail(what, text, f"function {name!r} needs arguments, e.g. {name}(x)")
        raise _fail(what, text, f"unknown symbol(s) {name}; use {', '.join(sorted(variables))} (and pi, E)")

    def combine(node: Tree, a: list) -> Any:
        op = node[0]
        if op == "call":
            name = node[1]
            if name not in FUNCTIONS:
                raise _fail(what, text, f"unknown function {name!r}; allowed: {', '.join(sorted(FUNCTIONS))}")
            if len(a) != 1:
                raise _fail(what, text, f"{name}() takes one argument, got {len(a)}")
            return getattr(sp, FUNCTIONS[name])(a[0])
        if op == "neg":
            return -a[0]
        if op == "pow":
            return _power(a[0], a[1], what, text)
        x, y = a
        return {"add": lambda: x + y, "sub": lambda: x - y, "mul": lambda: x * y, "div": lambda: x / y}[op]()

    return _fold(tree, leaf, combine)


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
    """Refuse a sympy expression given directly that is too big, has a huge integer
    exponent or uses a function outside :data:`FUNCTIONS` (naming it). Unknown symbols
    are left to the caller, which knows the names it allows."""
    import sympy as sp
    allowed_fns = {getattr(sp, n) for n in FUNCTIONS.values()}
    for n, sub in enumerate(sp.preorder_traversal(expr)):
        if n > MAX_NODES:
            raise ParameterError(f"{what}: the expression has more than {MAX_NODES} operations")
        if isinstance(sub, (sp.Add, sp.Mul, sp.Pow, sp.Symbol, sp.Number, sp.NumberSymbol)):
            if isinstance(sub, sp.Pow) and sub.exp.is_Integer and abs(int(sub.exp)) > MAX_EXPONENT:
                raise ParameterError(f"{what}: exponent {sub.exp} is larger than {MAX_EXPONENT}")
            continue
        if sub.func in allowed_fns:
            continue
        name = getattr(sub.func, "__name__", type(sub).__name__)
        raise ParameterError(f"{what}: function {name!r} is not supported; allowed: {', '.join(sorted(FUNCTIONS))}")


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
