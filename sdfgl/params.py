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
from .values.float32 import FLOAT32_MAX
from .values.live import LiveValue

if TYPE_CHECKING:  # pragma: no cover
    from .compiler.emitter import Emitter

Number = (int, float, np.integer, np.floating)

_building = threading.local()
_tokens = itertools.count()


def owns_checks(init: Callable[..., None]) -> Callable[..., None]:
    """Wrap a node's ``__init__`` so the live-parameter checks it registers belong to the node.

    A Param then holds those checks weakly: when the node is gone, so are its checks (a
    discarded node never rejects a value, and rebuilt nodes do not pile up checks)."""
    @functools.wraps(init)
    def wrapper(self: Any, *args: Any, **kwargs: Any) -> None:
        try:
            stack = _building.stack
        except AttributeError:  # this thread's first node (no list made per node: fewer collections)
            stack = _building.stack = []
        if stack and stack[-1] is self:  # a subclass's __init__ calling super().__init__: already owned
            init(self, *args, **kwargs)
            return
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


class Live(LiveValue):
    """An expression over parameters, evaluated now (numpy) or per frame (GLSL)."""

    def __init__(self, op: str, *args: Any) -> None:
        self.op, self.args = op, args

    # -- evaluation ---------------------------------------------------------------------
    @property
    def value(self) -> Any:
        a = [x.value if isinstance(x, Live) else x for x in self.args]
        with np.errstate(all="ignore"):  # a NaN here is caught by the checks of the nodes that use it
            out = OPS[self.op][0](*a)
        return float(out) if np.ndim(out) == 0 else np.asarray(out, dtype=np.float64)

    def __array__(self, dtype: Any = None, copy: Any = None) -> np.ndarray:
        return np.asarray(self.value, dtype=dtype)

    def __float__(self) -> float:
        return float(self.value)

    @property
    def dims(self) -> int:
        return max(_dims(x) for x in self.args)

    def roots(self) -> list["Param"]:
        """The parameters this expression reads."""
        out: list[Param] = []
        for x in self.args:
            if isinstance(x, Live):
                out += [p for p in x.roots() if p not in out]
        return out

    def glsl(self, em: "Emitter") -> str:
        g = [x.glsl(em) if isinstance(x, Live) else em.literal(x) for x in self.args]
        if self.op in FUNCS and self.dims == 3:  # GLSL has no min(float, vec3): promote scalars
            g = [c if _dims(x) == 3 else f"vec3({c})" for c, x in zip(g, self.args)]
        return OPS[self.op][1].format(*g)

    # -- arithmetic builds expressions; anything else falls back to the current value --
    def _bin(self, op: str, other: Any, swap: bool = False) -> Any:
        # with numbers and other live values the result stays live (it may end up in GLSL);
        # with arrays (points, bounds) it is computed now from the current value
        if isinstance(other, Live) or (isinstance(other, Number) and not isinstance(other, bool)):
            return Live(op, other, self) if swap else Live(op, self, other)
        val = self.value
        return OPS[op][0](*((other, val) if swap else (val, other)))

    def __add__(self, o: Any) -> Any: return self._bin("add", o)
    def __radd__(self, o: Any) -> Any: return self._bin("add", o, True)
    def __sub__(self, o: Any) -> Any: return self._bin("sub", o)
    def __rsub__(self, o: Any) -> Any: return self._bin("sub", o, True)
    def __mul__(self, o: Any) -> Any: return self._bin("mul", o)
    def __rmul__(self, o: Any) -> Any: return self._bin("mul", o, True)
    def __truediv__(self, o: Any) -> Any: return self._bin("div", o)
    def __rtruediv__(self, o: Any) -> Any: return self._bin("div", o, True)
    def __pow__(self, o: Any) -> Any: return self._bin("pow", o)
    def __rpow__(self, o: Any) -> Any: return self._bin("pow", o, True)
    def __mod__(self, o: Any) -> Any: return self._bin("mod", o)
    def __rmod__(self, o: Any) -> Any: return self._bin("mod", o, True)
    def __neg__(self) -> "Live": return Live("neg", self)
    def __abs__(self) -> "Live": return Live("abs", self)
    def __matmul__(self, o: Any) -> Any: return np.asarray(self.value) @ np.asarray(o)
    def __rmatmul__(self, o: Any) -> Any: return np.asarray(o) @ np.asarray(self.value)

    __array_priority__ = 1000  # ndarray op Live -> our reflected operator, not elementwise objects

    def __repr__(self) -> str:
        return f"Live({self.op}, value={self.value!r})"


class Param(Live):
    """A scalar or 3-vector that is a shader uniform; set ``.value`` between renders.

    Made by :func:`sdfgl.param`. Arithmetic with numbers and other parameters (+, -, *, /,
    unary -) gives live expressions that stay uniforms in the GLSL.

    Example:
        >>> p = sg.param((0.0, 1.0, 0.0), name="offset")
        >>> s = sg.sphere(0.5).translate(p)
        >>> p.value = (0.0, 2.0, 0.0)
        >>> float(s.distance((0, 2, 0)))
        -0.5
    """

    def __init__(self, value: Any, name: str | None = None, range: tuple[float, float] | None = None) -> None:
        super().__init__("param")
        if name is not None and not isinstance(name, str):
            raise ParameterError(f"param: 'name' must be a string or None, got {type(name).__name__} {_shown(name)}")
        self.name = name
        # token -> callable returning the check (a weak reference when a node owns the check)
        self._checks: dict[int, Callable[[], Callable[[Any], None] | None]] = {}
        self._value = self._coerce(value)
        self.range = None if range is None else self._check_range(range)
        self._in_range(self._value)

    def _check_range(self, rng: Any) -> tuple[float, float]:
        """The allowed (lo, hi) with lo < hi (for a 3-vector, of each component); an
        infinite end leaves that side open."""
        try:
            lo, hi = (float(x) for x in rng)
        except (TypeError, ValueError, OverflowError):
            raise ParameterError(f"param {self.label}: range must be (low, high), got {rng!r}") from None
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            raise ParameterError(f"param {self.label}: range must be two numbers low < high (an infinite end leaves "
                                 f"that side open), got {rng!r}")
        return lo, hi

    def _in_range(self, value: Any) -> None:
        if self.range is not None:
            lo, hi = self.range
            if np.any(np.asarray(value) < lo) or np.any(np.asarray(value) > hi):
                shown = value if np.ndim(value) == 0 else tuple(float(x) for x in value)
                raise ParameterError(f"param {self.label}: value {shown!r} is outside its range [{lo:g}, {hi:g}]")

    @staticmethod
    def _coerce(value: Any) -> Any:
        if isinstance(value, bool):
            raise ParameterError(f"param: value must be a number or 3 numbers, got {value!r}")
        if isinstance(value, Number):
            if not abs(value) <= FLOAT32_MAX:  # NaN, infinity and an int too big for a float too
                raise ParameterError(f"param: value must be finite and at most {FLOAT32_MAX:.3g} in magnitude "
                                     f"(a float32 uniform), got {_shown(value)}")
            return float(value)
        try:
            arr = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError, OverflowError):
            raise ParameterError(f"param: value must be a number or 3 numbers, got {_shown(value)}") from None
        if arr.shape != (3,) or not np.all(np.abs(arr) <= FLOAT32_MAX):
            raise ParameterError(f"param: value must be a finite number or 3 finite numbers, each at most "
                                 f"{FLOAT32_MAX:.3g} in magnitude (a float32 uniform), got {_shown(value)}")
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
        self._in_range(v)
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


def _shown(value: Any) -> str:
    """``repr(value)`` for a message, shortened (a huge integer has thousands of digits)."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def param(value: Any, name: str | None = None, range: tuple[float, float] | None = None) -> Param:
    """A live value that a render reads as a uniform: changing it needs no recompile.

    Args:
        value: a finite number or 3 finite numbers (a position, size or colour).
        name: a label for messages, shader comments, sliders and scene documents.
        range: the (low, high) the value must stay in (each component of a 3-vector);
            an infinite end leaves that side open. Sliders in the browser views span it
            (default: around the value, within what its nodes accept); scene documents
            keep it as ``min``/``max``.

    Every node that uses it checks each new value, naming itself.

    Example:
        >>> r = sg.param(1.0, name="r", range=(0.5, 2.0))
        >>> s = sg.sphere(r)
        >>> r.value = 2.0
        >>> float(s.distance((3, 0, 0)))
        1.0
        >>> r.value = 3.0
        Traceback (most recent call last):
        sdfgl.errors.ParameterError: param r: value 3.0 is outside its range [0.5, 2]
    """
    return Param(value, name, range)


class Time(Param):
    """The animation clock in seconds: ``sg.time()``. ``sg.animate`` sets it for every frame.

    It is an ordinary live scalar, so expressions over it (``1 + 0.2 * sg.sin(t)``) are
    written over one uniform and checked, at every new time, by the nodes that use them.
    """

    def __init__(self, value: float = 0.0) -> None:
        if np.ndim(value):
            raise ParameterError(f"time: the clock is a number of seconds, got {value!r}")
        super().__init__(value, "time")

    def __repr__(self) -> str:
        return f"time({self._value!r})"


def time(start: float = 0.0) -> Time:
    """The animation clock: a live scalar parameter holding the time in seconds.

    Args:
        start: the time (seconds) it holds until something sets it; ``sg.animate`` sets
            ``start + i / fps`` for frame i, and you may set ``.value`` yourself between
            renders. Must be a finite number.

    Returns a :class:`Time` (a ``Param`` named "time"). Expressions over it
    (``1 + 0.2 * sg.sin(t)``) become GLSL over one uniform, so the shader is compiled once
    for a whole clip; every node that reads it checks each new time.

    Example:
        >>> t = sg.time()
        >>> s = sg.sphere(1 + 0.5 * t)
        >>> t.value = 2.0
        >>> float(s.distance((3, 0, 0)))
        1.0
    """
    return Time(start)


def _dims(x: Any) -> int:
    return x.dims if isinstance(x, Live) else (3 if np.size(x) > 1 else 1)


def _mix(a: Any, b: Any, t: Any) -> Any:
    return a * (1.0 - t) + b * t


def _smoothstep(e0: Any, e1: Any, x: Any) -> Any:
    t = np.minimum(np.maximum(np.divide(np.subtract(x, e0), np.subtract(e1, e0)), 0.0), 1.0)  # e0 == e1: no raise
    return t * t * (3.0 - 2.0 * t)


# op -> (numpy float64 evaluation, GLSL template). The same table drives both evaluators.
OPS: dict[str, tuple[Callable[..., Any], str]] = {
    "add": (np.add, "({0} + {1})"),
    "sub": (np.subtract, "({0} - {1})"),
    "mul": (np.multiply, "({0} * {1})"),
    "div": (np.divide, "({0} / {1})"),
    "neg": (np.negative, "(-{0})"),
    "sin": (np.sin, "sin({0})"),
    "cos": (np.cos, "cos({0})"),
    "tan": (np.tan, "tan({0})"),
    "abs": (np.abs, "abs({0})"),
    "sqrt": (np.sqrt, "sqrt({0})"),
    "exp": (np.exp, "exp({0})"),
    "log": (np.log, "log({0})"),
    "sign": (np.sign, "sign({0})"),
    "floor": (np.floor, "floor({0})"),
    "fract": (lambda x: x - np.floor(x), "fract({0})"),
    "radians": (np.radians, "radians({0})"),
    "min": (np.minimum, "min({0}, {1})"),
    "max": (np.maximum, "max({0}, {1})"),
    "pow": (np.power, "pow({0}, {1})"),
    "mod": (lambda x, y: x - y * np.floor(np.divide(x, y)), "mod({0}, {1})"),
    "step": (lambda e, x: np.where(x < e, 0.0, 1.0), "step({0}, {1})"),
    "clamp": (lambda x, lo, hi: np.minimum(np.maximum(x, lo), hi), "clamp({0}, {1}, {2})"),
    "mix": (_mix, "mix({0}, {1}, {2})"),
    "smoothstep": (_smoothstep, "smoothstep({0}, {1}, {2})"),
}
FUNCS = frozenset(OPS) - {"add", "sub", "mul", "div", "neg"}  # written as GLSL calls


def apply(op: str, *args: Any, names: tuple[str, ...] = ()) -> Any:
    """``op`` (a name in OPS) of ``args``: a Live expression if any argument is live, else a number now.
    ``names`` (the caller's parameter names) label a bad argument in the error."""
    vals = []
    for i, x in enumerate(args):
        if isinstance(x, Live):
            vals.append(x)
            continue
        try:  # None and bools are no numbers here (np.asarray would make them nan and 1.0)
            arr = None if x is None or isinstance(x, bool) else np.asarray(x, dtype=np.float64)
        except (TypeError, ValueError, OverflowError):  # OverflowError: an int too big for a float
            arr = None
        if arr is None or arr.shape not in ((), (3,)):
            label = f"parameter '{names[i]}'" if i < len(names) else f"argument {i + 1}"
            raise ParameterError(f"sg.{op}: {label} must be a number, 3 numbers or a live value, "
                                 f"got {type(args[i]).__name__} {args[i]!r}")
        vals.append(float(arr) if arr.ndim == 0 else arr)
    if any(isinstance(x, Live) for x in vals):
        return Live(op, *vals)
    with np.errstate(all="ignore"):
        out = OPS[op][0](*vals)
    return float(out) if np.ndim(out) == 0 else np.asarray(out, dtype=np.float64)
