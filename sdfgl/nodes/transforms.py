"""Rigid transforms, scaling and colour: nodes that wrap exactly one child."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import axes
from ..values import validate as v
from ..params import Live
from .base import BOUND, IMPLICIT, Node, Unary, box_of, boxes_of, fluent

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter


class Translate(Unary):
    """The child moved by ``offset`` (x, y, z); keeps its exactness."""

    kind = "translate"
    rebuilt_from = ("child", "offset")

    def __init__(self, child: Node, offset: Sequence[float]) -> None:
        off = v.vector(self.kind, "offset", offset)
        super().__init__(child, offset=off)
        self.offset = off

    def distance_keeping(self) -> tuple[Node, np.ndarray | None]:
        """A translation keeps distances and turns nothing."""
        return self.child, None

    def _emit(self, em: "Emitter", p: str) -> str:
        if isinstance(self.offset, Live):
            q = em.shift_live(p, self.offset)  # folded with a moving origin on the CPU, else a GLSL sum
            return self.child.emit(em, q if q is not None else em.assign("vec3", f"{em.point(p)} - {em.vec(self.offset)}"))
        return self.child.emit(em, em.shift(p, -self.offset))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.child._distance(p - self.offset)

    @property
    def _bounds(self) -> np.ndarray:
        return box_of(self.child) + self.offset  # (lo, hi) rows

    @classmethod
    def batch_bounds(cls, nodes: Sequence[Node]) -> np.ndarray | None:
        if not all(type(n.offset) is np.ndarray for n in nodes):
            return None  # a live offset: one by one
        return boxes_of([n.child for n in nodes]) + np.array([n.offset for n in nodes])[:, None, :]

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.level_bounds(t)
        return lo + self.offset, hi + self.offset


_EYE = np.eye(3)


def _axis_angle_matrix(axis: np.ndarray, degrees: float) -> np.ndarray:
    """I cos + K sin + (1 - cos) a a^T (Rodrigues), in Python floats: one array made, not
    six (a 10^5-step rotate loop pays this per step); the same floats as the matrix sum."""
    x, y, z = (axis / math.sqrt(float(axis @ axis))).tolist()
    t = math.radians(degrees)
    c, s = math.cos(t), math.sin(t)
    C = 1 - c
    return np.array([[c + C * (x * x), -s * z + C * (x * y), s * y + C * (x * z)],
                     [s * z + C * (y * x), c + C * (y * y), -s * x + C * (y * z)],
                     [-s * y + C * (z * x), s * x + C * (z * y), c + C * (z * z)]])


class Rotate(Unary):
    """Rotation by the orthonormal matrix ``matrix`` (world = matrix @ local), or by a live
    angle (degrees) about a fixed axis."""

    kind = "rotate"

    def __init__(self, child: Node, matrix: np.ndarray | None = None, axis: np.ndarray | None = None,
                 angle: Live | None = None) -> None:
        if angle is not None:
            super().__init__(child, axis=axis, angle=angle)
            self.axis, self.angle = np.asarray(axis, dtype=np.float64) / np.linalg.norm(axis), angle
            return
        m = np.asarray(matrix, dtype=np.float64)
        if m.shape != (3, 3) or not np.all(np.isfinite(m)) or float(np.abs(m @ m.T - _EYE).max()) > 1e-9:
            raise ParameterError(f"{self.kind}: 'matrix' must be a finite 3x3 rotation, got {m.tolist()}")
        m = np.where(np.abs(m) < 1e-15, 0.0, m)  # cos(90 deg) is 6e-17, not 0
        super().__init__(child, matrix=m)
        self.angle = None
        self._m = m

    @property
    def m(self) -> np.ndarray:
        """The current rotation matrix."""
        return self._m if self.angle is None else _axis_angle_matrix(self.axis, float(self.angle))

    @classmethod
    def axis_angle(cls, child: Node, angle: float | Live, axis: Sequence[float]) -> "Rotate":
        """Rotate ``child`` by ``angle`` degrees about ``axis``."""
        deg = v.scalar(cls.kind, "angle", angle)
        ax = axes.direction(cls.kind, "axis", axis)
        if isinstance(deg, Live):
            if isinstance(ax, Live):
                raise ParameterError(f"{cls.kind}: the axis cannot be a live parameter (the angle can)")
            return cls(child, axis=ax, angle=deg)
        return cls(child, _axis_angle_matrix(ax, deg))

    @classmethod
    def orient(cls, child: Node, axis: Sequence[float]) -> "Rotate":
        """Rotate ``child`` so that its +Y axis points along ``axis``."""
        a = axes.direction("orient", "axis", axis)
        a = a / np.linalg.norm(a)
        y = np.array([0.0, 1.0, 0.0])
        c = float(np.clip(a @ y, -1.0, 1.0))
        if c > 1 - 1e-12:
            return cls(child, np.eye(3))
        if c < -1 + 1e-12:
            return cls(child, _axis_angle_matrix(np.array([1.0, 0.0, 0.0]), 180.0))
        return cls(child, _axis_angle_matrix(np.cross(y, a), math.degrees(math.acos(c))))

    def distance_keeping(self) -> tuple[Node, np.ndarray | None]:
        """A rotation keeps distances and turns its child by :attr:`m`."""
        return self.child, self.m

    def _emit(self, em: "Emitter", p: str) -> str:
        if self.angle is not None:
            em.require("op_rotate")
            rad = em.num(self.angle * (math.pi / 180.0))
            q = em.assign("vec3", f"opRotateInverse({em.point(p)}, {em.vec(self.axis)}, {rad})")
            return self.child.emit(em, q)
        turned = em.rotate(p, self.m)  # a pending float64 offset is turned in float64
        if turned is not None:
            return self.child.emit(em, turned)
        # GLSL's mat3 constructor is column-major, so the row-major entries of m build m^T.
        entries = ", ".join(em.num(x) for x in self.m.ravel())
        q = em.assign("vec3", f"mat3({entries}) * {em.point(p)}")
        return self.child.emit(em, q)

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.child._distance(p @ self.m)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self._turned(*box_of(self.child))

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        return self._turned(*self.child.level_bounds(t))

    def _turned(self, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The box holding the box (lo, hi) turned by this rotation."""
        finite = np.isfinite(lo) & np.isfinite(hi)
        lo_f, hi_f = np.where(finite, lo, 0.0), np.where(finite, hi, 0.0)
        centre = (lo_f + hi_f) / 2
        half = np.where(finite, (hi_f - lo_f) / 2, np.inf)
        a = np.abs(self.m)
        with np.errstate(invalid="ignore"):  # 0 * inf where an axis does not contribute
            contrib = np.where(a > 1e-12, a * half[None, :], 0.0)
        h = contrib.sum(axis=1)
        c = self.m @ centre
        return c - h, c + h


class Scale(Unary):
    """Uniform scale: f(p / s) * s, exactness kept."""

    kind = "scale"

    def __init__(self, child: Node, factor: float) -> None:
        s = v.scalar(self.kind, "factor", factor, positive=True)
        super().__init__(child, factor=s)
        self.s = s

    def _emit(self, em: "Emitter", p: str) -> str:
        q = em.assign("vec3", f"{em.point(p)} * {em.num(1.0 / self.s)}")
        return em.scale_distance(self.child.emit(em, q), em.num(self.s))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.child._distance(p * (1.0 / self.s)) * self.s

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = box_of(self.child)
        return lo * self.s, hi * self.s

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.level_bounds(t / float(self.s))  # f = d(p / s) s
        return lo * self.s, hi * self.s


class ScaleAxes(Unary):
    """Non-uniform scale: f(p / s) * min(s). A distance bound (1-Lipschitz), never exact."""

    kind = "scale_axes"

    def __init__(self, child: Node, factors: Sequence[float]) -> None:
        s = v.vector(self.kind, "factors", factors, positive=True)
        super().__init__(child, factors=s)
        self.s = s

    @property
    def exactness(self) -> str:
        return IMPLICIT if self.child.exactness == IMPLICIT else BOUND

    def _emit(self, em: "Emitter", p: str) -> str:
        q = em.assign("vec3", f"{em.point(p)} / {em.vec(self.s)}")
        if isinstance(self.s, Live):
            s = em.assign("vec3", em.vec(self.s))
            smin = f"min({s}.x, min({s}.y, {s}.z))"
        else:
            smin = em.num(self.s.min())
        return em.scale_distance(self.child.emit(em, q), smin)

    def _distance(self, p: np.ndarray) -> np.ndarray:
        s = np.asarray(self.s, dtype=np.float64)
        return self.child._distance(p / s) * s.min()

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = box_of(self.child)
        return lo * self.s, hi * self.s

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        s = np.asarray(self.s, dtype=np.float64)
        lo, hi = self.child.level_bounds(t / float(s.min()))  # f = d(p / s) min(s)
        return lo * s, hi * s

    def level_stretch(self) -> float:
        s = np.asarray(self.s, dtype=np.float64)
        return float(s.max() / s.min())  # p / s is at least 1 / max(s) of p's way outside


@fluent()
def translate(node: Node, offset: Sequence[float]) -> Node:
    """Move ``node`` by ``offset`` (consecutive rigid moves fold into one translate and one rotate)."""
    if type(node) is Translate and _baked(node):  # s = s.translate(d) in a loop: one node a step, not two
        off = v.vector(Translate.kind, "offset", offset)
        if not isinstance(off, Live):
            return _translate(node.child, node.offset + off)
    return fold(Translate(node, offset))


@fluent()
def orient(node: Node, axis: str | Sequence[float]) -> Node:
    """Rotate ``node`` so that its Y axis points along ``axis`` ("x", ``sg.X`` or any vector)."""
    return fold(Rotate.orient(node, axis))


@fluent()
def scale(node: Node, factor: float | Sequence[float] | Live) -> Node:
    """Scale ``node`` uniformly by a positive factor (exactness kept) or by one positive factor
    per axis (the result is a bound); folded into the moves under it."""
    return fold(_scaled(node, factor))


def _scaled(node: Node, factor: float | Sequence[float] | Live) -> Node:
    """``node`` under a new Scale or ScaleAxes node for ``factor`` (not folded)."""
    if isinstance(factor, Live):
        return Scale(node, factor) if factor.dims == 1 else ScaleAxes(node, factor)
    if isinstance(factor, (int, float, np.floating, np.integer)) and not isinstance(factor, bool):
        return Scale(node, factor)
    s = v.vector("scale", "factor", factor, positive=True)
    if np.all(s == s[0]):
        return Scale(node, float(s[0]))
    return ScaleAxes(node, s)


class Material(Unary):
    """Colour for every part of the child that has no colour of its own. Free in map()."""

    kind = "color"

    def __init__(self, child: Node, rgb: object) -> None:
        c = v.color(self.kind, rgb)
        super().__init__(child, rgb=c)
        self.rgb = c
        self.fields: dict[str, object] = {"albedo": c}  # the material fields this node sets
        self.surface = False  # sets fields besides colour (see sdfgl.nodes.material)

    def distance_keeping(self) -> tuple[Node, np.ndarray | None]:
        """A colour or material changes no distance."""
        return self.child, None

    def _emit(self, em: "Emitter", p: str) -> str:
        with em.colored(self.fields):
            return self.child.emit(em, p)

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.child._distance(p)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return box_of(self.child)

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        return self.child.level_bounds(t)


def _baked(node: Node) -> bool:
    for x in node.params.values():
        if isinstance(x, Live):
            return False
    return True


def _translate(child: Node, offset: np.ndarray) -> "Translate":
    """A Translate by a checked, finite offset (no validation: folds of checked values)."""
    n = Translate.unchecked(child, (offset,), offset=offset)
    n.offset = offset
    return n


def _rotate(child: Node, m: np.ndarray) -> "Rotate":
    """A Rotate by a product of checked rotations (no validation; rounded as Rotate() rounds,
    so the recorded call rebuilds the same node)."""
    m = np.where(np.abs(m) < 1e-15, 0.0, m)
    n = Rotate.unchecked(child, (m,), matrix=m)
    n.angle, n._m = None, m
    return n


def _scale(child: Node, s: float) -> "Scale":
    n = Scale.unchecked(child, (s,), factor=s)
    n.s = s
    return n


@fluent()
def rotate(node: Node, angle: float | Live, axis: str | Sequence[float] = (0.0, 0.0, 1.0)) -> Node:
    """``node`` rotated by ``angle`` degrees about ``axis`` ("x", ``sg.X`` or any vector through
    the origin; default Z), folded into the moves under it."""
    deg = v.scalar(Rotate.kind, "angle", angle)
    ax = axes.direction(Rotate.kind, "axis", axis)
    if isinstance(deg, Live) or isinstance(ax, Live):
        return fold(Rotate.axis_angle(node, deg, ax))
    return fold(_rotate(node, _axis_angle_matrix(ax, deg)))  # a rotation by construction


@fluent()
def color(node: Node, r: float | Sequence[float] | str, g: float | None = None, b: float | None = None) -> Node:
    """Give every part of ``node`` that has no colour of its own the colour (r, g, b), or ``r``
    alone: a name, "#rrggbb", three 0..255 integers or three 0..1 floats."""
    rgb = r if g is None and b is None else (r, g, b)
    return fold_material(Material(node, rgb))


def fold_material(node: Node) -> Node:
    """A colour or material node over one that already sets every field it sets is that
    inner node (the innermost setting wins): ``s = s.color(...)`` in a loop stays one node.
    Live values stay (their parameters keep their uniforms)."""
    inner = node.child if isinstance(node, Material) else None
    if isinstance(inner, Material) and _baked(node) and node.fields.keys() <= inner.fields.keys():
        return inner
    return node


def fold(node: Node) -> Node:
    """A new rigid transform or uniform scale merged with the ones directly under it, into
    the order translate(rotate(scale(x))): a chain of 10^5 moves stays three nodes deep.
    Exact up to float64 rounding of the composed offsets and matrices; live values stay."""
    if not isinstance(node, (Translate, Rotate, Scale)) or not _baked(node):
        return node
    inner = node.child
    if not isinstance(inner, (Translate, Rotate, Scale)) or not _baked(inner):
        return node
    if isinstance(node, Translate):
        return _translate(inner.child, inner.offset + node.offset) if isinstance(inner, Translate) else node
    if isinstance(node, Rotate):
        if isinstance(inner, Rotate):
            return fold(_rotate(inner.child, node.m @ inner.m))
        if isinstance(inner, Translate):  # R (x + t) = R x + R t
            return _translate(fold(_rotate(inner.child, node.m)), node.m @ inner.offset)
        return node
    s = float(node.s)
    if isinstance(inner, Scale):
        return fold(_scale(inner.child, s * float(inner.s)))
    if isinstance(inner, Translate):  # s (x + t) = s x + s t
        return _translate(fold(_scale(inner.child, s)), inner.offset * s)
    return _rotate(fold(_scale(inner.child, s)), inner.m)  # scaling commutes with rotating


__all__ = ["Translate", "Rotate", "Scale", "ScaleAxes", "Material", "translate", "rotate", "orient", "scale", "color",
           "fold", "fold_material"]
