"""Costly children of hard unions and differences skipped where their box proves them idle.

At a point outside a node's bounds by d, its field is at least d / g, g being its level
factor (sdfgl.nodes.base.level_factor). So in a hard union min(a, b), wherever d / g > a,
the result is a whatever b is; in a hard difference max(a, -b), wherever d / g > -a, it is
a too. A smooth union or difference adds its blend's support R (beyond it the smooth minimum
is the minimum exactly, sdfgl.compiler.data.blend_lists): a + R and R - a. The generated code tests that bound first (a box distance) and evaluates b only
where it can matter (:meth:`sdfgl.compiler.emitter.Emitter.guarded`): the field is the same
number either way, so its exactness, the twin's parity and every consumer of map() stay as
they are, and only the time changes. What the test saves is the loops inside the branch:
llvmpipe runs the straight code of an ``if`` for every block of pixels, whether or not one
of them takes it, but a loop ends where no pixel of the block is in it
(``benchmarks/llvmpipe_branches.py``). So the test is written only for a child holding a
node whose own code loops (``Node.costly``: a text, a polygon of many vertices, a mesh, a
fractal, noise, user GLSL); for a subtree of plain primitives it would only add its own cost
to every call. An engraved plate's text, for one, is then searched only near its letters, not
at every step of every ray.

Inside the branch the value above which the result ignores the child still holds, so a
node that can stop its search there does (:func:`cap_target`): a text's search for its
nearest outline curve starts just above max(that value, 0) instead of infinity (a solid
from a 2D shape by extrusion or revolution keeps both the shape's exact values below a
positive cap and values at or above it; moves, turns and materials keep the values
themselves; "just above", so that a colour pass, which keeps the first of two equal
distances, never picks the child for its capped value). The premise needs honest bounds:
a 2D shape whose grid caps its field reports its grid's box (sdfgl.nodes.text,
sdfgl.nodes.shapes2d), since between the two boxes the cap lies below the distance.
"""
from __future__ import annotations

import numpy as np

from ..nodes.base import IMPLICIT, Node, level_factor
from ..nodes.traverse import cached

MAX_FACTOR = 2.0  # the largest level factor whose box bound is worth testing
PAD = 1e-5        # the box grows by this share of its size and distance from the origin (float32 rounding)


def worth_guarding(node: Node) -> bool:
    """Whether ``node`` holds code that loops (a ``costly`` node) and its box bounds its
    field well: a distance bound (not an implicit field) with constant parameters, finite
    bounds and a level factor of at most ``MAX_FACTOR`` (a field divided by more, as a strong
    displacement's is, lies below its box distance nearly everywhere the test would run)."""
    if node.exactness == IMPLICIT or node.live_params():
        return False
    lo, hi = node.bounds
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))) or level_factor(node) > MAX_FACTOR:
        return False
    return cached(node, "_loops", _loops_below)


def _loops_below(n: Node) -> bool:
    """Whether ``n`` or a node under it is ``costly`` (from its children's cached values)."""
    if n.costly:
        return True
    for c in n.children:
        if c.__dict__["_loops"]:
            return True
    return False


def guard_box(node: Node) -> tuple[np.ndarray, np.ndarray, float]:
    """(centre, half extents, 1 / level factor) of the box test for ``node``: its bounds grown
    for float32 rounding, so the test's distance is never above the true one."""
    lo, hi = (np.asarray(b, dtype=np.float64) for b in node.bounds)
    centre, half = (lo + hi) / 2, (hi - lo) / 2
    half = half + PAD * (float(np.max(half)) + float(np.max(np.abs(centre)))) + 1e-30
    return centre, half, 1.0 / float(level_factor(node))


def cap_target(node: Node) -> tuple[object, float] | None:
    """(the 2D shape under ``node`` that may stop its distance search, what to add to the
    value its caller ignores to get its own): the shape of an extrusion or revolution
    (``cap_target()``) moved, turned or coloured as a whole, followed down through 2D moves,
    turns and roundings (``cap_child()``: a rounding by r adds r). None where there is none."""
    n = node
    while True:
        target = getattr(n, "cap_target", None)
        if target is not None:
            shape, offset = target(), 0.0
            while (step := getattr(shape, "cap_child", None)) is not None:
                shape, more = step()
                offset += more
            return shape, offset
        kept = n.distance_keeping()
        if kept is None:
            return None
        n = kept[0]
