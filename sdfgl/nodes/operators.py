"""Operators: erode (dilate is .round), morph between two nodes, and shear."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..params import Live
from ..values import axes
from ..values import validate as v
from .base import BOUND, IMPLICIT, Node, Unary, fluent

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

AXES = "xyz"


def _field(em: "Emitter", r: str) -> str:
    return f"{r}.w" if em.mode == "color" else r


def _result(em: "Emitter", r: str, d: str) -> str:
    return em.assign("float", d) if em.mode == "dist" else em.assign("vec4", f"vec4({r}.rgb, {d})")


class Erode(Unary):
    """The child shrunk by ``radius`` (f + r): a bound outside even where the child is exact."""

    kind = "erode"

    def __init__(self, child: Node, radius: float) -> None:
        r = v.scalar(self.kind, "radius", radius, nonnegative=True)
        super().__init__(child, radius=r)
        self.r = r

    @property
    def exactness(self) -> str:
        return IMPLICIT if self.child.exactness == IMPLICIT else BOUND

    def _emit(self, em: "Emitter", p: str) -> str:
        r = self.child.emit(em, p)
        return _result(em, r, f"{_field(em, r)} + {em.num(self.r)}")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.child._distance(p) + float(self.r)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.child.bounds


class Morph(Node):
    """(1 - t) a + t b: the solid turns from ``a`` (t = 0) into ``b`` (t = 1); colours and
    materials mix the same way. A convex combination of bounds is a bound. ``t`` may be
    live (sg.param): morphing then re-renders without recompiling."""

    kind = "morph"

    def __init__(self, a: Node, b: Node, t: float) -> None:
        tt = v.scalar(self.kind, "t", t)

        def check() -> None:
            if not 0.0 <= float(tt) <= 1.0:
                raise ParameterError(f"{self.kind}: parameter 't' must lie in [0, 1], got {float(tt):g}")
        v.watch(check, tt)
        super().__init__((a, b), t=tt)
        self.t = tt

    @property
    def exactness(self) -> str:
        return IMPLICIT if any(c.exactness == IMPLICIT for c in self.children) else BOUND

    @property
    def lipschitz(self) -> float:
        return max(c.lipschitz for c in self.children)

    def _emit(self, em: "Emitter", p: str) -> str:
        ra, rb = (c.emit(em, p) for c in self.children)
        return em.assign("float" if em.mode == "dist" else "vec4", f"mix({ra}, {rb}, {em.num(self.t)})")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        t = float(self.t)
        return self.children[0]._distance(p) * (1.0 - t) + self.children[1]._distance(p) * t

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        # (1 - t) a + t b < 0 needs a < 0 or b < 0
        (la, ha), (lb, hb) = (c.bounds for c in self.children)
        return np.minimum(la, lb), np.maximum(ha, hb)


class Shear(Unary):
    """Shear: coordinate ``along`` moves by ``amount`` times coordinate ``by``. The field
    f(S^-1 p) is divided by ||S^-1|| = (|k| + sqrt(k^2 + 4)) / 2, for this subtree only."""

    kind = "shear"

    def __init__(self, child: Node, amount: float, along: str | Sequence[float] = "x",
                 by: str | Sequence[float] = "y") -> None:
        k = v.scalar(self.kind, "amount", amount)
        v.fixed(self.kind, "the step safety factor is compiled from it", amount=k)
        a, b = axes.coordinate(self.kind, "along", along), axes.coordinate(self.kind, "by", by)
        if a == b:
            raise ParameterError(f"{self.kind}: 'along' and 'by' must be two different axes of x, y, z, "
                                 f"got {axes.shown(along)}, {axes.shown(by)}")
        super().__init__(child, amount=k, along=AXES[a], by=AXES[b])
        self.k, self.a, self.b = float(k), a, b
        self.stretch = (abs(self.k) + math.sqrt(self.k ** 2 + 4.0)) / 2.0

    @property
    def exactness(self) -> str:
        return IMPLICIT if self.child.exactness == IMPLICIT else BOUND

    def _emit(self, em: "Emitter", p: str) -> str:
        pt = em.point(p)
        comps = [f"{pt}.{c}" for c in AXES]
        comps[self.a] = f"{pt}.{AXES[self.a]} - {em.num(self.k)} * {pt}.{AXES[self.b]}"
        q = em.assign("vec3", f"vec3({', '.join(comps)})")
        return em.scale_distance(self.child.emit(em, q), em.num(1.0 / self.stretch))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        q = p.copy()
        q[..., self.a] = p[..., self.a] - self.k * p[..., self.b]
        return self.child._distance(q) / self.stretch

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        if self.k == 0:
            return lo, hi
        with np.errstate(invalid="ignore"):
            ext = (self.k * lo[self.b], self.k * hi[self.b])
        lo2, hi2 = lo.copy(), hi.copy()
        lo2[self.a] = lo[self.a] + min(ext)
        hi2[self.a] = hi[self.a] + max(ext)
        return lo2, hi2


@fluent()
def erode(node: Node, radius: float) -> Erode:
    """Shrink ``node`` by ``radius`` (f + r; a bound)."""
    return Erode(node, radius)


@fluent()
def shear(node: Node, amount: float, along: str | Sequence[float] = "x", by: str | Sequence[float] = "y") -> Shear:
    """Move coordinate ``along`` of ``node`` by ``amount`` times coordinate ``by`` (each "x",
    "y", "z" or a vector along one, such as ``sg.X``); a bound, and only this subtree's steps
    shrink."""
    return Shear(node, amount, along, by)


def morph(a: Node, b: Node, t: float | Live = 0.5) -> Morph:
    """Blend the fields of ``a`` and ``b``: (1 - t) a + t b.

    Args:
        a: the field at t = 0.
        b: the field at t = 1.
        t: the blend, in [0, 1] (may be a live ``sg.param``).

    Example:
        >>> float(sg.morph(sg.sphere(1), sg.box(2), 0.5).distance((2, 0, 0)))
        1.0
    """
    return Morph(a, b, t)
