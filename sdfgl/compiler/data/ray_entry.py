"""Pieces that hold a subtree, for where a ray first enters it (the grid's free way).

A translated subtree listed in a grid cell bounds the free way along the ray by where the
ray enters its bounding box (shaders/templates/grid_ray.glsl). The box of a robot-like subtree is
mostly empty: rays that pass between its parts enter the box and then step by the field's
value. ``pieces`` splits a subtree into a few balls and boxes whose union holds every
point where its field is <= 0, so the entry into the nearest of them is a tighter lower
bound on where the ray meets the subtree:

- a hard union is held by its children's pieces together;
- a hard difference by its first operand's (the others only remove);
- a hard intersection by the pieces of the operand whose pieces hold the least volume,
  cut to the intersection's bounds (a box piece to the common box; a ball is kept or,
  where it misses that box, dropped);
- translations, rotations and uniform scales move their child's pieces (a turned box
  becomes the box round it); a colour or material changes nothing;
- a sphere is its ball; any other node (a primitive, a smooth blend, a warp) is its
  bounding box, which holds it by the bounds' contract.

The expansion stops at ``MAX_PIECES``: past that it goes less deep, down to the one box
of the whole subtree (then there is nothing to gain, and ``pieces`` says so with None).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...nodes.base import Node, box_of
from ...nodes.booleans import Difference, Intersection, Union
from ...nodes.primitives import Sphere
from ...nodes.transforms import Material, Rotate, Scale, Translate

if TYPE_CHECKING:  # pragma: no cover
    from ..emitter import Emitter

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

    @property
    def volume(self) -> float:
        return 4.18879 * self.radius ** 3 if self.kind == "ball" else float(np.prod(self.hi - self.lo))

    def inside(self, other: "Piece") -> bool:
        """Whether this piece lies in the box ``other`` (balls by their bounding box)."""
        return other.kind == "box" and bool(np.all(self.lo >= other.lo) and np.all(self.hi <= other.hi))


def pieces(node: Node) -> list[Piece] | None:
    """Balls and boxes whose union holds ``node`` (at most MAX_PIECES), or None where the
    best split is the node's own bounding box (or a live parameter may move its parts)."""
    if node.live_params():
        return None
    for depth in range(_DEEPEST, 0, -1):
        found = _expand(node, _Move(np.eye(3), np.zeros(3)), depth)
        if found is not None:
            kept: list[Piece] = []
            for a in found:  # a piece inside another adds nothing
                if not any(a.inside(b) for b in kept):
                    kept = [b for b in kept if not b.inside(a)] + [a]
            return kept if len(kept) > 1 or kept[0].kind == "ball" else None
    return None


@dataclass(frozen=True)
class _Move:
    """world = a @ local + t, with a a rotation times a uniform scale."""

    a: np.ndarray
    t: np.ndarray

    def then(self, a: np.ndarray, t: np.ndarray) -> "_Move":
        """This move after the local one (a, t)."""
        return _Move(self.a @ a, self.a @ t + self.t)

    def box(self, lo: np.ndarray, hi: np.ndarray) -> Piece:
        centre, half = self.a @ (0.5 * (lo + hi)) + self.t, np.abs(self.a) @ (0.5 * (hi - lo))
        return Piece("box", centre - half, centre + half)

    def ball(self, centre: np.ndarray, radius: float) -> Piece:
        c, r = self.a @ centre + self.t, radius * float(np.linalg.norm(self.a[:, 0]))
        return Piece("ball", c - r, c + r, r)


def _expand(node: Node, move: _Move, depth: int) -> list[Piece] | None:
    """``node``'s pieces in the world of ``move``; None past MAX_PIECES."""
    while isinstance(node, (Material, Translate, Rotate, Scale)):
        if isinstance(node, Translate):
            move = move.then(np.eye(3), node.offset)
        elif isinstance(node, Rotate):
            move = move.then(node.m, np.zeros(3))
        elif isinstance(node, Scale):
            move = move.then(float(node.s) * np.eye(3), np.zeros(3))
        node = node.child
    hard = depth > 0 and isinstance(node, (Union, Difference, Intersection)) and node._hard
    if hard and isinstance(node, Union):
        out: list[Piece] = []
        for child in node.children:
            more = _expand(child, move, depth - 1)
            if more is None or len(out) + len(more) > MAX_PIECES:
                return None
            out += more
        return out
    if hard and isinstance(node, Difference):
        return _expand(node.children[0], move, depth - 1)
    if hard and isinstance(node, Intersection):
        whole = move.box(*box_of(node))
        options = [p for p in (_expand(c, move, depth - 1) for c in node.children) if p is not None]
        if options:
            return _cut(min(options, key=lambda ps: sum(p.volume for p in ps)), whole)
    if isinstance(node, Sphere):
        return [move.ball(np.asarray(node.c, dtype=np.float64), float(node.r))]
    return [move.box(*box_of(node))]


def _cut(found: list[Piece], whole: Piece) -> list[Piece]:
    """``found`` within the box ``whole``: boxes cut to it, balls that miss it dropped."""
    out = []
    for p in found:
        lo, hi = np.maximum(p.lo, whole.lo), np.minimum(p.hi, whole.hi)
        if np.all(lo <= hi):
            out.append(p if p.kind == "ball" else Piece("box", lo, hi))
    return out or [whole]


def entry_glsl(em: "Emitter", gid: str, found: list[Piece], q: str, inv: str, direction: str) -> str:
    """GLSL for where the ray (unit ``direction``, 1 / it ``inv``) from ``q`` first enters
    ``found`` (shaders/templates/grid_ray.glsl's tests; 3e38 where it enters none)."""
    tests = [f"{gid}RayBall({q} - {em.vec(p.centre)}, {direction}, {em.num(p.radius)})" if p.kind == "ball"
             else f"{gid}RayBox({q}, {inv}, {em.vec(p.lo)}, {em.vec(p.hi)})" for p in found]
    while len(tests) > 1:  # a balanced tree of mins
        tests = [f"min({a}, {b})" for a, b in zip(tests[::2], tests[1::2])] + tests[len(tests) - len(tests) % 2:]
    return tests[0]
