"""Domain and distance operators: mirror, symmetry, polar repetition, elongate, round, shell."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import BOUND, IMPLICIT, Node, Unary, fluent

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter



def _box_corners(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])


class Mirror(Unary):
    """The child on the side ``normal`` points to, and its reflection in the plane.

    Exact when the child lies wholly on that side; where it crosses the plane the part
    behind is cut off and the field is a bound."""

    kind = "mirror"

    def __init__(self, child: Node, normal: Sequence[float] = (1.0, 0.0, 0.0),
                 point: Sequence[float] = (0.0, 0.0, 0.0)) -> None:
        v.fixed(self.kind, "it shapes the code", normal=normal, point=point)
        n = v.vector(self.kind, "normal", normal, nonzero=True)
        o = v.vector(self.kind, "point", point)
        super().__init__(child, normal=n / np.linalg.norm(n), point=o)
        self.n, self.o = n / np.linalg.norm(n), o

    def _one_sided(self) -> bool:
        lo, hi = self.child.bounds
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            return False
        return bool(np.all((_box_corners(lo, hi) - self.o) @ self.n >= -1e-12))

    @property
    def exactness(self) -> str:
        if self.child.exactness == IMPLICIT:
            return IMPLICIT
        return self.child.exactness if self._one_sided() else BOUND

    def _fold(self, p: np.ndarray) -> np.ndarray:
        s = np.minimum((p - self.o) @ self.n, 0.0)
        return p - 2.0 * s[..., None] * self.n

    def _emit(self, em: "Emitter", p: str) -> str:
        pt = em.point(p)
        n = em.vec(self.n)
        q = em.assign("vec3", f"{pt} - 2.0 * min(dot({pt} - {em.vec(self.o)}, {n}), 0.0) * {n}")
        return self.child.emit(em, q)

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.child._distance(self._fold(p))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            return np.full(3, -np.inf), np.full(3, np.inf)
        c = _box_corners(lo, hi)
        r = c - 2.0 * ((c - self.o) @ self.n)[:, None] * self.n
        allc = np.concatenate([c, r])
        return allc.min(axis=0), allc.max(axis=0)


@fluent()
def symmetric(node: Node, axes: str = "x") -> Node:
    """Mirror ``node`` across the planes x = 0, y = 0 and/or z = 0 named in ``axes``.

    Args:
        node: the node; its part on the positive side of each named axis is kept.
        axes: letters from "xyz", e.g. "xz" for four copies.

    Example:
        >>> s = sg.symmetric(sg.sphere(0.3, (1, 0, 1)), "xz")
        >>> float(s.distance((-1, 0, -1)))
        -0.3
    """
    if not isinstance(axes, str) or not axes or any(a not in "xyz" for a in axes):
        raise ParameterError(f"symmetric: 'axes' must be letters from 'xyz', got {axes!r}")
    for a in dict.fromkeys(axes):
        node = Mirror(node, np.eye(3)["xyz".index(a)])
    return node


MAX_POLAR_COUNT = 1_000_000  # copies of a polar repeat (each sector is then 0.00036 degrees wide)


class PolarRepeat(Unary):
    """``count`` copies of the child turned about the Y axis; the child sits around +X.

    Each point evaluates its own sector and the nearest neighbour sector, which is exact
    while the child stays within one sector of its own."""

    kind = "repeat_polar"

    def __init__(self, child: Node, count: int) -> None:
        v.fixed(self.kind, "it shapes the code", count=count)
        if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or not 2 <= count <= MAX_POLAR_COUNT:
            raise ParameterError(f"{self.kind}: 'count' must be a whole number in 2..{MAX_POLAR_COUNT}, got {count!r}")
        lo, hi = child.bounds
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            raise ParameterError(f"{self.kind}: the child {child.label()} is unbounded")
        angle = 2 * math.pi / count
        c = _box_corners(lo, hi)
        if np.any(c[:, 0] <= 0) or np.any(np.abs(np.arctan2(c[:, 2], c[:, 0])) > angle):
            raise ParameterError(
                f"{self.kind}: the child {child.label()} must lie around +X within {math.degrees(angle):g} degrees "
                f"of it (one sector each way) for {count} copies; move it out along X or use fewer copies")
        super().__init__(child, count=int(count))
        self.count, self.angle = int(count), angle

    def _emit(self, em: "Emitter", p: str) -> str:
        em.require("op_polar")
        pt = em.point(p)
        a = em.num(self.angle)
        rel = em.assign("float", f"atan({pt}.z, {pt}.x) / {a}")
        k = em.assign("float", f"floor({rel} + 0.5)")
        fn = em.function(self.child)
        rtype = "float" if em.mode == "dist" else "vec4"
        own = em.assign(rtype, f"{fn}(opPolarSector({pt}, {k}, {a}))")
        other = em.assign(rtype, f"{fn}(opPolarSector({pt}, {k} + sign({rel} - {k}), {a}))")
        if em.mode == "dist":
            return em.assign("float", f"min({own}, {other})")
        return em.assign("vec4", f"({other}.w < {own}.w) ? {other} : {own}")

    def _sector(self, p: np.ndarray, k: np.ndarray) -> np.ndarray:
        a = -k * self.angle
        c, s = np.cos(a), np.sin(a)
        return np.stack([c * p[..., 0] - s * p[..., 2], p[..., 1], s * p[..., 0] + c * p[..., 2]], axis=-1)

    def _distance(self, p: np.ndarray) -> np.ndarray:
        rel = np.arctan2(p[..., 2], p[..., 0]) / self.angle
        k = np.floor(rel + 0.5)
        own = self.child._distance(self._sector(p, k))
        return np.minimum(own, self.child._distance(self._sector(p, k + np.sign(rel - k))))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        r = float(np.max(np.hypot(_box_corners(lo, hi)[:, 0], _box_corners(lo, hi)[:, 2])))
        return np.array([-r, lo[1], -r]), np.array([r, hi[1], r])


class Elongate(Unary):
    """Stretch the child by inserting ``length`` along each axis at its centre planes."""

    kind = "elongate"

    def __init__(self, child: Node, length: float | Sequence[float]) -> None:
        v.fixed(self.kind, "it shapes the code", length=length)
        h = v.vector(self.kind, "length", length)
        if np.any(h < 0):
            raise ParameterError(f"{self.kind}: parameter 'length' must be >= 0 per axis, got {tuple(h)}")
        super().__init__(child, length=h)
        self.h = h / 2

    @property
    def exactness(self) -> str:
        return IMPLICIT if self.child.exactness == IMPLICIT else BOUND

    def _emit(self, em: "Emitter", p: str) -> str:
        pt = em.point(p)
        h = em.vec(self.h)
        return self.child.emit(em, em.assign("vec3", f"{pt} - clamp({pt}, -{h}, {h})"))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.child._distance(p - np.clip(p, -self.h, self.h))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        return lo - self.h, hi + self.h


class _Offset(Unary):
    """Shared by Round (f - r) and Shell (|f| - t/2)."""

    _is_shell = False

    def __init__(self, child: Node, amount: float) -> None:
        name = "thickness" if self._is_shell else "radius"
        a = v.scalar(self.kind, name, amount, positive=self._is_shell, nonnegative=not self._is_shell)
        super().__init__(child, **{name: a})
        self.amount = a

    def _emit(self, em: "Emitter", p: str) -> str:
        r = self.child.emit(em, p)
        a = em.num(self.amount * 0.5 if self._is_shell else self.amount)
        d = f"{r}.w" if em.mode == "color" else r
        d = f"abs({d}) - {a}" if self._is_shell else f"{d} - {a}"
        return em.assign("float", d) if em.mode == "dist" else em.assign("vec4", f"vec4({r}.rgb, {d})")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        d = self.child._distance(p)
        return np.abs(d) - float(self.amount) * 0.5 if self._is_shell else d - float(self.amount)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.level_bounds(0.0)

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        # f - r < t needs f < t + r; |f| - t' / 2 < t needs f < t + t' / 2
        return self.child.level_bounds(t + float(self.amount) * (0.5 if self._is_shell else 1.0))


class Round(_Offset):
    """The child grown by ``radius``: rounded edges (f - r)."""

    kind = "round"


class Shell(_Offset):
    """A shell ``thickness`` thick around the child's surface (|f| - t / 2)."""

    kind = "shell"
    _is_shell = True


@fluent()
def mirror(node: Node, normal: Sequence[float] = (1.0, 0.0, 0.0), point: Sequence[float] = (0.0, 0.0, 0.0)) -> Node:
    """``node`` on the side ``normal`` points to, plus its reflection in that plane.

    Args:
        node: the node (only its part on the normal's side is kept).
        normal: the plane's normal (x, y, z), not zero.
        point: a point on the plane.

    Keeps the child's exactness where the child lies on one side.

    Example:
        >>> s = sg.mirror(sg.sphere(0.5, (1, 0, 0)), (1, 0, 0))
        >>> float(s.distance((-1, 0, 0)))
        -0.5
    """
    return Mirror(node, normal, point)


@fluent()
def repeat_polar(node: Node, count: int) -> Node:
    """``count`` copies of ``node`` turned evenly about the Y axis.

    Args:
        node: the copy placed around +X.
        count: number of copies, a whole number in 2..1000000 (a baked constant).

    Example:
        >>> s = sg.repeat_polar(sg.sphere(0.2, (1, 0, 0)), 4)
        >>> round(float(s.distance((0, 0, 1))), 6)
        -0.2
    """
    return PolarRepeat(node, count)


@fluent()
def elongate(node: Node, length: float | Sequence[float]) -> Node:
    """Stretch ``node`` by inserting a slab at its centre planes.

    Args:
        node: the node.
        length: added length per axis (one number or (lx, ly, lz)), >= 0.

    Keeps exactness.

    Example:
        >>> float(sg.elongate(sg.sphere(1), (2, 0, 0)).distance((3, 0, 0)))
        1.0
    """
    return Elongate(node, length)


@fluent("round", "dilate")
def rounded(node: Node, radius: float) -> Node:
    """Grow ``node`` by ``radius`` (f - r): rounded edges and corners (also ``node.round(r)``
    and ``node.dilate(r)``).

    Args:
        node: the node.
        radius: growth in scene units, >= 0.

    Exact outside where the child is exact.

    Example:
        >>> float(sg.rounded(sg.box(1), 0.1).distance((1, 0, 0)))
        0.4
    """
    return Round(node, radius)


@fluent()
def shell(node: Node, thickness: float) -> Node:
    """A shell of the given thickness around ``node``'s surface (|f| - t/2).

    Args:
        node: the node.
        thickness: full wall thickness, > 0.

    Keeps exactness (a hollow shape; cut it open to see inside).

    Example:
        >>> float(sg.shell(sg.sphere(1), 0.1).distance((0, 0, 0)))
        0.95
    """
    return Shell(node, thickness)
