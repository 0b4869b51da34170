"""Graph walks without recursion: scenes may be chains of 10^5 nodes or DAGs of 2^30 paths.

Every walk visits each distinct node object once (a shared subtree costs once), and
deep evaluations (the float64 twin, code generation) run on a thread with a large stack
when the graph is deeper than Python's default recursion allows.
"""
from __future__ import annotations

import contextlib
import gc
import sys
import threading
from typing import TYPE_CHECKING, Any, Callable, Iterator, Sequence, TypeVar

if TYPE_CHECKING:  # pragma: no cover
    from .base import Node

T = TypeVar("T")

SHALLOW = 400            # deeper graphs are evaluated on a big-stack thread
WIDE = 1024              # a node with this many children fills its caches with the garbage collector paused
MAX_DEPTH = 1_000_000    # nesting deeper than this is refused with a message
_STACK_BYTES = 1 << 30   # per level: a few Python frames of a few hundred bytes each


_pause_lock = threading.Lock()
_pauses = [0, False]  # [holders, whether the collector ran before the first]


@contextlib.contextmanager
def collector_paused() -> Iterator[None]:
    """Pause Python's cyclic garbage collector while a walk fills the caches of a big graph:
    everything it makes survives (the caches), so each collection would only scan the graph
    again (on a 3 x 10^5-node chain, its bounds and compile took 18 % longer). Nested and
    concurrent pauses share one; the collector runs again when the last ends, as it was."""
    with _pause_lock:
        if _pauses[0] == 0:
            _pauses[1] = gc.isenabled()
            gc.disable()
        _pauses[0] += 1
    try:
        yield
    finally:
        with _pause_lock:
            _pauses[0] -= 1
            if _pauses[0] == 0 and _pauses[1]:
                gc.enable()


def _children(node: Any) -> Sequence[Any]:
    return node.children


def postorder(root: "Node", skip: Callable[["Node"], bool] | None = None,
              kids: Callable[[Any], Sequence[Any]] = _children) -> Iterator["Node"]:
    """Each distinct node under ``root`` once, children before parents (in their order); the
    subtree of a node for which ``skip`` is true is not entered (nor is the node yielded).
    ``kids`` gives a node's children (default: ``node.children``; pickling and scene
    documents walk the nodes in constructor arguments)."""
    if skip is not None and skip(root):
        return
    seen = {id(root)}
    stack: list[tuple[Any, Iterator[Any]]] = [(root, iter(kids(root)))]
    while stack:
        node, it = stack[-1]
        for c in it:
            if id(c) not in seen and (skip is None or not skip(c)):
                seen.add(id(c))
                stack.append((c, iter(kids(c))))
                break
        else:
            stack.pop()
            yield node


def walk(root: Any, kids: Callable[[Any], Sequence[Any]] = _children) -> tuple[list[Any], dict[int, int]]:
    """(every distinct node under ``root`` children first, uses): ``uses[id(n)]`` counts the
    references to ``n`` from its parents (a child listed twice counts twice; the root
    counts one). ``kids`` is called once per distinct node."""
    order: list[Any] = []
    uses = {id(root): 1}
    stack: list[tuple[Any, Iterator[Any]]] = [(root, iter(kids(root)))]
    while stack:
        node, it = stack[-1]
        for c in it:
            k = id(c)
            if k in uses:
                uses[k] += 1
                continue
            uses[k] = 1
            stack.append((c, iter(kids(c))))
            break
        else:
            stack.pop()
            order.append(node)
    return order, uses


def cached(node: "Node", name: str, compute: Callable[["Node"], T]) -> T:
    """``node.__dict__[name]``, computed bottom-up over the subtree by ``compute`` (which
    may read its children's cached values) without recursion."""
    d = node.__dict__
    hit = d.get(name, _MISSING)
    if hit is not _MISSING:
        return hit  # type: ignore[return-value]
    if len(node.children) >= WIDE:  # reading each child's __dict__ makes it: a big walk
        with collector_paused():
            return _fill(node, name, compute)
    return _fill(node, name, compute)


def _fill(node: "Node", name: str, compute: Callable[["Node"], T]) -> T:
    """The work of :func:`cached` where ``node`` lacks ``name``."""
    d = node.__dict__
    pending = [c for c in node.children if name not in c.__dict__]
    if all(name in g.__dict__ for c in pending for g in c.children):  # the common cases: no walk
        for c in pending:
            c.__dict__[name] = compute(c)
        value = d[name] = compute(node)
        return value
    # the walk of postorder(), inlined: a 10^5-node scene pays per node only this loop
    seen = {id(node)}
    stack: list[tuple[Any, Iterator[Any]]] = [(node, iter(node.children))]
    with collector_paused():
        while stack:
            n, it = stack[-1]
            for c in it:
                if id(c) not in seen and name not in c.__dict__:
                    seen.add(id(c))
                    below = c.children
                    if not below:  # a leaf is computed here, without a stack entry
                        c.__dict__[name] = compute(c)
                        continue
                    if len(below) == 1:  # so is a move of a leaf (or of a node done): the most common
                        g = below[0]
                        if name not in g.__dict__ and not g.children:
                            g.__dict__[name] = compute(g)
                        if name in g.__dict__:
                            c.__dict__[name] = compute(c)
                            continue
                    stack.append((c, iter(below)))
                    break
            else:
                stack.pop()
                n.__dict__[name] = compute(n)
    return d[name]


_MISSING = object()


def _depth_of(n: Any, d: dict, kids: Sequence[Any]) -> None:
    if not kids:
        d["_depth"] = 1
    elif len(kids) == 1:  # the most common inner node: a move, a colour, an offset
        d["_depth"] = 1 + kids[0].__dict__["_depth"]
    else:
        d["_depth"] = 1 + max([c.__dict__["_depth"] for c in kids])


# Structural facts of a node, each computed from the node and its children's: all are
# filled in one walk (a 10^5-node scene is walked once, not once per fact). Each function
# here is called as f(node, node.__dict__, node.children) and sets its facts in the dict:
# "_depth" here, sdfgl.nodes.facts the live parameters, detail and material fields.
FACTS: list[Callable[[Any, dict, Sequence[Any]], None]] = [_depth_of]


def _fill_facts(n: Any) -> bool:
    d, kids = n.__dict__, n.children
    for fill in FACTS:
        fill(n, d, kids)
    return True


def fact(node: Any, name: str) -> Any:
    """The structural fact ``name`` of ``node`` (one that a function of FACTS sets); the
    first call fills every fact of every node under it that lacks them, in one walk."""
    d = node.__dict__
    if "_facts" not in d:
        cached(node, "_facts", _fill_facts)
    return d[name]


def depth(node: "Node") -> int:
    """The number of nodes on the longest path from ``node`` to a leaf."""
    hit = node.__dict__.get("_depth")
    return hit if hit is not None else fact(node, "_depth")


def run_deep(node: "Node", fn: Callable[[], T]) -> T:
    """Call ``fn`` (which recurses over ``node``'s graph) with room for the graph's depth."""
    d = depth(node)
    if d <= SHALLOW or threading.current_thread().name == "sdfgl-deep":
        with collector_paused():
            return fn()
    if d > MAX_DEPTH:
        from ..errors import ParameterError
        raise ParameterError(f"scene: nesting depth {d} exceeds the limit of {MAX_DEPTH} nodes")
    out: dict[str, Any] = {}

    def work() -> None:
        try:
            with collector_paused():
                out["value"] = fn()
        except BaseException as exc:  # re-raised in the caller's thread
            out["error"] = exc
    old_limit, old_stack = sys.getrecursionlimit(), threading.stack_size()
    sys.setrecursionlimit(max(old_limit, 20 * d + 1000))
    try:
        threading.stack_size(_STACK_BYTES)
        t = threading.Thread(target=work, name="sdfgl-deep")
        threading.stack_size(old_stack)
        t.start()
        t.join()
    finally:
        sys.setrecursionlimit(old_limit)
    if "error" in out:
        raise out["error"]
    return out["value"]
