"""The structural facts every node has, filled for a whole graph in one walk.

:func:`sdfgl.nodes.traverse.fact` fills them the first time one is asked for: the live
parameters at or under a node (``_live_cache``), whether some node shades with more
detail than it marches (``_detail``), and the material fields some node sets
(``_fields``); traverse itself sets the depth.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

from ..params import Live
from .traverse import FACTS

if TYPE_CHECKING:  # pragma: no cover
    from ..params import Param
    from .base import Node


def live_below(n: "Node", kids: Sequence["Node"]) -> tuple["Param", ...]:
    """The live parameters of ``n`` and under it, from its children's (cached) lists."""
    out: list[Param] = []
    for v in n.params.values():
        if isinstance(v, Live):
            out += [p for p in v.roots() if p not in out]
    for c in kids:
        below = c.__dict__["_live_cache"]
        if below:
            out += [p for p in below if p not in out]
    return tuple(out) if out else ()  # () for most nodes: no object for the garbage collector to track


_NO_FIELDS: frozenset = frozenset()


def node_facts(n: "Node", d: dict, kids: Sequence["Node"]) -> None:
    """Set in ``d`` (n's __dict__) from its children's: ``_live_cache`` (the live parameters
    at or under n), ``_detail`` (has_detail) and ``_fields`` (the material fields some node
    at or under n sets: a material's ``fields`` dict). One function for the three: a
    10^6-node scene pays one call per node."""
    fields = d.get("fields")
    own = frozenset(fields) if fields else _NO_FIELDS
    live = False
    for v in n.params.values():  # a loop, not any(): a generator costs more than the test
        if isinstance(v, Live):
            live = True
    if len(kids) == 1:  # the most common: a leaf's parent (a move, a colour, an offset)
        k = kids[0].__dict__
        d["_live_cache"] = live_below(n, kids) if live or k["_live_cache"] else ()
        d["_detail"] = k["_detail"] or n._detail_here()
        below = k["_fields"]
        d["_fields"] = own | below if below else own
        return
    if not kids:
        d["_live_cache"] = live_below(n, kids) if live else ()
        d["_detail"] = n._detail_here()
        d["_fields"] = own
        return
    below = [c.__dict__ for c in kids]
    d["_live_cache"] = live_below(n, kids) if live or any(k["_live_cache"] for k in below) else ()
    d["_detail"] = any(k["_detail"] for k in below) or n._detail_here()
    more = [f for k in below if (f := k["_fields"])]
    d["_fields"] = own.union(*more) if more else own


FACTS.append(node_facts)
