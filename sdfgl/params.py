"""Live parameters: values that become shader uniforms instead of baked constants.

    r = sg.param(1.0)
    s = sg.sphere(r) | sg.box(1.5)
    sg.render(s)         # compiles once
    r.value = 1.2        # validated against every node that uses it
    sg.render(s)         # same source, same program: only the uniform changes

A Param (and arithmetic on it: +, -, *, / with numbers) is a ``Live`` expression. Nodes
compute with it as if it were a number (numpy sees its current value through
``__array__``); the code generator writes the expression over a uniform.
"""
from __future__ import annotations

import functools
import itertools
import math
import threading
import weakref
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from .errors import ParameterError

if TYPE_CHECKING:  # pragma: no cover
    from .codegen import Emitter

Number = (int, float, np.integer, np.floating)

_building = threading.local()
_tokens = itertools.count()


def owns_checks(init: Callable[..., None]) -> Callable[..., None]:
    """Wrap a node's ``__init__`` so the live-parameter checks it registers belong to the node.

    A Param then holds those checks weakly: when the node is gone, so are its checks (a
    discarded node never rejects a value, and rebuilt nodes do not pile up checks)."""
    @functools.wraps(init)
    def wrapper(self: Any, *args: Any, **kwargs: Any) -> None:
        stack = _building.__dict__.setdefault("stack", [])
        stack.append(self)
        try:
            init(self, *args, **kwargs)
        finally:
            stack.pop()
    return wrapper


def _owner() -> Any:
    """The node whose constructor is running on this thread (innermost), or None."""
    stack = getattr(_building, "stack", None)
    return stack[-1] if stack else None


class Live:
    """An expression over parameters, evaluated now (numpy) or per frame (GLSL)."""

    def __init__(self, op: str, *args: Any) -> None:
        self.op, self.args = op, args

    # -- evaluation ---------------------------------------------------------------------
    @property
    def value(self) -> Any:
        a = [x.value if isinstance(x, Live) else x for x in self.args]
        return {"add": lambda: a[0] + a[1], "sub": lambda: a[0] - a[1], "mul": lambda: a[0] * a[1],
                "div": lambda: a[0] / a[1], "neg": lambda: -a[0]}[self.op]()

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return np.asarray(self.value, dtype=dtype)

    def __float__(self) -> float:
        return float(self.value)

    @property
    def dims(self) -> int:
        return max((x.dims if isinstance(x, Live) else (np.size(x) if np.size(x) > 1 else 1)) for x in self.args)

    def roots(self) -> list["Param"]:
        """The parameters this expression reads."""
        out: list[Param] = []
        for x in self.args:
            if isinstance(x, Live):
                out += [p for p in x.roots() if p not in out]
        return out

    def glsl(self, em: "Emitter") -> str:
        g = [x.glsl(em) if isinstance(x, Live) else em.literal(x) for x in self.args]
        if self.op == "neg":
            return f"(-{g[0]})"
        sym = {"add": "+", "sub": "-", "mul": "*", "div": "/"}[self.op]
        return f"({g[0]} {sym} {g[1]})"

    # -- arithmetic builds expressions; anything else falls back to the current value --
    def _bin(self, op: str, other: Any, swap: bool = False) -> Any:
        # with numbers and other live values the result stays live (it may end up in GLSL);
        # with arrays (points, bounds) it is computed now from the current value
        if isinstance(other, Live) or (isinstance(other, Number) and not isinstance(other, bool)):
            return Live(op, other, self) if swap else Live(op, self, other)
        val = self.value
        return {"add": np.add, "sub": np.subtract, "mul": np.multiply, "div": np.divide}[op](
            *((other, val) if swap else (val, other)))

    def __add__(self, o: Any) -> Any: return self._bin("add", o)
    def __radd__(self, o: Any) -> Any: return self._bin("add", o, True)
    def __sub__(self, o: Any) -> Any: return self._bin("sub", o)
    def __rsub__(self, o: Any) -> Any: return self._bin("sub", o, True)
    def __mul__(self, o: Any) -> Any: return self._bin("mul", o)
    def __rmul__(self, o: Any) -> Any: return self._bin("mul", o, True)
    def __truediv__(self, o: Any) -> Any: return self._bin("div", o)
    def __rtruediv__(self, o: Any) -> Any: return self._bin("div", o, True)
    def __neg__(self) -> "Live": return Live("neg", self)
    def __matmul__(self, o: Any) -> Any: return np.asarray(self.value) @ np.asarray(o)
    def __rmatmul__(self, o: Any) -> Any: return np.asarray(o) @ np.asarray(self.value)

    __array_priority__ = 1000  # ndarray op Live -> our reflected operator, not elementwise objects

    def __repr__(self) -> str:
        return f"Live({self.op}, value={self.value!r})"


class Param(Live):
    """A scalar or 3-vector that is a shader uniform; set ``.value`` between renders."""

    def __init__(self, value: Any, name: str | None = None) -> None:
        super().__init__("param")
        self.name = name
        # token -> callable returning the check (a weak reference when a node owns the check)
        self._checks: dict[int, Callable[[], Callable[[Any], None] | None]] = {}
        self._value = self._coerce(value)

    @staticmethod
    def _coerce(value: Any) -> Any:
        if isinstance(value, bool):
            raise ParameterError(f"param: value must be a number or 3 numbers, got {value!r}")
        if isinstance(value, Number):
            v = float(value)
            if not math.isfinite(v):
                raise ParameterError(f"param: value must be finite, got {v}")
            return v
        try:
            arr = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError):
            raise ParameterError(f"param: value must be a number or 3 numbers, got {value!r}") from None
        if arr.shape != (3,) or not np.all(np.isfinite(arr)):
            raise ParameterError(f"param: value must be a finite number or 3 finite numbers, got {value!r}")
        return arr

    @property
    def value(self) -> Any:
        return self._value

    @value.setter
    def value(self, new: Any) -> None:
        v = self._coerce(new)
        if np.ndim(v) != np.ndim(self._value):
            raise ParameterError(f"param {self.label}: a {'vector' if np.ndim(self._value) else 'scalar'} "
                                 f"parameter cannot take {new!r}")
        old, self._value = self._value, v
        try:
            for ref in list(self._checks.values()):
                check = ref()
                if check is not None:
                    check(v)
        except ParameterError:
            self._value = old
            raise

    @property
    def dims(self) -> int:
        return 3 if np.ndim(self._value) else 1

    @property
    def label(self) -> str:
        return self.name or f"#{id(self) & 0xffff:04x}"

    def add_check(self, check: Callable[[Any], None]) -> None:
        """Run ``check(value)`` now and on every later assignment (it raises ParameterError).

        Registered while a node is being built, the check lives as long as that node: the
        node holds it and this parameter only a weak reference (dropped when the node dies).
        """
        check(self._value)
        token = next(_tokens)
        owner = _owner()
        if owner is None:
            self._checks[token] = lambda: check
            return
        owner.__dict__.setdefault("_param_checks", []).append(check)
        checks = self._checks
        self._checks[token] = weakref.ref(check, lambda _r: checks.pop(token, None))

    @property
    def checks(self) -> int:
        """How many live checks guard this parameter (those of nodes still alive)."""
        return sum(1 for ref in self._checks.values() if ref() is not None)

    def roots(self) -> list["Param"]:
        return [self]

    def glsl(self, em: "Emitter") -> str:
        return em.uniform_for(self)

    def __repr__(self) -> str:
        return f"param({self._value!r}{', name=' + repr(self.name) if self.name else ''})"


def param(value: Any, name: str | None = None) -> Param:
    """A live value (number or 3-vector) that a render reads as a uniform: changing it needs no recompile."""
    return Param(value, name)
