"""2D shapes in the XY plane, made solid by extrude (along Z) or revolve (about Y)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from . import validate as v
from .base import BOUND, EXACT, Node

if TYPE_CHECKING:  # pragma: no cover
    from .polygrid import PolygonGrid
    from ..codegen import Emitter


class Shape2D:
    """A 2D signed distance: GLSL over a vec2, numpy over (..., 2), and its bounds."""

    kind = "shape2d"
    exactness = EXACT

    def __init__(self, **params: object) -> None:
        v.fixed(self.kind, "2D shapes are baked", **params)
        self.params = params

    def label(self) -> str:
        def fmt(x: object) -> str:
            return "(" + ", ".join(f"{y:g}" for y in np.ravel(x)) + ")" if isinstance(x, np.ndarray) else f"{x:g}"
        return f"{self.kind}({', '.join(f'{k}={fmt(x)}' for k, x in self.params.items())})"

    def key(self) -> tuple:
        return (self.kind, tuple((k, tuple(np.ravel(x).tolist())) for k, x in self.params.items()))

    def expr(self, em: "Emitter", q: str) -> str:
        raise NotImplementedError

    def distance2(self, q: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        raise NotImplementedError

    # -- making solids ------------------------------------------------------------------
    def extrude(self, height: float) -> "Extrude":
        return Extrude(self, height)

    def revolve(self, offset: float = 0.0) -> "Revolve":
        return Revolve(self, offset)


class Circle(Shape2D):
    kind = "circle"

    def __init__(self, radius: float = 0.5, center: Sequence[float] = (0.0, 0.0)) -> None:
        r = v.scalar(self.kind, "radius", radius, positive=True)
        c = v.vector(self.kind, "center", center, 2)
        super().__init__(radius=r, center=c)
        self.r, self.c = r, c

    def expr(self, em: "Emitter", q: str) -> str:
        return f"(length({q} - {em.vec(self.c)}) - {em.num(self.r)})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return np.linalg.norm(q - self.c, axis=-1) - self.r

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        return self.c - self.r, self.c + self.r


class Rectangle(Shape2D):
    kind = "rectangle"

    def __init__(self, size: float | Sequence[float] = 1.0, radius: float = 0.0) -> None:
        s = v.vector(self.kind, "size", size, 2, positive=True)
        r = v.scalar(self.kind, "radius", radius, nonnegative=True)
        v.at_most_half_edge(self.kind, "radius", r, s, edge="side")
        super().__init__(size=s, radius=r)
        self.half, self.r = s / 2, r

    def expr(self, em: "Emitter", q: str) -> str:
        em.require("sd2_box")
        return f"sd2Box({q}, {em.vec(self.half)}, {em.num(self.r)})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        k = np.abs(q) - self.half + self.r
        return np.linalg.norm(np.maximum(k, 0.0), axis=-1) + np.minimum(k.max(axis=-1), 0.0) - self.r

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        return -self.half, self.half.copy()


class Polygon(Shape2D):
    """A simple (non self-intersecting) polygon through ``points`` in order."""

    kind = "polygon"

    def __init__(self, points: Sequence[Sequence[float]]) -> None:
        try:
            pts = np.array([v.vector(self.kind, f"points[{i}]", p, 2) for i, p in enumerate(points)])
        except TypeError:
            raise ParameterError(f"{self.kind}: 'points' must be a list of (x, y) pairs") from None
        if len(pts) < 3:
            raise ParameterError(f"{self.kind}: needs at least 3 points, got {len(pts)}")
        if np.any(np.linalg.norm(np.diff(np.vstack([pts, pts[:1]]), axis=0), axis=1) == 0):
            raise ParameterError(f"{self.kind}: two consecutive points coincide")
        super().__init__(points=pts)
        self.v = pts

    def expr(self, em: "Emitter", q: str) -> str:
        from .. import shaderlib
        n = len(self.v)
        grid = self.grid
        if grid is not None:  # many vertices: edges listed per cell of a 2D grid
            em.require("sd_polygon_grid")
            cells, edges = em.table(grid.cells), em.table(grid.edges)
            return f"sdPolygonGrid({q}, {grid.defines(em, 'g', cells, edges)})"
        if n >= em.data_min:  # vertices as data: a loop over a texture, not an unrolled array
            em.require("sd_polygon_data")
            return f"sdPolygonData({q}, {em.table(self.v)}, {n})"
        em.helper(f"sdPolygon{n}", shaderlib.read("lib/sd_polygon").replace("POLYN", str(n)))
        verts = ", ".join(em.vec(p) for p in self.v)
        return f"sdPolygon{n}({q}, vec2[{n}]({verts}))"

    @property
    def grid(self) -> "PolygonGrid | None":
        """The edge grid of a polygon with at least GRID_VERTICES vertices, else None."""
        from .polygrid import GRID_VERTICES, PolygonGrid
        if "_grid" not in self.__dict__:
            self.__dict__["_grid"] = PolygonGrid(self.v) if len(self.v) >= GRID_VERTICES else None
        return self.__dict__["_grid"]

    def distance2(self, q: np.ndarray) -> np.ndarray:
        d = self._exact2(q)
        grid = self.grid
        return d if grid is None else np.sign(d) * np.minimum(np.abs(d), grid.cap(q))

    def _exact2(self, q: np.ndarray) -> np.ndarray:
        v = self.v
        d = np.sum((q - v[0]) ** 2, axis=-1)
        s = np.ones(q.shape[:-1])
        n = len(v)
        for i in range(n):
            j = (i - 1) % n
            e, w = v[j] - v[i], q - v[i]
            b = w - e * np.clip((w @ e) / (e @ e), 0.0, 1.0)[..., None]
            d = np.minimum(d, np.sum(b * b, axis=-1))
            c1, c2 = q[..., 1] >= v[i][1], q[..., 1] < v[j][1]
            c3 = e[0] * w[..., 1] > e[1] * w[..., 0]
            flip = (c1 & c2 & c3) | (~c1 & ~c2 & ~c3)
            s = np.where(flip, -s, s)
        return s * np.sqrt(d)

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        return self.v.min(axis=0), self.v.max(axis=0)


class Extrude(Node):
    """A 2D shape (in XY) extruded along Z to full ``height``, centred on z = 0."""

    kind = "extrude"

    def __init__(self, shape: Shape2D, height: float) -> None:
        if not isinstance(shape, Shape2D):
            raise ParameterError(f"{self.kind}: needs a 2D shape, got {type(shape).__name__}")
        h = v.scalar(self.kind, "height", height, positive=True)
        super().__init__((), shape=shape.key(), height=h)
        self.shape, self.h = shape, float(h) / 2

    def label(self) -> str:
        return f"extrude({self.shape.label()}, height={2 * self.h:g})"

    @property
    def exactness(self) -> str:
        return BOUND if getattr(self.shape, "grid", None) is not None else EXACT

    def _emit(self, em: "Emitter", p: str) -> str:
        em.require("op_extrude")
        pt = em.point(p)
        d = em.assign("float", f"opExtrude({self.shape.expr(em, f'{pt}.xy')}, {pt}.z, {em.num(self.h)})")
        return em.with_color(d)

    def _distance(self, p: np.ndarray) -> np.ndarray:
        d2 = self.shape.distance2(p[..., :2])
        wx, wy = d2, np.abs(p[..., 2]) - self.h
        return np.minimum(np.maximum(wx, wy), 0.0) + np.hypot(np.maximum(wx, 0.0), np.maximum(wy, 0.0))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.shape.bounds2
        return np.array([lo[0], lo[1], -self.h]), np.array([hi[0], hi[1], self.h])


class Revolve(Node):
    """A 2D shape (x: distance from the Y axis minus ``offset``, y: height) revolved about Y."""

    kind = "revolve"

    def __init__(self, shape: Shape2D, offset: float = 0.0) -> None:
        if not isinstance(shape, Shape2D):
            raise ParameterError(f"{self.kind}: needs a 2D shape, got {type(shape).__name__}")
        o = v.scalar(self.kind, "offset", offset, nonnegative=True)
        super().__init__((), shape=shape.key(), offset=o)
        self.shape, self.o = shape, float(o)

    def label(self) -> str:
        return f"revolve({self.shape.label()}, offset={self.o:g})"

    @property
    def exactness(self) -> str:
        return BOUND if getattr(self.shape, "grid", None) is not None else EXACT

    def _emit(self, em: "Emitter", p: str) -> str:
        pt = em.point(p)
        q = em.assign("vec2", f"vec2(length({pt}.xz) - {em.num(self.o)}, {pt}.y)")
        return em.with_color(em.assign("float", self.shape.expr(em, q)))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        q = np.stack([np.hypot(p[..., 0], p[..., 2]) - self.o, p[..., 1]], axis=-1)
        return self.shape.distance2(q)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.shape.bounds2
        r = max(abs(lo[0] + self.o), abs(hi[0] + self.o))
        return np.array([-r, lo[1], -r]), np.array([r, hi[1], r])


def circle(radius: float = 0.5, center: Sequence[float] = (0.0, 0.0)) -> Circle:
    """A 2D circle."""
    return Circle(radius, center)


def rectangle(size: float | Sequence[float] = 1.0, radius: float = 0.0) -> Rectangle:
    """A 2D rectangle of full ``size``, corners rounded by ``radius``."""
    return Rectangle(size, radius)


def polygon(points: Sequence[Sequence[float]]) -> Polygon:
    """A 2D simple polygon."""
    return Polygon(points)


def extrude(shape: Shape2D, height: float) -> Extrude:
    """Extrude a 2D shape along Z to full ``height``. Exact."""
    return Extrude(shape, height)


def revolve(shape: Shape2D, offset: float = 0.0) -> Revolve:
    """Revolve a 2D shape about the Y axis, its x measured from ``offset``. Exact."""
    return Revolve(shape, offset)
