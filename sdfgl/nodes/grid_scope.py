"""Which unions a compile keeps as data: the grid_min in force on this thread.

The choice belongs to the compile, never to the nodes (see :func:`grid_min_as`), so it is
kept per thread beside the node graph, not on it.
"""
from __future__ import annotations

import contextlib
import threading
from typing import Iterator

_GRID_MIN = threading.local()  # the fewest instances a union keeps as data, in this compile


def grid_min_now() -> int | None:
    """The grid_min in force on this thread (None: the default, sdfgl.compiler.data.grid.GRID_MIN):
    set by the compiler for the scene it compiles; distance() evaluates under the default."""
    return getattr(_GRID_MIN, "least", None)


@contextlib.contextmanager
def grid_min_as(least: int | None) -> Iterator[None]:
    """Compile with unions of ``least`` or more instances as data. The choice belongs to the
    compile, never to the nodes: a union shared into another scene is not changed by this
    one's compile, and the float64 twin does not follow it."""
    old = getattr(_GRID_MIN, "least", None)
    _GRID_MIN.least = least
    try:
        yield
    finally:
        _GRID_MIN.least = old
