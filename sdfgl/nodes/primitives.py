"""Primitive solids. Formulas after Inigo Quilez's distance-function article (MIT).

Conventions: Y is up, sizes are full edge lengths (as in fogleman/sdf), cylinders,
cones, capsules and prisms run along Y, the torus lies in the XZ plane.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from ..params import Live
from .base import INF, Primitive

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter


def _len(a: np.ndarray) -> np.ndarray:
    return np.sqrt(np.sum(a * a, axis=-1))


def _box_of(half: Any) -> tuple[np.ndarray, np.ndarray]:
    h = np.asarray(half, dtype=np.float64)
    return -h, h.copy()


ORIGIN = (0.0, 0.0, 0.0)
_ORIGIN = np.zeros(3)
_ORIGIN.flags.writeable = False  # shared by every sphere left at the origin


class Sphere(Primitive):
    kind = "sphere"
    lib = ("sd_sphere",)
    rebuilt_from = ("r", "c")

    def __init__(self, radius: float = 1.0, center: Sequence[float] = ORIGIN) -> None:
        r = v.scalar(self.kind, "radius", radius, positive=True)
        c = _ORIGIN if center is ORIGIN else v.vector(self.kind, "center", center)
        super().__init__(radius=r, center=c)
        self.r, self.c = r, c

    def _expr(self, em: "Emitter", p: str) -> str:
        q = f"({p} - {em.vec(self.c)})" if isinstance(self.c, Live) or self.c.any() else p
        return f"sdSphere({q}, {em.num(self.r)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return _len(p - self.c) - self.r

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.c - self.r, self.c + self.r

    @classmethod
    def batch_bounds(cls, nodes: Sequence[Node]) -> np.ndarray | None:
        if not all(type(n.r) is float and type(n.c) is np.ndarray for n in nodes):
            return None  # a live radius or centre: one by one
        c = np.array([n.c for n in nodes])
        r = np.array([n.r for n in nodes])[:, None]
        return np.stack([c - r, c + r], axis=1)


class Box(Primitive):
    kind = "box"
    lib = ("sd_box",)

    def __init__(self, size: float | Sequence[float] = 1.0) -> None:
        s = v.vector(self.kind, "size", size, positive=True)
        super().__init__(size=s)
        self.half = s / 2

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdBox({p}, {em.vec(self.half)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        q = np.abs(p) - self.half
        return _len(np.maximum(q, 0.0)) + np.minimum(q.max(axis=-1), 0.0)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return _box_of(self.half)


class RoundedBox(Primitive):
    kind = "rounded_box"
    lib = ("sd_round_box",)

    def __init__(self, size: float | Sequence[float] = 1.0, radius: float = 0.1) -> None:
        s = v.vector(self.kind, "size", size, positive=True)
        r = v.scalar(self.kind, "radius", radius, nonnegative=True)
        v.at_most_half_edge(self.kind, "radius", r, s)
        super().__init__(size=s, radius=r)
        self.half, self.r = s / 2, r

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdRoundBox({p}, {em.vec(self.half)}, {em.num(self.r)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        q = np.abs(p) - self.half + self.r
        return _len(np.maximum(q, 0.0)) + np.minimum(q.max(axis=-1), 0.0) - self.r

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return _box_of(self.half)


class Plane(Primitive):
    """Half-space below the plane through ``point`` with normal ``normal`` (solid side opposite the normal)."""

    kind = "plane"
    lib = ("sd_plane",)

    def __init__(self, normal: Sequence[float] = (0.0, 1.0, 0.0), point: Sequence[float] = (0.0, 0.0, 0.0)) -> None:
        n = v.vector(self.kind, "normal", normal, nonzero=True)
        o = v.vector(self.kind, "point", point)
        if not isinstance(n, Live):
            n = n / np.linalg.norm(n)
        super().__init__(normal=n, point=o)
        self.n, self.o = n, o

    def _unit_normal(self) -> np.ndarray:
        n = np.asarray(self.n, dtype=np.float64)
        return n / np.linalg.norm(n)

    def _expr(self, em: "Emitter", p: str) -> str:
        n = f"normalize({em.vec(self.n)})" if isinstance(self.n, Live) else em.vec(self.n)
        return f"sdPlane({p}, {n}, {em.vec(self.o)})"

    def _emit(self, em: "Emitter", p: str) -> str:
        if isinstance(self.n, Live) or isinstance(self.o, Live):
            return super()._emit(em, p)
        # dot(p - o, n) with o folded into the point's offset along n only (float64): exact
        # to float32 rounding of p however far o and the shader origin lie from each other
        n = self._unit_normal()
        q = em.point(em.shift(p, -np.asarray(self.o, dtype=np.float64)), along=n)
        em.require(*self.lib)
        return em.with_color(em.assign("float", f"sdPlane({q}, {em.vec(n)}, vec3(0.0))"))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return (p - self.o) @ self._unit_normal()

    def analytic_plane(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(unit normal, point) of this plane, or None where a parameter is live."""
        if any(isinstance(x, Live) for x in self.params.values()):
            return None
        return self._unit_normal(), np.asarray(self.o, dtype=float)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = np.full(3, -INF), np.full(3, INF)
        n, o = self._unit_normal(), np.asarray(self.o, dtype=np.float64)
        axis = int(np.argmax(np.abs(n)))
        if abs(n[axis]) == 1.0 and not isinstance(self.n, Live):  # axis-aligned: one side is finite
            if n[axis] > 0:
                hi[axis] = o[axis]
            else:
                lo[axis] = o[axis]
        return lo, hi


class Torus(Primitive):
    kind = "torus"
    lib = ("sd_torus",)

    def __init__(self, r1: float = 1.0, r2: float = 0.25) -> None:
        a = v.scalar(self.kind, "r1", r1, positive=True)
        b = v.scalar(self.kind, "r2", r2, positive=True)
        super().__init__(r1=a, r2=b)
        self.r1, self.r2 = a, b

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdTorus({p}, vec2({em.num(self.r1)}, {em.num(self.r2)}))"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        qx = np.hypot(p[..., 0], p[..., 2]) - self.r1
        return np.hypot(qx, p[..., 1]) - self.r2

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        e = self.r1 + self.r2
        return _box_of(np.array([float(e), float(self.r2), float(e)]))


class Capsule(Primitive):
    kind = "capsule"
    lib = ("sd_capsule",)

    def __init__(self, a: Sequence[float] = (0.0, -0.5, 0.0), b: Sequence[float] = (0.0, 0.5, 0.0),
                 radius: float = 0.25) -> None:
        pa = v.vector(self.kind, "a", a)
        pb = v.vector(self.kind, "b", b)
        r = v.scalar(self.kind, "radius", radius, positive=True)
        def check() -> None:
            if np.array_equal(np.asarray(pa, float), np.asarray(pb, float)):
                raise ParameterError(f"{self.kind}: end points 'a' and 'b' coincide at "
                                     f"{tuple(np.asarray(pa, float))}; use sphere()")
        v.watch(check, pa, pb)
        super().__init__(a=pa, b=pb, radius=r)
        self.a, self.b, self.r = pa, pb, r

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdCapsule({p}, {em.vec(self.a)}, {em.vec(self.b)}, {em.num(self.r)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        pa, ba = p - self.a, self.b - self.a
        h = np.clip((pa @ ba) / (ba @ ba), 0.0, 1.0)
        return _len(pa - h[..., None] * ba) - self.r

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        a, b, r = np.asarray(self.a, float), np.asarray(self.b, float), float(self.r)
        return np.minimum(a, b) - r, np.maximum(a, b) + r


class Cylinder(Primitive):
    kind = "cylinder"
    lib = ("sd_cylinder",)

    def __init__(self, radius: float = 0.5, height: float = 1.0) -> None:
        r = v.scalar(self.kind, "radius", radius, positive=True)
        h = v.scalar(self.kind, "height", height, positive=True)
        super().__init__(radius=r, height=h)
        self.r, self.h = r, h / 2

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdCylinder({p}, {em.num(self.r)}, {em.num(self.h)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        dx = np.hypot(p[..., 0], p[..., 2]) - self.r
        dy = np.abs(p[..., 1]) - self.h
        return np.minimum(np.maximum(dx, dy), 0.0) + np.hypot(np.maximum(dx, 0.0), np.maximum(dy, 0.0))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return _box_of(np.array([float(self.r), float(self.h), float(self.r)]))


class Cone(Primitive):
    kind = "cone"
    lib = ("sd_cone",)

    def __init__(self, height: float = 1.0, r1: float = 0.5, r2: float = 0.0) -> None:
        h = v.scalar(self.kind, "height", height, positive=True)
        a = v.scalar(self.kind, "r1", r1, nonnegative=True)
        b = v.scalar(self.kind, "r2", r2, nonnegative=True)
        def check() -> None:
            if float(a) == 0 and float(b) == 0:
                raise ParameterError(f"{self.kind}: radii 'r1' and 'r2' are both 0; the cone is empty")
        v.watch(check, a, b)
        super().__init__(height=h, r1=a, r2=b)
        self.h, self.r1, self.r2 = h / 2, a, b

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdCone({p}, {em.num(self.h)}, {em.num(self.r1)}, {em.num(self.r2)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        qx, qy = np.hypot(p[..., 0], p[..., 2]), p[..., 1]
        r1, r2, hh = float(self.r1), float(self.r2), float(self.h)
        k1 = np.array([r2, hh])
        k2 = np.array([r2 - r1, 2 * hh])
        rr = np.where(qy < 0, r1, r2)
        cax, cay = qx - np.minimum(qx, rr), np.abs(qy) - hh
        q = np.stack([qx, qy], axis=-1)
        t = np.clip(((k1 - q) @ k2) / (k2 @ k2), 0.0, 1.0)
        cb = q - k1 + t[..., None] * k2
        s = np.where((cb[..., 0] < 0) & (cay < 0), -1.0, 1.0)
        return s * np.sqrt(np.minimum(cax * cax + cay * cay, np.sum(cb * cb, axis=-1)))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        r = max(float(self.r1), float(self.r2))
        return _box_of(np.array([r, float(self.h), r]))


class Ellipsoid(Primitive):
    """Ellipsoid with semi-axes ``radii``: a distance bound (1-Lipschitz), not exact."""

    kind = "ellipsoid"
    lib = ("sd_ellipsoid",)
    exact = False

    def __init__(self, radii: float | Sequence[float] = (1.0, 0.5, 0.75)) -> None:
        r = v.vector(self.kind, "radii", radii, positive=True)
        super().__init__(radii=r)
        self.r = r

    def level_stretch(self) -> float:
        r = np.asarray(self.r, dtype=np.float64)  # f >= (|p / r| - 1) min(r): a box gap D gives D min(r) / max(r)
        return float(r.max() / r.min())

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdEllipsoid({p}, {em.vec(self.r)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        r = np.asarray(self.r, dtype=np.float64)
        near = (_len(p / r) - 1.0) * r.min()
        far = _len(p) - r.max()
        return np.maximum(near, far)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return _box_of(self.r)


class Octahedron(Primitive):
    kind = "octahedron"
    lib = ("sd_octahedron",)

    def __init__(self, size: float = 1.0) -> None:
        s = v.scalar(self.kind, "size", size, positive=True)
        super().__init__(size=s)
        self.s = s

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdOctahedron({p}, {em.num(self.s)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        s = self.s
        a = np.abs(p)
        m = a.sum(axis=-1) - s
        x, y, z = a[..., 0], a[..., 1], a[..., 2]
        cx, cy, cz = 3 * x < m, 3 * y < m, 3 * z < m
        q = np.where(cx[..., None], a, np.where(cy[..., None], np.stack([y, z, x], -1),
                                                  np.stack([z, x, y], -1)))
        k = np.clip(0.5 * (q[..., 2] - q[..., 1] + s), 0.0, s)
        edge = np.sqrt(q[..., 0] ** 2 + (q[..., 1] - s + k) ** 2 + (q[..., 2] - k) ** 2)
        return np.where(cx | cy | cz, edge, m * 0.57735027)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return _box_of(np.full(3, self.s))


class HexPrism(Primitive):
    """Hexagonal prism along Y; ``radius`` is the inradius (centre to a flat side)."""

    kind = "hex_prism"
    lib = ("sd_hex_prism",)

    def __init__(self, radius: float = 0.5, height: float = 1.0) -> None:
        r = v.scalar(self.kind, "radius", radius, positive=True)
        h = v.scalar(self.kind, "height", height, positive=True)
        super().__init__(radius=r, height=h)
        self.r, self.h = r, h / 2

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdHexPrism({p}, {em.num(self.r)}, {em.num(self.h)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        kx, ky, kz = -0.8660254, 0.5, 0.57735027
        x, y, z = np.abs(p[..., 0]), np.abs(p[..., 2]), np.abs(p[..., 1])
        dk = np.minimum(kx * x + ky * y, 0.0)
        x, y = x - 2 * dk * kx, y - 2 * dk * ky
        cx = np.clip(x, -kz * self.r, kz * self.r)
        dx = np.hypot(x - cx, y - self.r) * np.sign(y - self.r)
        dy = z - self.h
        return np.minimum(np.maximum(dx, dy), 0.0) + np.hypot(np.maximum(dx, 0.0), np.maximum(dy, 0.0))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        rc = self.r / 0.8660254037844386
        return _box_of(np.array([float(rc), float(self.h), float(rc)]))


class BoxFrame(Primitive):
    """The twelve edges of a box of full size ``size``, as bars ``thickness`` thick."""

    kind = "box_frame"
    lib = ("sd_box_frame",)

    def __init__(self, size: float | Sequence[float] = 1.0, thickness: float = 0.05) -> None:
        s = v.vector(self.kind, "size", size, positive=True)
        e = v.scalar(self.kind, "thickness", thickness, positive=True)
        v.at_most_half_edge(self.kind, "thickness", e, s)
        super().__init__(size=s, thickness=e)
        self.half, self.e = s / 2, e / 2

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdBoxFrame({p}, {em.vec(self.half)}, {em.num(self.e)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        p = np.abs(p) - self.half
        q = np.abs(p + self.e) - self.e
        def part(a: np.ndarray) -> np.ndarray:
            return _len(np.maximum(a, 0.0)) + np.minimum(a.max(axis=-1), 0.0)
        px, py, pz = p[..., :1], p[..., 1:2], p[..., 2:]
        qx, qy, qz = q[..., :1], q[..., 1:2], q[..., 2:]
        return np.minimum(np.minimum(part(np.concatenate([px, qy, qz], -1)),
                                     part(np.concatenate([qx, py, qz], -1))),
                          part(np.concatenate([qx, qy, pz], -1)))

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return _box_of(self.half)


def sphere(radius: float = 1.0, center: Sequence[float] = ORIGIN) -> Sphere:
    """Sphere of ``radius`` centred at ``center``.

    Args:
        radius: radius in scene units, > 0 (a number or a live ``sg.param``).
        center: centre point (x, y, z) in scene units (or a live 3-vector).

    Exact: ``distance()`` is the Euclidean distance to the surface (negative inside).

    Example:
        >>> float(sg.sphere(1.0, center=(0, 1, 0)).distance((0, 3, 0)))
        1.0
    """
    return Sphere(radius, center)


def box(size: float | Sequence[float] = 1.0) -> Box:
    """Axis-aligned box centred at the origin.

    Args:
        size: full edge lengths: one number for a cube or (sx, sy, sz), each > 0 (as in
            fogleman/sdf; the half-extents are size / 2).

    Exact.

    Example:
        >>> float(sg.box((2, 1, 1)).distance((3, 0, 0)))
        2.0
    """
    return Box(size)


def rounded_box(size: float | Sequence[float] = 1.0, radius: float = 0.1) -> RoundedBox:
    """Box of full edge lengths ``size`` with its edges rounded by ``radius``.

    Args:
        size: full edge lengths (a number or (sx, sy, sz)), > 0.
        radius: rounding radius, 0 <= radius <= half the smallest edge. The outer size is kept.

    Exact.

    Example:
        >>> float(sg.rounded_box(2, 0.5).distance((2, 0, 0)))
        1.0
    """
    return RoundedBox(size, radius)


def plane(normal: Sequence[float] = (0.0, 1.0, 0.0), point: Sequence[float] = (0.0, 0.0, 0.0)) -> Plane:
    """Half-space behind the plane through ``point`` facing ``normal`` (solid opposite the normal).

    Args:
        normal: outward normal (x, y, z), not zero; normalised here.
        point: a point on the plane.

    Exact. Unbounded: the renderer intersects a lone plane in closed form.

    Example:
        >>> float(sg.plane((0, 1, 0), (0, -1, 0)).distance((0, 2, 0)))
        3.0
    """
    return Plane(normal, point)


def torus(r1: float = 1.0, r2: float = 0.25) -> Torus:
    """Torus lying in the XZ plane (around the Y axis), centred at the origin.

    Args:
        r1: major radius (centre of the tube to the Y axis), > 0.
        r2: tube radius, > 0.

    Exact.

    Example:
        >>> float(sg.torus(1.0, 0.25).distance((1, 0, 0)))
        -0.25
    """
    return Torus(r1, r2)


def capsule(a: Sequence[float] = (0.0, -0.5, 0.0), b: Sequence[float] = (0.0, 0.5, 0.0),
            radius: float = 0.25) -> Capsule:
    """Capsule: the points within ``radius`` of the segment from ``a`` to ``b``.

    Args:
        a: one end point (x, y, z).
        b: the other end point.
        radius: radius, > 0.

    Exact.

    Example:
        >>> float(sg.capsule((0, -1, 0), (0, 1, 0), 0.5).distance((0, 3, 0)))
        1.5
    """
    return Capsule(a, b, radius)


def cylinder(radius: float = 0.5, height: float = 1.0) -> Cylinder:
    """Capped cylinder along Y, centred at the origin.

    Args:
        radius: radius, > 0.
        height: full height (from -height/2 to height/2), > 0.

    Exact.

    Example:
        >>> float(sg.cylinder(0.5, 2.0).distance((0, 2, 0)))
        1.0
    """
    return Cylinder(radius, height)


def cone(height: float = 1.0, r1: float = 0.5, r2: float = 0.0) -> Cone:
    """Capped cone (frustum) along Y, centred at the origin.

    Args:
        height: full height, > 0.
        r1: radius at the bottom (y = -height/2), >= 0.
        r2: radius at the top (y = height/2), >= 0; not both radii 0.

    Exact.

    Example:
        >>> float(sg.cone(2.0, 1.0, 0.0).distance((0, -2, 0)))
        1.0
    """
    return Cone(height, r1, r2)


def ellipsoid(radii: float | Sequence[float] = (1.0, 0.5, 0.75)) -> Ellipsoid:
    """Ellipsoid centred at the origin.

    Args:
        radii: semi-axes (one number or (rx, ry, rz)), each > 0.

    A distance bound (Inigo Quilez's), not exact: ``|f|`` never exceeds the distance.

    Example:
        >>> sg.ellipsoid((1, 0.5, 0.75)).exactness
        'bound'
    """
    return Ellipsoid(radii)


def octahedron(size: float = 1.0) -> Octahedron:
    """Regular octahedron centred at the origin.

    Args:
        size: distance from the centre to each vertex (on the axes), > 0.

    Exact.

    Example:
        >>> float(sg.octahedron(1.0).distance((2, 0, 0)))
        1.0
    """
    return Octahedron(size)


def box_frame(size: float | Sequence[float] = 1.0, thickness: float = 0.05) -> BoxFrame:
    """The twelve edges of a box, as square bars.

    Args:
        size: full edge lengths of the box (a number or (sx, sy, sz)), > 0.
        thickness: width of the bars, > 0 and at most half the smallest edge.

    Exact.

    Example:
        >>> sg.box_frame(1.0, 0.05).exactness
        'exact'
    """
    return BoxFrame(size, thickness)


def hex_prism(radius: float = 0.5, height: float = 1.0) -> HexPrism:
    """Hexagonal prism along Y, centred at the origin.

    Args:
        radius: inradius (centre to the middle of a side), > 0.
        height: full height, > 0.

    Exact.

    Example:
        >>> float(sg.hex_prism(0.5, 1.0).distance((0, 1.5, 0)))
        1.0
    """
    return HexPrism(radius, height)
