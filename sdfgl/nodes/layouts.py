"""The data layouts some nodes' fields are defined by, supplied by the compiler.

A hard union of many instances is kept as data, listed in the cells of a grid, and so is
a polygon of many vertices: far from its parts such a field is the cells' cap, a distance
bound, and the float64 twin computes the same number. How the cells are laid out is a
compiler strategy (:mod:`sdfgl.compiler.data`), which registers its builders here when it
is imported (importing any part of sdfgl imports it); the nodes ask for a layout by name
and never import the compiler.
"""
from __future__ import annotations

from typing import Any, Callable

_LAYOUTS: dict[str, Callable[..., Any]] = {}


def register_layout(name: str, build: Callable[..., Any]) -> None:
    """Make ``build`` the layout called ``name``: "union" (children, fewest instances or None,
    and ``blend=(k, kind)`` for a smooth union -> a grid or None), "polygon" (vertices
    (n, 2) -> an edge grid or None) or "mesh" (vertices (v, 3), faces (n, 3) -> a triangle
    hierarchy)."""
    _LAYOUTS[name] = build


def layout(name: str) -> Callable[..., Any] | None:
    """The builder registered as ``name``, or None (then the node stays code everywhere)."""
    return _LAYOUTS.get(name)
