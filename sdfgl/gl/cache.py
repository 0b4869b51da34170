"""Least-recently-used caches of GL objects, within a settable memory budget.

Every renderer keeps three caches on its context, each bounded:

- compiled programs (keyed by the full fragment source): at most ``programs`` of them
  (llvmpipe keeps about 1 to 3 MB of machine code per program);
- data textures of big unions kept as data: at most ``data_mb`` megabytes;
- render targets (one framebuffer per image size and output set): at most ``targets_mb``
  megabytes; the target in use is always kept, so one render larger than the budget still
  works and is released by the next one.

The least recently used entry is released first (its GL objects are deleted at once).
``sg.cache_budget(programs=..., data_mb=..., targets_mb=...)`` changes the budget of every
renderer that has none of its own; ``Renderer(budget=CacheBudget(...))`` gives one its own
(``None`` for a limit means unbounded).
"""
from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass, fields, replace
from typing import Callable, Generic, Hashable, TypeVar

from ..errors import ParameterError

V = TypeVar("V")
MB = 1 << 20


@dataclass(frozen=True)
class CacheBudget:
    """Limits of a renderer's GL caches, least recently used entries evicted first.

    Args:
        programs: compiled shader programs kept (default 32); None: unbounded.
        data_mb: megabytes of data textures (unions kept as data) kept (default 256).
        targets_mb: megabytes of render targets (one set per image size and outputs) kept
            (default 256).

    Example:
        >>> sg.CacheBudget(programs=8).programs
        8
        >>> r = sg.Renderer(budget=sg.CacheBudget(programs=4))
    """

    programs: int | None = 32
    data_mb: float | None = 256.0
    targets_mb: float | None = 256.0

    def __post_init__(self) -> None:
        for f in fields(self):
            val = getattr(self, f.name)
            if val is None:
                continue
            if isinstance(val, bool) or not isinstance(val, (int, float)) or not math.isfinite(val) or val < 1:
                raise ParameterError(f"cache budget '{f.name}' must be None (unbounded) or a finite number >= 1, "
                                     f"got {val!r}")
            if f.name == "programs" and int(val) != val:
                raise ParameterError(f"cache budget 'programs' must be a whole number, got {val!r}")


_budget = CacheBudget()


def cache_budget(**limits: int | float | None) -> CacheBudget:
    """Set any of ``programs``, ``data_mb``, ``targets_mb`` for every renderer without a budget of
    its own; return the budget now in force (call with no arguments to read it).

    Args:
        limits: ``programs`` (count), ``data_mb`` and ``targets_mb`` (megabytes), each a
            number >= 1 or None (unbounded); see :class:`CacheBudget`.

    Example:
        >>> old = sg.cache_budget()
        >>> sg.cache_budget(programs=64).programs
        64
        >>> _ = sg.cache_budget(programs=old.programs)
    """
    global _budget
    names = {f.name for f in fields(CacheBudget)}
    unknown = sorted(set(limits) - names)
    if unknown:
        raise ParameterError(f"cache_budget: unknown limit(s) {', '.join(unknown)}; known: {', '.join(sorted(names))}")
    _budget = replace(_budget, **limits)
    return _budget


def default_budget() -> CacheBudget:
    """The budget of renderers that have none of their own."""
    return _budget


class LRU(Generic[V]):
    """Entries with a size in bytes, least recently used first; ``release`` frees an evicted value."""

    def __init__(self, release: Callable[[V], None]) -> None:
        self._items: OrderedDict[Hashable, tuple[V, int]] = OrderedDict()
        self._release = release
        self.bytes = 0

    def get(self, key: Hashable) -> V | None:
        """The value for ``key`` (now the most recently used), or None."""
        item = self._items.get(key)
        if item is None:
            return None
        self._items.move_to_end(key)
        return item[0]

    def put(self, key: Hashable, value: V, nbytes: int = 0) -> None:
        """Add ``value`` as the most recently used entry (replacing and releasing an old one)."""
        old = self._items.pop(key, None)
        if old is not None:
            self.bytes -= old[1]
            self._release(old[0])
        self._items[key] = (value, nbytes)
        self.bytes += nbytes

    def trim(self, max_items: int | None = None, max_bytes: float | None = None) -> None:
        """Release least recently used entries until within both limits (the newest always stays)."""
        while len(self._items) > 1 and ((max_items is not None and len(self._items) > max_items)
                                        or (max_bytes is not None and self.bytes > max_bytes)):
            _, (value, nbytes) = self._items.popitem(last=False)
            self.bytes -= nbytes
            self._release(value)

    def forget(self) -> None:
        """Drop every entry without releasing it (its context is gone)."""
        self._items.clear()
        self.bytes = 0

    def clear(self) -> None:
        """Release every entry."""
        while self._items:
            _, (value, _n) = self._items.popitem(last=False)
            self._release(value)
        self.bytes = 0

    def __len__(self) -> int:
        return len(self._items)

    def __contains__(self, key: Hashable) -> bool:
        return key in self._items
