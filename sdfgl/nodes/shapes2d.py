"""2D shapes in the XY plane, made solid by extrude (along Z) or revolve (about Y)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import BOUND, EXACT, Node
from .layouts import layout
from .record import Recorded

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.data.polygrid import PolygonGrid
    from ..compiler.emitter import Emitter


class Shape2D(Recorded, register=False):
    """A 2D signed distance: GLSL over a vec2, numpy over (..., 2), and its bounds.

    Shapes combine like 3D nodes (``a | b``, ``a & b``, ``a - b``, ``sg.union(..., k=)``),
    move (``translate``, ``rotate``, ``scale``), round and onion, and become solids by
    ``extrude`` or ``revolve``. Each keeps its exactness and Lipschitz factor.

    Example:
        >>> ring = sg.circle(1) - sg.rectangle(1)
        >>> isinstance(ring, sg.Shape2D), float(sg.extrude(ring, 0.2).distance((0, 0, 0)))
        (True, 0.5)
    """

    kind = "shape2d"
    exactness = EXACT
    lipschitz = 1.0

    def __init__(self, children: Sequence["Shape2D"] = (), **params: object) -> None:
        v.fixed(self.kind, "2D shapes are baked", **params)
        for i, c in enumerate(children):
            if not isinstance(c, Shape2D):
                raise ParameterError(f"{self.kind}: operand {i} must be a 2D shape, got {type(c).__name__} {c!r}")
        self.children: tuple[Shape2D, ...] = tuple(children)
        self.params = params

    @property
    def costly(self) -> bool:
        """Whether its GLSL costs far more than a box test (see sdfgl.compiler.guards): where a part's does."""
        return any(c.costly for c in self.children)

    def label(self) -> str:
        def fmt(x: object) -> str:
            if isinstance(x, str):
                return x
            return "(" + ", ".join(f"{y:g}" for y in np.ravel(x)) + ")" if isinstance(x, np.ndarray) else f"{x:g}"
        own = f"{self.kind}({', '.join(f'{k}={fmt(x)}' for k, x in self.params.items())})"
        return own if not self.children else f"{own}[{', '.join(c.label() for c in self.children)}]"

    def __repr__(self) -> str:
        return self.label()

    def key(self) -> tuple:
        def freeze(x: object) -> object:
            return x if isinstance(x, str) else tuple(np.ravel(x).tolist())
        return (self.kind, tuple((k, freeze(x)) for k, x in self.params.items()), tuple(c.key() for c in self.children))

    def expr(self, em: "Emitter", q: str) -> str:
        raise NotImplementedError

    def distance2(self, q: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        raise NotImplementedError

    # -- combining and moving (sdfgl.nodes.shapes2d_ops) ---------------------------------
    def _op(self, name: str, other: object) -> "Shape2D":
        from . import shapes2d_ops as ops
        if not isinstance(other, Shape2D):
            raise ParameterError(f"2D {name}: both operands must be 2D shapes (extrude or revolve a 2D shape to "
                                 f"combine it with 3D nodes), got {type(other).__name__}")
        return getattr(ops, name)(self, other)

    def __or__(self, other: object) -> "Shape2D":
        return self._op("union", other)

    def __and__(self, other: object) -> "Shape2D":
        return self._op("intersection", other)

    def __sub__(self, other: object) -> "Shape2D":
        return self._op("difference", other)

    def translate(self, offset: Sequence[float]) -> "Shape2D":
        from .shapes2d_ops import Translate2D
        return Translate2D(self, offset)

    def rotate(self, angle: float) -> "Shape2D":
        """Rotate by ``angle`` degrees (counter-clockwise) about the origin."""
        from .shapes2d_ops import Rotate2D
        return Rotate2D(self, angle)

    def scale(self, factor: float | Sequence[float]) -> "Shape2D":
        """Scale uniformly (exactness kept) or per axis (a bound)."""
        from .shapes2d_ops import Scale2D
        return Scale2D(self, factor)

    def round(self, radius: float) -> "Shape2D":
        """Grow by ``radius``: rounded corners."""
        from .shapes2d_ops import Round2D
        return Round2D(self, radius)

    def onion(self, thickness: float) -> "Shape2D":
        """A band ``thickness`` wide around the outline."""
        from .shapes2d_ops import Onion2D
        return Onion2D(self, thickness)

    # -- making solids ------------------------------------------------------------------
    def extrude(self, height: float, taper: float = 0.0, twist: float = 0.0) -> "Node":
        return extrude(self, height, taper, twist)

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


POLYGON_BLOCK = 1 << 21  # points x edges per block of the polygon's twin
COSTLY_VERTICES = 16  # a polygon of this many vertices costs far more than a box test


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
        em.helper(f"sdPolygon{n}", shaderlib.read("templates/sd_polygon").replace("POLYN", str(n)))
        verts = ", ".join(em.vec(p) for p in self.v)
        return f"sdPolygon{n}({q}, vec2[{n}]({verts}))"

    @property
    def costly(self) -> bool:  # type: ignore[override]
        """A polygon of many vertices: its code loops over them (see sdfgl.compiler.guards)."""
        return len(self.v) >= COSTLY_VERTICES

    @property
    def exactness(self) -> str:  # type: ignore[override]
        """Exact, or a bound where the edge grid's cap limits the distance far from the edges."""
        return BOUND if self.grid is not None else EXACT

    @property
    def grid(self) -> "PolygonGrid | None":
        """The edge grid of a polygon with many vertices (sdfgl.compiler.data.polygrid), else None."""
        if "_grid" not in self.__dict__:
            build = layout("polygon")
            self.__dict__["_grid"] = build(self.v) if build is not None else None
        return self.__dict__["_grid"]

    def distance2(self, q: np.ndarray) -> np.ndarray:
        d = self._exact2(q)
        grid = self.grid
        return d if grid is None else np.sign(d) * np.minimum(np.abs(d), grid.cap(q))

    def _exact2(self, q: np.ndarray) -> np.ndarray:
        """The exact signed distance at (..., 2) points: every edge at once, in blocks of points."""
        pts = np.asarray(q, dtype=np.float64).reshape(-1, 2)
        out = np.empty(len(pts))
        block = max(1, POLYGON_BLOCK // len(self.v))
        for s in range(0, len(pts), block):
            out[s:s + block] = self._exact_block(pts[s:s + block])
        return out.reshape(np.shape(q)[:-1])

    def _exact_block(self, q: np.ndarray) -> np.ndarray:
        vi = self.v
        vj = np.roll(vi, 1, axis=0)  # edge i runs from vertex i - 1 to vertex i
        e, w = vj - vi, q[:, None, :] - vi[None]
        t = np.clip((w * e).sum(axis=-1) / (e * e).sum(axis=-1), 0.0, 1.0)
        b = w - e * t[..., None]
        d = (b * b).sum(axis=-1).min(axis=1)
        c1, c2 = q[:, None, 1] >= vi[:, 1], q[:, None, 1] < vj[:, 1]
        c3 = e[:, 0] * w[..., 1] > e[:, 1] * w[..., 0]
        flips = ((c1 & c2 & c3) | (~c1 & ~c2 & ~c3)).sum(axis=1)
        return np.where(flips % 2 == 1, -1.0, 1.0) * np.sqrt(d)

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        """The vertices' box, or a large polygon's edge-grid box around it (its capped field can
        be below the distance to the vertices' box between the two)."""
        lo, hi = self.v.min(axis=0), self.v.max(axis=0)
        grid = self.grid
        if grid is None:
            return lo, hi
        glo, ghi = grid.box()
        return np.minimum(lo, glo), np.maximum(hi, ghi)


class SweptShape(Node):
    """A solid made from a 2D shape (``shape``): its exactness and Lipschitz factor are the
    shape's, and so is the cost of its code."""

    shape: Shape2D

    @property
    def exactness(self) -> str:
        return self.shape.exactness

    @property
    def lipschitz(self) -> float:
        return self.shape.lipschitz

    @property
    def costly(self) -> bool:  # type: ignore[override]
        """Where its 2D shape's code is costly (see sdfgl.compiler.guards)."""
        return self.shape.costly

    def cap_target(self) -> Shape2D:
        """The shape that may stop its search at a positive value the caller ignores (its
        values at or above it keep this node's there; see sdfgl.compiler.guards)."""
        return self.shape


class Extrude(SweptShape):
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


class Revolve(SweptShape):
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
    """A 2D circle in the XY plane, made solid by :func:`extrude` or :func:`revolve`.

    Args:
        radius: radius, > 0.
        center: centre (x, y).

    Exact (in 2D).

    Example:
        >>> sg.extrude(sg.circle(0.5), 0.2).exactness
        'exact'
    """
    return Circle(radius, center)


def rectangle(size: float | Sequence[float] = 1.0, radius: float = 0.0) -> Rectangle:
    """A 2D rectangle centred at the origin of the XY plane.

    Args:
        size: full side lengths (a number or (sx, sy)), > 0.
        radius: corner rounding radius, 0 .. half the smaller side.

    Exact (in 2D).

    Example:
        >>> float(sg.extrude(sg.rectangle((2, 1)), 1.0).distance((2, 0, 0)))
        1.0
    """
    return Rectangle(size, radius)


def polygon(points: Sequence[Sequence[float]]) -> Polygon:
    """A 2D simple polygon (no self-intersections) in the XY plane.

    Args:
        points: 3 or more (x, y) vertices in order (either winding).

    Exact (in 2D).

    Example:
        >>> tri = sg.polygon([(0, 0), (1, 0), (0, 1)])
        >>> sg.extrude(tri, 0.2).exactness
        'exact'
    """
    return Polygon(points)


def extrude(shape: Shape2D, height: float, taper: float = 0.0, twist: float = 0.0) -> Node:
    """Extrude a 2D shape along Z, centred on z = 0.

    Args:
        shape: a 2D shape (:func:`circle`, :func:`rectangle`, :func:`polygon`, ...).
        height: full height along Z (from -height/2 to height/2), > 0.
        taper: the shape shrinks linearly from full size at the bottom (z = -height/2) to
            (1 - taper) times it at the top (negative widens it); < 1.
        twist: degrees the shape turns (counter-clockwise seen from +Z) from bottom to top.

    Exact where the shape is, without taper and twist. Both are warps
    (sdfgl.nodes.deform) that divide only this solid's field by their own stretch.

    Example:
        >>> float(sg.extrude(sg.circle(0.5), 1.0).distance((0, 0, 1.5)))
        1.0
        >>> sg.extrude(sg.rectangle(1), 2.0, twist=90).exactness
        'bound'
    """
    t = v.scalar("extrude", "taper", taper)
    w = v.scalar("extrude", "twist", twist)
    v.fixed("extrude", "taper and twist are compiled into the warp", taper=t, twist=w)
    if not t < 1.0:
        raise ParameterError(f"extrude: parameter 'taper' must be < 1 (1 shrinks the top to a point), got {t:g}")
    node: Node = Extrude(shape, height)
    h = 2.0 * float(node.h)  # type: ignore[attr-defined]
    if w:
        from .deform import Twist
        node = Twist(node, -w / h, "z")  # q = R(-a) p: the shape turns counter-clockwise by a
    if t:
        from .deform import Taper
        node = Taper(node, -t / h, axis="z", origin=-h / 2)
    return node


def revolve(shape: Shape2D, offset: float = 0.0) -> Revolve:
    """Revolve a 2D shape about the Y axis: its x is the distance from the axis minus ``offset``.

    Args:
        shape: a 2D shape in the XY plane.
        offset: distance of the shape's origin from the Y axis (>= 0 or negative).

    Exact.

    Example:
        >>> float(sg.revolve(sg.circle(0.25), 1.0).distance((0, 0, 1)))
        -0.25
    """
    return Revolve(shape, offset)
