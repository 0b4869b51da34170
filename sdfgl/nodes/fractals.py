"""Recursive shapes built by mirror folding, whose cost is linear in the recursion depth."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import BOUND, Primitive

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter


def _levels(node: str, levels: object, most: int) -> int:
    if isinstance(levels, bool) or not isinstance(levels, (int, np.integer)) or not 0 <= levels <= most:
        raise ParameterError(f"{node}: 'levels' must be a whole number 0..{most}, got {levels!r}")
    return int(levels)


class Sierpinski(Primitive):
    """Sierpinski tetrahedron of ``levels`` recursions, vertices at (±size, ±size, ±size)."""

    kind = "sierpinski"
    costly = True
    lib = ("sd_sierpinski",)
    exact = False

    def __init__(self, levels: int = 5, size: float = 1.0) -> None:
        n = _levels(self.kind, levels, 16)
        s = v.scalar(self.kind, "size", size, positive=True)
        super().__init__(levels=n, size=s)
        self.levels, self.size = n, float(s)

    def level_stretch(self) -> float:
        return 3.0  # like its enclosing tetrahedron's faces: circumradius / inradius

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdSierpinski({p}, {self.levels}, {em.num(self.size)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        p = p.copy()
        for _ in range(self.levels):
            for i, j in ((0, 1), (0, 2), (1, 2)):
                m = p[..., i] + p[..., j] < 0
                a, b = -p[..., j].copy(), -p[..., i].copy()
                p[..., i] = np.where(m, a, p[..., i])
                p[..., j] = np.where(m, b, p[..., j])
            p = 2.0 * p - self.size
        d = (np.maximum(np.abs(p[..., 0] + p[..., 1]) - p[..., 2], np.abs(p[..., 0] - p[..., 1]) + p[..., 2])
             - self.size) * 0.57735027
        return d / 2.0 ** self.levels

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(3, -self.size), np.full(3, self.size)


SPELLED = 6  # tree levels whose branches the bounds list one by one (4^6 of them at the deepest)


class Tree(Primitive):
    """A branching tree: a trunk of ``height`` and ``radius`` on the origin, and ``levels``
    of four branches each, leaning out by ``angle`` degrees and shrinking by ``shrink``."""

    kind = "tree"
    costly = True
    lib = ("sd_tree",)
    exact = False

    def __init__(self, levels: int = 5, height: float = 1.0, radius: float = 0.08, angle: float = 30.0,
                 shrink: float = 0.7) -> None:
        n = _levels(self.kind, levels, 12)
        h = v.scalar(self.kind, "height", height, positive=True)
        r = v.scalar(self.kind, "radius", radius, positive=True)
        a = v.scalar(self.kind, "angle", angle)
        k = v.scalar(self.kind, "shrink", shrink, positive=True)
        if not (0 < float(k) < 1):
            raise ParameterError(f"{self.kind}: parameter 'shrink' must lie in (0, 1), got {float(k):g}")
        super().__init__(levels=n, height=h, radius=r, angle=a, shrink=k)
        self.levels, self.h, self.r, self.k = n, float(h), float(r), float(k)
        self.c, self.s = math.cos(math.radians(float(a))), math.sin(math.radians(float(a)))

    def _expr(self, em: "Emitter", p: str) -> str:
        return (f"sdTree({p}, {self.levels}, {em.num(self.h)}, {em.num(self.r)}, {em.num(self.c)}, "
                f"{em.num(self.s)}, {em.num(self.k)})")

    def _capsule(self, p: np.ndarray) -> np.ndarray:
        y = np.clip(p[..., 1], 0.0, self.h)
        return np.sqrt(p[..., 0] ** 2 + (p[..., 1] - y) ** 2 + p[..., 2] ** 2) - self.r

    def _distance(self, p: np.ndarray) -> np.ndarray:
        p = p.copy()
        scale = 1.0
        d = self._capsule(p)
        c, s = self.c, self.s
        for _ in range(self.levels):
            p[..., 1] -= self.h
            p[..., 0], p[..., 2] = np.abs(p[..., 0]), np.abs(p[..., 2])
            x, y = p[..., 0].copy(), p[..., 1].copy()
            p[..., 0], p[..., 1] = c * x - s * y, s * x + c * y
            z, y = p[..., 2].copy(), p[..., 1].copy()
            p[..., 2], p[..., 1] = c * z - s * y, s * z + c * y
            p /= self.k
            scale *= self.k
            d = np.minimum(d, self._capsule(p) * scale)
        return d

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Box of every branch's end points (the first ``SPELLED`` levels one by one, 4 ** level
        of them, each mapped back through the folds), padded by the trunk's radius and, past
        those levels, by the lengths the smaller branches can still add."""
        ends = np.array([[0.0, 0.0, 0.0], [0.0, self.h, 0.0]])
        c, s, k = self.c, self.s, self.k
        found = [ends]
        for level in range(1, min(self.levels, SPELLED) + 1):
            q = ends
            for _ in range(level):  # from the level's own frame to the parent's, up to the trunk's
                u = k * q
                y, z = -s * u[:, 2] + c * u[:, 1], c * u[:, 2] + s * u[:, 1]
                x, y = c * u[:, 0] + s * y, -s * u[:, 0] + c * y
                q = np.concatenate([np.stack([sx * x, y + self.h, sz * z], 1)
                                    for sx in (1, -1) for sz in (1, -1)])
            found.append(q)
        pts = np.concatenate(found)
        pad = self.r + ((self.h + self.r) * k ** (SPELLED + 1) / (1 - k) if self.levels > SPELLED else 0.0)
        return pts.min(axis=0) - pad, pts.max(axis=0) + pad


def sierpinski(levels: int = 5, size: float = 1.0) -> Sierpinski:
    """A Sierpinski tetrahedron by mirror folding: 4**levels copies for the cost of ``levels`` folds.

    Args:
        levels: fold levels, a whole number (baked into the code).
        size: distance from the centre to a vertex, > 0.

    A bound.

    Example:
        >>> sg.sierpinski(4, 1.0).exactness
        'bound'
    """
    return Sierpinski(levels, size)


def tree(levels: int = 5, height: float = 1.0, radius: float = 0.08, angle: float = 30.0,
         shrink: float = 0.7) -> Tree:
    """A branching tree by mirror recursion: 4**levels branches at a cost linear in ``levels``.

    Args:
        levels: branching levels, a whole number (baked into the code).
        height: trunk height, > 0.
        radius: trunk radius, > 0.
        angle: branch angle from the vertical, degrees.
        shrink: size of each level relative to the one below, in (0, 1).

    A bound.

    Example:
        >>> sg.tree(3).exactness
        'bound'
    """
    return Tree(levels, height, radius, angle, shrink)


__all__ = ["Sierpinski", "Tree", "sierpinski", "tree", "BOUND"]
