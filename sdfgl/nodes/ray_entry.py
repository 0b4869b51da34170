"""Pieces that hold a subtree, for where a ray first enters it (the grid's free way).

A translated subtree listed in a grid cell bounds the free way along the ray by where the
ray enters its bounding box (shaders/grid_ray.glsl). The box of a robot-like subtree is
mostly empty: rays that pass between its parts enter the box and then step by the field's
value. ``pieces`` splits a subtree into a few balls and boxes whose union holds every
point where its field is <= 0, so the entry into the nearest of them is a tighter lower
bound on where the ray meets the subtree:

- a hard union is held by its children's pieces together;
- a hard difference by its first operand's (the others only remove);
- a translation moves its child's pieces; a colour or material changes nothing;
- a sphere is its ball; any other node (a primitive, a rotation, a smooth blend, a warp)
  is its bounding box, which holds it by the bounds' contract.

The expansion stops at ``MAX_PIECES``: past that it goes less deep, down to the one box
of the whole subtree (then there is nothing to gain, and ``pieces`` says so with None).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .base import Node, box_of

if TYPE_CHECKING:  # pragma: no cover
    from ..codegen import Emitter

MAX_PIECES = 6   # entry tests per refined instance at most (each costs about a box entry)
_DEEPEST = 12    # levels of unions, differences and moves expanded at most


@dataclass(frozen=True)
class Piece:
    """A ball (centre, radius) or an axis-aligned box (lo, hi) in the subtree's frame."""

    kind: str  # "ball" or "box"
    lo: np.ndarray
    hi: np.ndarray
    radius: float = 0.0

    @property
    def centre(self) -> np.ndarray:
        return 0.5 * (self.lo + self.hi)

    def inside(self, other: "Piece") -> bool:
        """Whether this piece lies in the box ``other`` (balls by their bounding box)."""
        return other.kind == "box" and bool(np.all(self.lo >= other.lo) and np.all(self.hi <= other.hi))


def pieces(node: Node) -> list[Piece] | None:
    """Balls and boxes whose union holds ``node`` (at most MAX_PIECES), or None where the
    best split is the node's own bounding box (or a live parameter may move its parts)."""
    if node.live_params():
        return None
    for depth in range(_DEEPEST, 0, -1):
        found = _expand(node, np.zeros(3), depth, [])
        if found is not None:
            kept: list[Piece] = []
            for a in found:  # a piece inside another adds nothing
                if not any(a.inside(b) for b in kept):
                    kept = [b for b in kept if not b.inside(a)] + [a]
            return kept if len(kept) > 1 or kept[0].kind == "ball" else None
    return None


def _expand(node: Node, offset: np.ndarray, depth: int, out: list[Piece]) -> list[Piece] | None:
    """Append ``node``'s pieces (moved by ``offset``) to ``out``; None once they pass MAX_PIECES."""
    from .booleans import Difference, Union
    from .primitives import Sphere
    from .transforms import Material, Translate
    while isinstance(node, (Material, Translate)):
        if isinstance(node, Translate):
            offset = offset + node.offset
        node = node.child
    if depth > 0 and isinstance(node, Union) and node._hard:
        for child in node.children:
            if _expand(child, offset, depth - 1, out) is None:
                return None
        return out
    if depth > 0 and isinstance(node, Difference) and node._hard:
        return _expand(node.children[0], offset, depth - 1, out)
    if isinstance(node, Sphere):
        c = np.asarray(node.c, dtype=np.float64) + offset
        r = float(node.r)
        out.append(Piece("ball", c - r, c + r, r))
    else:
        lo, hi = box_of(node)
        out.append(Piece("box", lo + offset, hi + offset))
    return out if len(out) <= MAX_PIECES else None


def entry_glsl(em: "Emitter", gid: str, found: list[Piece], q: str) -> str:
    """GLSL for where the ray (gRayDir, 1/it gRayInv) from ``q`` first enters ``found``
    (shaders/grid_ray.glsl's tests; 3e38 where it enters none)."""
    tests = [f"{gid}RayBall({q} - {em.vec(p.centre)}, gRayDir, {em.num(p.radius)})" if p.kind == "ball"
             else f"{gid}RayBox({q}, gRayInv, {em.vec(p.lo)}, {em.vec(p.hi)})" for p in found]
    while len(tests) > 1:  # a balanced tree of mins
        tests = [f"min({a}, {b})" for a, b in zip(tests[::2], tests[1::2])] + tests[len(tests) - len(tests) % 2:]
    return tests[0]
