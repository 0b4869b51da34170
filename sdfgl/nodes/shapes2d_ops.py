"""2D booleans (hard or blended), transforms, rounding, onion, and slices of 3D nodes.

The formulas are the 3D ones over vec2: the same smooth-min library functions, the
same twins (sdfgl.nodes.booleans), so 2D and 3D blends agree exactly.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import BOUND, EXACT, IMPLICIT, Node
from .booleans import BLEND_GLSL, BLEND_REACH, BLENDS, K_MIN, smooth_min
from .shapes2d import Shape2D

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter


class _Boolean2D(Shape2D):
    """N-ary 2D boolean folded left to right, hard (k = 0) or blended over k."""

    def __init__(self, *children: Shape2D, k: float = 0.0, blend: str = "quadratic") -> None:
        if len(children) < 2:
            raise ParameterError(f"{self.kind}: needs at least two operands, got {len(children)}")
        if blend not in BLENDS:
            raise ParameterError(f"{self.kind}: 'blend' must be one of {', '.join(BLENDS)}, got {blend!r}")
        kk = v.scalar(self.kind, "k", k, nonnegative=True)
        kk = 0.0 if kk < K_MIN else float(kk)
        super().__init__(children, k=kk, **({} if blend == "quadratic" else {"blend": blend}))
        self.k, self.blend = kk, blend

    @property
    def exactness(self) -> str:  # type: ignore[override]
        kinds = {c.exactness for c in self.children}
        return IMPLICIT if IMPLICIT in kinds else BOUND

    @property
    def lipschitz(self) -> float:  # type: ignore[override]
        return max(c.lipschitz for c in self.children)

    def _min(self, em: "Emitter", a: str, b: str) -> str:
        if self.k == 0:
            return f"min({a}, {b})"
        if self.blend == "quadratic":
            em.require("op_smin")
            return f"opSmin({a}, {b}, {em.num(self.k)})"
        lib, fn = BLEND_GLSL[self.blend]
        em.require(lib)
        return f"{fn}({a}, {b}, {em.num(self.k)})"

    def _max(self, em: "Emitter", a: str, b: str) -> str:
        return f"-{self._min(em, f'(-{a})', f'(-{b})')}" if self.k else f"max({a}, {b})"

    def _fmin(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.minimum(a, b) if self.k == 0 else smooth_min(a, b, self.k, self.blend)

    def _fmax(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return -self._fmin(-a, -b)

    def expr(self, em: "Emitter", q: str) -> str:
        acc = em.assign("float", self.children[0].expr(em, q))
        for c in self.children[1:]:
            acc = em.assign("float", self._fold_glsl(em, acc, em.assign("float", c.expr(em, q))))
        return acc

    def distance2(self, q: np.ndarray) -> np.ndarray:
        acc = self.children[0].distance2(q)
        for c in self.children[1:]:
            acc = self._fold(acc, c.distance2(q))
        return acc

    def _fold_glsl(self, em: "Emitter", a: str, b: str) -> str:
        raise NotImplementedError

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        raise NotImplementedError


class Union2D(_Boolean2D):
    kind = "union2"

    @property
    def exactness(self) -> str:  # type: ignore[override]
        if self.k == 0 and all(c.exactness == EXACT for c in self.children):
            return EXACT  # exact outside, a bound inside, as in 3D
        return super().exactness

    def _fold_glsl(self, em: "Emitter", a: str, b: str) -> str:
        return self._min(em, a, b)

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return self._fmin(a, b)

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        grow = self.k * BLEND_REACH[self.blend]
        return (np.min([c.bounds2[0] for c in self.children], axis=0) - grow,
                np.max([c.bounds2[1] for c in self.children], axis=0) + grow)


class Intersection2D(_Boolean2D):
    kind = "intersection2"

    def _fold_glsl(self, em: "Emitter", a: str, b: str) -> str:
        return self._max(em, a, b)

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return self._fmax(a, b)

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        lo = np.max([c.bounds2[0] for c in self.children], axis=0)
        hi = np.min([c.bounds2[1] for c in self.children], axis=0)
        return lo, np.maximum(hi, lo)


class Difference2D(_Boolean2D):
    kind = "difference2"

    def _fold_glsl(self, em: "Emitter", a: str, b: str) -> str:
        return self._max(em, a, f"(-{b})")

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return self._fmax(a, -b)

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        return self.children[0].bounds2


def union(*shapes: Shape2D, k: float = 0.0, blend: str = "quadratic") -> Union2D:
    """2D union; ``k`` > 0 blends (as sg.union)."""
    return Union2D(*shapes, k=k, blend=blend)


def intersection(*shapes: Shape2D, k: float = 0.0, blend: str = "quadratic") -> Intersection2D:
    """2D intersection; ``k`` > 0 rounds the seam."""
    return Intersection2D(*shapes, k=k, blend=blend)


def difference(*shapes: Shape2D, k: float = 0.0, blend: str = "quadratic") -> Difference2D:
    """The first 2D shape minus the others; ``k`` > 0 rounds the cut."""
    return Difference2D(*shapes, k=k, blend=blend)


class _Unary2D(Shape2D):
    def __init__(self, child: Shape2D, **params: object) -> None:
        super().__init__((child,), **params)
        self.child = child

    @property
    def exactness(self) -> str:  # type: ignore[override]
        return self.child.exactness

    @property
    def lipschitz(self) -> float:  # type: ignore[override]
        return self.child.lipschitz


class Translate2D(_Unary2D):
    kind = "translate2"

    def __init__(self, child: Shape2D, offset: Sequence[float]) -> None:
        off = v.vector(self.kind, "offset", offset, 2)
        super().__init__(child, offset=off)
        self.offset = off

    def expr(self, em: "Emitter", q: str) -> str:
        return self.child.expr(em, em.assign("vec2", f"{q} - {em.vec(self.offset)}"))

    def cap_child(self) -> tuple[Shape2D, float]:
        """Its shape, which may stop a search at the same value (see sdfgl.compiler.guards)."""
        return self.child, 0.0

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return self.child.distance2(q - self.offset)

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds2
        return lo + self.offset, hi + self.offset


class Rotate2D(_Unary2D):
    kind = "rotate2"

    def __init__(self, child: Shape2D, angle: float) -> None:
        a = v.scalar(self.kind, "angle", angle)
        super().__init__(child, angle=a)
        t = math.radians(a)
        c, s = math.cos(t), math.sin(t)
        self.m = np.array([[c, -s], [s, c]])  # world = m @ local

    def expr(self, em: "Emitter", q: str) -> str:
        m = self.m  # local = m^T world; GLSL mat2 is column-major, so mat2(m row-major) is m^T
        return self.child.expr(em, em.assign("vec2", f"mat2({', '.join(em.num(x) for x in m.ravel())}) * {q}"))

    def cap_child(self) -> tuple[Shape2D, float]:
        """Its shape, which may stop a search at the same value (see sdfgl.compiler.guards)."""
        return self.child, 0.0

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return self.child.distance2(q @ self.m)

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds2
        corners = np.array([[x, y] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])]) @ self.m.T
        return corners.min(axis=0), corners.max(axis=0)


class Scale2D(_Unary2D):
    """Uniform scale (exact) or per-axis scale (a bound: f(q / s) * min(s))."""

    kind = "scale2"

    def __init__(self, child: Shape2D, factor: float | Sequence[float]) -> None:
        s = v.vector(self.kind, "factor", factor, 2, positive=True)
        super().__init__(child, factor=s)
        self.s = s

    @property
    def exactness(self) -> str:  # type: ignore[override]
        if self.child.exactness == IMPLICIT or self.s[0] == self.s[1]:
            return self.child.exactness
        return BOUND

    def expr(self, em: "Emitter", q: str) -> str:
        inner = self.child.expr(em, em.assign("vec2", f"{q} / {em.vec(self.s)}"))
        return f"({inner}) * {em.num(self.s.min())}"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return self.child.distance2(q / self.s) * self.s.min()

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds2
        return lo * self.s, hi * self.s


class Round2D(_Unary2D):
    kind = "round2"

    def __init__(self, child: Shape2D, radius: float) -> None:
        r = v.scalar(self.kind, "radius", radius, nonnegative=True)
        super().__init__(child, radius=r)
        self.r = float(r)

    def expr(self, em: "Emitter", q: str) -> str:
        return f"({self.child.expr(em, q)} - {em.num(self.r)})"

    def cap_child(self) -> tuple[Shape2D, float]:
        """Its shape, which may stop a search at the value plus the radius (see sdfgl.compiler.guards)."""
        return self.child, self.r

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return self.child.distance2(q) - self.r

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds2
        return lo - self.r, hi + self.r


class Onion2D(_Unary2D):
    kind = "onion2"

    def __init__(self, child: Shape2D, thickness: float) -> None:
        t = v.scalar(self.kind, "thickness", thickness, positive=True)
        super().__init__(child, thickness=t)
        self.t = float(t) / 2

    def expr(self, em: "Emitter", q: str) -> str:
        return f"(abs({self.child.expr(em, q)}) - {em.num(self.t)})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return np.abs(self.child.distance2(q)) - self.t

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds2
        return lo - self.t, hi + self.t


class Slice(Shape2D):
    """The cross-section of a 3D node by the plane z = 0, as a 2D shape. A bound: the 3D
    distance is never more than the distance within the plane."""

    kind = "slice"

    def __init__(self, node: Node) -> None:
        if not isinstance(node, Node):
            raise ParameterError(f"{self.kind}: needs a 3D sdfgl node, got {type(node).__name__} {node!r}")
        if node.live_params():
            raise ParameterError(f"{self.kind}: the node has live parameters "
                                 f"({', '.join(p.label for p in node.live_params())}); 2D shapes are baked")
        super().__init__()
        self.node = node
        self.bounds2  # refuse an unbounded node now, not at render time

    def label(self) -> str:
        return f"slice({self.node.label()})"

    def key(self) -> tuple:
        return (self.kind, self.node.key)

    @property
    def exactness(self) -> str:  # type: ignore[override]
        return IMPLICIT if self.node.exactness == IMPLICIT else BOUND

    @property
    def lipschitz(self) -> float:  # type: ignore[override]
        return self.node.lipschitz

    def expr(self, em: "Emitter", q: str) -> str:
        r = self.node.emit(em, em.assign("vec3", f"vec3({q}, 0.0)"))
        return f"{r}.w" if em.mode == "color" else r

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return self.node._distance(np.concatenate([q, np.zeros(q.shape[:-1] + (1,))], axis=-1))

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.node.bounds
        if not (np.all(np.isfinite(lo[:2])) and np.all(np.isfinite(hi[:2]))):
            raise ParameterError(f"{self.label()}: the node is unbounded in x or y; a slice needs finite bounds")
        return lo[:2].copy(), hi[:2].copy()


def slice(node: Node) -> Slice:  # noqa: A001 - the name users expect
    """The cross-section of ``node`` at z = 0 as a 2D shape (a distance bound).

    Args:
        node: a 3D node without live parameters (2D shapes are baked).

    Example:
        >>> disc = sg.slice(sg.sphere(1))
        >>> disc.exactness, float(sg.extrude(disc, 0.2).distance((2, 0, 0)))
        ('bound', 1.0)
    """
    return Slice(node)
