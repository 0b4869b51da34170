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
    _ctor: tuple[tuple, dict]

    def __new__(cls, *args: Any, **kwargs: Any) -> "Recorded":
        self = super().__new__(cls)
        self.__dict__["_ctor"] = (args, kwargs)
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
        args, kwargs = self.__dict__.get("_ctor", ((), {}))
        return type(self), args, kwargs

    def __reduce__(self) -> tuple:
        cls, args, kwargs = self.constructor
        return (_rebuild, (cls, args, kwargs))


def registry() -> dict[str, type]:
    """Every registered node kind: imports each module of ``sdfgl.nodes`` first, so kinds
    defined in modules that are otherwise imported lazily are there too."""
    import importlib
    import pkgutil

    from .. import nodes
    for mod in pkgutil.iter_modules(nodes.__path__):
        importlib.import_module(f"{nodes.__name__}.{mod.name}")
    return REGISTRY


def _rebuild(cls: type, args: tuple, kwargs: dict) -> Any:
    return cls(*args, **kwargs)


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
