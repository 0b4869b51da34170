"""Nodes remember how they were built: the registry behind pickling and scene documents.

Every class that derives from :class:`Recorded` (``Node``, ``Shape2D``) and sets its own
``kind`` is registered under that kind, and every instance keeps the arguments of the
call that made it. Rebuilding a node is calling its class with those arguments again, so
pickle (:meth:`Recorded.__reduce__`) and JSON scene documents (``sdfgl.scene_io``) work for
every node kind without per-class code.

Registering a new node kind takes nothing beyond what a node has anyway::

    class Star(Primitive):
        kind = "star"                       # unique: registers the class
        def __init__(self, points: int = 5, radius: float = 1.0) -> None: ...

Its constructor's arguments must be values a document can hold: numbers, strings, bools,
None, sequences of those, numpy arrays, live parameters, sympy expressions (kept as
text) and other nodes. A constructor that takes anything else (a callable, a file)
declares ``serializable = False`` (and may say why in ``unsaved_reason``); saving such a
node then names it.
A helper base class that should not be registered passes ``register=False``::

    class _Warp(Unary, register=False): ...   # (only needed when it sets a kind)
"""
from __future__ import annotations

import copyreg
from typing import Any, ClassVar

REGISTRY: dict[str, type] = {}  # kind -> class


class Recorded:
    """Keeps ``(args, kwargs)`` of the constructor call; registers subclasses by ``kind``."""

    kind: ClassVar[str] = "recorded"
    serializable: ClassVar[bool] = True
    unsaved_reason: ClassVar[str] = ""  # why a class with serializable = False cannot be saved
    rebuilt_from: ClassVar[tuple[str, ...]] = ()
    """Names of the attributes that hold the constructor's positional arguments as given (a
    class that sets them keeps no copy of a call that passes exactly those, positionally:
    one object less per node for the garbage collector)."""
    _ctor: tuple  # the positional arguments; keyword arguments, if any, in _ctor_kw

    def __new__(cls, *args: Any, **kwargs: Any) -> "Recorded":
        self = super().__new__(cls)
        if kwargs or not cls.rebuilt_from or len(args) != len(cls.rebuilt_from):
            self._ctor = args  # no (args, kwargs) pair: one object less per node for the garbage collector
            if kwargs:
                self._ctor_kw = kwargs
        return self

    def __init_subclass__(cls, register: bool = True, **kw: Any) -> None:
        super().__init_subclass__(**kw)
        if not register or "kind" not in cls.__dict__:
            return
        other = REGISTRY.get(cls.kind)
        if other is not None and other is not cls and other.__qualname__ != cls.__qualname__:
            raise TypeError(f"node kind {cls.kind!r} of {cls.__module__}.{cls.__qualname__} is already taken by "
                            f"{other.__module__}.{other.__qualname__}; kinds name scene documents' nodes and must "
                            f"be unique")
        REGISTRY[cls.kind] = cls

    @property
    def constructor(self) -> tuple[type, tuple, dict]:
        """(class, args, kwargs) of the call that built this object."""
        d = self.__dict__
        if "_ctor" not in d and self.rebuilt_from:
            return type(self), tuple(getattr(self, name) for name in self.rebuilt_from), {}
        return type(self), d.get("_ctor", ()), d.get("_ctor_kw", {})

    @property
    def made_by_call(self) -> bool:
        """Whether this object was made by calling its class, so :attr:`constructor` rebuilds it."""
        return "_ctor" in self.__dict__ or bool(self.rebuilt_from)

    def __reduce__(self) -> tuple:
        """Pickle the graph as a flat table of constructor calls, children first: no
        recursion however deep the graph (a 10^5-deep chain pickles), shared nodes stay shared."""
        order = _postorder(self)
        index = {id(n): i for i, n in enumerate(order)}
        table = []
        for n in order:
            cls, args, kwargs = n.constructor
            table.append((cls, _to_refs(args, index), _to_refs(kwargs, index)))
        return (_rebuild_table, (table,))


def registry() -> dict[str, type]:
    """Every registered node kind: imports each module of ``sdfgl.nodes`` first, so kinds
    defined in modules that are otherwise imported lazily are there too."""
    import importlib
    import pkgutil

    from .. import nodes
    for mod in pkgutil.iter_modules(nodes.__path__):
        importlib.import_module(f"{nodes.__name__}.{mod.name}")
    return REGISTRY


class _Ref:
    """A reference to an earlier entry of a pickled constructor table."""

    __slots__ = ("index",)

    def __init__(self, index: int) -> None:
        self.index = index

    def __reduce__(self) -> tuple:
        return (_Ref, (self.index,))


def recorded_in(value: Any) -> list["Recorded"]:
    """The recorded objects (nodes, 2D shapes) inside a constructor argument, in order
    (through lists, tuples and dict values); pickling and scene documents both use it."""
    out, stack = [], [value]
    while stack:
        v = stack.pop()
        if isinstance(v, Recorded):
            out.append(v)
        elif isinstance(v, (list, tuple)):
            stack.extend(reversed(v))
        elif isinstance(v, dict):
            stack.extend(reversed(list(v.values())))
    return out


def _postorder(root: "Recorded") -> list["Recorded"]:
    """Every recorded object reachable through constructor arguments, each after those it
    was built from (iterative)."""
    from .traverse import walk
    return walk(root, lambda n: recorded_in(n.constructor[1:]))[0]


def _to_refs(value: Any, index: dict[int, int]) -> Any:
    if isinstance(value, Recorded):
        return _Ref(index[id(value)])
    if isinstance(value, (list, tuple)) and recorded_in(value):
        return type(value)(_to_refs(v, index) for v in value) if type(value) in (list, tuple) else value
    if isinstance(value, dict) and recorded_in(value):
        return {k: _to_refs(v, index) for k, v in value.items()}
    return value


def _from_refs(value: Any, made: list) -> Any:
    if isinstance(value, _Ref):
        return made[value.index]
    if type(value) in (list, tuple):
        return type(value)(_from_refs(v, made) for v in value)
    if isinstance(value, dict):
        return {k: _from_refs(v, made) for k, v in value.items()}
    return value


def _rebuild_table(table: list[tuple[type, tuple, dict]]) -> Any:
    """Inverse of Recorded.__reduce__: each constructor called in table order."""
    made: list[Any] = []
    for cls, args, kwargs in table:
        made.append(cls(*_from_refs(args, made), **_from_refs(kwargs, made)))
    return made[-1]


def _reduce_param(p: Any) -> tuple:
    # a Param's checks are closures of the nodes that use it: the nodes add them again
    # when pickle rebuilds them, so only value, name and range travel (an unnamed
    # parameter is named by its label, so the generated source stays the same)
    return (_rebuild_param, (p.value, p.name or p.label, p.range))


def _rebuild_param(value: Any, name: str | None, rng: Any) -> Any:
    from ..params import Param
    return Param(value, name, rng)


def _install_param_pickling() -> None:
    from ..params import Param
    copyreg.pickle(Param, _reduce_param)


_install_param_pickling()
