"""More solids: regular tetrahedron, dodecahedron, icosahedron, pyramid, slab, tubes along
a polyline or a quadratic Bezier curve, capped torus and gyroid sheet. Formulas after
Inigo Quilez's distance functions (MIT) and the classic face-plane solids."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import INF, Primitive

if TYPE_CHECKING:  # pragma: no cover
    from ..codegen import Emitter

PHI = (1 + math.sqrt(5)) / 2
INV_SQRT3 = 0.57735027


def _unit(x: Sequence[float]) -> np.ndarray:
    a = np.asarray(x, dtype=np.float64)
    return a / np.linalg.norm(a)


def _cyclic_max(q: np.ndarray, n: np.ndarray) -> np.ndarray:
    """max(q.n, q.n.zxy, q.n.yzx) as in GLSL (n.zxy = (n2, n0, n1))."""
    return np.maximum.reduce([q @ n, q @ n[[2, 0, 1]], q @ n[[1, 2, 0]]])


class _FacePlanes(Primitive):
    """A regular solid as the largest distance to its face planes, faces at distance
    ``radius`` (the inradius): exact inside, a 1-Lipschitz bound outside."""

    exact = False
    lib = ("sd_platonic",)
    glsl = ""
    circum = 1.0  # circumradius / inradius

    def __init__(self, radius: float = 1.0) -> None:
        r = v.scalar(self.kind, "radius", radius, positive=True)
        super().__init__(radius=r)
        self.r = r

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"{self.glsl}({p}, {em.num(self.r)})"

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        e = float(self.r) * self.circum
        return np.full(3, -e), np.full(3, e)


class Tetrahedron(_FacePlanes):
    kind = "tetrahedron"
    glsl = "sdTetrahedron"
    circum = 3.0

    def _distance(self, p: np.ndarray) -> np.ndarray:
        x, y, z = p[..., 0], p[..., 1], p[..., 2]
        a = np.maximum(x + y + z, -x - y + z)
        b = np.maximum(x - y - z, -x + y - z)
        return np.maximum(a, b) * INV_SQRT3 - self.r


class Dodecahedron(_FacePlanes):
    kind = "dodecahedron"
    glsl = "sdDodecahedron"
    circum = 1.2584

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return _cyclic_max(np.abs(p), _unit((0.0, 1.0, PHI))) - self.r


class Icosahedron(_FacePlanes):
    kind = "icosahedron"
    glsl = "sdIcosahedron"
    circum = 1.2584

    def _distance(self, p: np.ndarray) -> np.ndarray:
        q = np.abs(p)
        return np.maximum(_cyclic_max(q, _unit((0.0, 1.0 / PHI, PHI))), q.sum(axis=-1) * INV_SQRT3) - self.r


class Pyramid(Primitive):
    """A square pyramid: base ``base`` wide in XZ at y = 0, apex at y = ``height``."""

    kind = "pyramid"
    lib = ("sd_pyramid",)

    def __init__(self, height: float = 1.0, base: float = 1.0) -> None:
        h = v.scalar(self.kind, "height", height, positive=True)
        b = v.scalar(self.kind, "base", base, positive=True)
        v.fixed(self.kind, "the unit pyramid's height is a ratio", height=h, base=b)
        super().__init__(height=h, base=b)
        self.h, self.b = float(h), float(b)

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"(sdPyramid({p} / {em.num(self.b)}, {em.num(self.h / self.b)}) * {em.num(self.b)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        p = p / self.b
        h = self.h / self.b
        m2 = h * h + 0.25
        x, y, z = np.abs(p[..., 0]), p[..., 1], np.abs(p[..., 2])
        x, z = np.where(z > x, z, x) - 0.5, np.where(z > x, x, z) - 0.5
        qx, qy, qz = z, h * y - 0.5 * x, h * x + 0.5 * y
        s = np.maximum(-qx, 0.0)
        t = np.clip((qy - 0.5 * z) / (m2 + 0.25), 0.0, 1.0)
        a = m2 * (qx + s) ** 2 + qy * qy
        b = m2 * (qx + 0.5 * t) ** 2 + (qy - m2 * t) ** 2
        d2 = np.where(np.minimum(qy, -qx * m2 - qy * 0.5) > 0.0, 0.0, np.minimum(a, b))
        above = np.maximum(np.sqrt((d2 + qz * qz) / m2) * np.sign(np.maximum(qz, -y)), -y)
        ax, az = np.abs(p[..., 0]), np.abs(p[..., 2])
        below = np.sqrt(np.maximum(ax - 0.5, 0.0) ** 2 + y * y + np.maximum(az - 0.5, 0.0) ** 2)
        return np.where(y < 0.0, below, above) * self.b

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([-self.b / 2, 0.0, -self.b / 2]), np.array([self.b / 2, self.h, self.b / 2])


class Slab(Primitive):
    """The space between axis-aligned planes: any of x0 < x < x1, y0 < y < y1, z0 < z < z1
    (None: unbounded on that side). Exact next to one plane; a bound near edges."""

    kind = "slab"
    exact = False

    def __init__(self, x0: float | None = None, x1: float | None = None, y0: float | None = None,
                 y1: float | None = None, z0: float | None = None, z1: float | None = None) -> None:
        given = {k: val for k, val in dict(x0=x0, x1=x1, y0=y0, y1=y1, z0=z0, z1=z1).items() if val is not None}
        if not given:
            raise ParameterError(f"{self.kind}: give at least one of x0, x1, y0, y1, z0, z1")
        vals = {k: float(v.scalar(self.kind, k, val)) for k, val in given.items()}
        v.fixed(self.kind, "the planes are compiled in", **given)
        for ax in "xyz":
            if f"{ax}0" in vals and f"{ax}1" in vals and not vals[f"{ax}0"] < vals[f"{ax}1"]:
                raise ParameterError(f"{self.kind}: '{ax}0' ({vals[ax + '0']:g}) must be below '{ax}1' "
                                     f"({vals[ax + '1']:g})")
        super().__init__(**vals)
        self.sides = vals

    def _terms(self) -> list[tuple[int, float, float]]:
        """(axis, sign, offset): the field is max(sign * (p[axis] - offset))."""
        out = []
        for name, val in self.sides.items():
            ax, low = "xyz".index(name[0]), name[1] == "0"
            out.append((ax, -1.0 if low else 1.0, val))
        return out

    def _expr(self, em: "Emitter", p: str) -> str:
        terms = [f"{'-' if s < 0 else ''}({p}.{'xyz'[ax]} - {em.num(o)})" for ax, s, o in self._terms()]
        expr = terms[0]
        for t in terms[1:]:
            expr = f"max({expr}, {t})"
        return expr

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return np.maximum.reduce([s * (p[..., ax] - o) for ax, s, o in self._terms()] + [np.full(p.shape[:-1], -INF)])

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = np.full(3, -INF), np.full(3, INF)
        for name, val in self.sides.items():
            (lo if name[1] == "0" else hi)["xyz".index(name[0])] = val
        return lo, hi


class Tube(Primitive):
    """A tube of ``radius`` along the polyline through ``points`` (round joints and ends). Exact."""

    kind = "tube"

    def __init__(self, points: Sequence[Sequence[float]], radius: float) -> None:
        try:
            pts = np.array([v.vector(self.kind, f"points[{i}]", q) for i, q in enumerate(points)])
        except TypeError:
            raise ParameterError(f"{self.kind}: 'points' must be a list of (x, y, z) points") from None
        if len(pts) < 2:
            raise ParameterError(f"{self.kind}: needs at least 2 points, got {len(pts)}")
        if np.any(np.linalg.norm(np.diff(pts, axis=0), axis=1) == 0):
            raise ParameterError(f"{self.kind}: two consecutive points coincide")
        r = v.scalar(self.kind, "radius", radius, positive=True)
        v.fixed(self.kind, "the tube is compiled in", radius=r)
        super().__init__(points=pts, radius=r)
        self.v, self.r = pts, float(r)

    def _expr(self, em: "Emitter", p: str) -> str:
        from .. import shaderlib
        n = len(self.v)
        em.require("sd_segment")
        em.helper(f"sdTube{n}", shaderlib.read("lib/sd_tube").replace("TUBEN", str(n)))
        return f"sdTube{n}({p}, vec3[{n}]({', '.join(em.vec(q) for q in self.v)}), {em.num(self.r)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        d = np.full(p.shape[:-1], INF)
        for a, b in zip(self.v[:-1], self.v[1:]):
            pa, ba = p - a, b - a
            h = np.clip((pa @ ba) / (ba @ ba), 0.0, 1.0)
            d = np.minimum(d, np.linalg.norm(pa - ba * h[..., None], axis=-1))
        return d - self.r

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.v.min(axis=0) - self.r, self.v.max(axis=0) + self.r


class BezierTube(Primitive):
    """A tube of ``radius`` along the quadratic Bezier curve from ``a`` to ``c`` pulled
    toward ``b`` (the nearest point by a closed-form cubic, IQ). Exact."""

    kind = "bezier_tube"
    lib = ("sd_bezier",)

    def __init__(self, a: Sequence[float], b: Sequence[float], c: Sequence[float], radius: float) -> None:
        pa, pb, pc = (v.vector(self.kind, n, q) for n, q in (("a", a), ("b", b), ("c", c)))
        r = v.scalar(self.kind, "radius", radius, positive=True)
        v.fixed(self.kind, "the curve is compiled in", radius=r)
        bend = pa - 2 * pb + pc
        span = max(float(np.linalg.norm(pc - pa)), 1e-300)
        if np.linalg.norm(bend) < 1e-3 * span:
            raise ParameterError(f"{self.kind}: the control point 'b' lies (almost) on the line from 'a' to 'c'; "
                                 f"use sg.tube([a, c], radius) for a straight tube")
        super().__init__(a=pa, b=pb, c=pc, radius=r)
        self.a, self.b, self.c, self.r = pa, pb, pc, float(r)

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"(sdBezier({p}, {em.vec(self.a)}, {em.vec(self.b)}, {em.vec(self.c)}) - {em.num(self.r)})"

    def _distance(self, pos: np.ndarray) -> np.ndarray:
        a = self.b - self.a
        b = self.a - 2.0 * self.b + self.c
        c = a * 2.0
        d = self.a - pos
        kk = 1.0 / (b @ b)
        kx = kk * (a @ b)
        ky = kk * (2.0 * (a @ a) + d @ b) / 3.0
        kz = kk * (d @ a)
        p = ky - kx * kx
        q = kx * (2.0 * kx * kx - 3.0 * ky) + kz
        h = q * q + 4.0 * p ** 3

        def dist2(t: np.ndarray) -> np.ndarray:
            e = d + (c + b * t[..., None]) * t[..., None]
            return np.sum(e * e, axis=-1)
        with np.errstate(invalid="ignore"):
            hs = np.sqrt(np.maximum(h, 0.0))
            x1, x2 = (hs - q) / 2.0, (-hs - q) / 2.0
            t1 = np.clip(np.cbrt(x1) + np.cbrt(x2) - kx, 0.0, 1.0)
            z = np.sqrt(np.maximum(-p, 0.0))
            den = np.where(p * z != 0, p * z * 2.0, 1.0)
            vv = np.arccos(np.clip(q / den, -1.0, 1.0)) / 3.0
            m, n = np.cos(vv), np.sin(vv) * 1.732050808
            ta = np.clip((m + m) * z - kx, 0.0, 1.0)
            tb = np.clip((-n - m) * z - kx, 0.0, 1.0)
        t1, ta, tb = (self._polish(t, b, c, d) for t in (t1, ta, tb))
        res = np.where(h >= 0.0, dist2(t1), np.minimum(dist2(ta), dist2(tb)))
        return np.sqrt(res) - self.r

    @staticmethod
    def _polish(t: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Two Newton steps on the nearest-point condition (B(t) - pos) . B'(t) = 0, as in GLSL:
        the closed-form cubic loses digits to cancellation in float32."""
        for _ in range(2):
            tt = t[..., None]
            e, de = d + (c + b * tt) * tt, c + 2.0 * b * tt
            g, dg = np.sum(e * de, axis=-1), np.sum(de * de, axis=-1) + 2.0 * np.sum(e * b, axis=-1)
            t = np.clip(t - g / np.where(dg > 0, dg, 1.0) * (dg > 0), 0.0, 1.0)
        return t

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        pts = np.stack([self.a, self.b, self.c])  # the curve lies in its control points' hull
        return pts.min(axis=0) - self.r, pts.max(axis=0) + self.r


class CappedTorus(Primitive):
    """A torus (radii ``r1``, ``r2``) in the XY plane cut to an arc ``aperture`` degrees wide,
    symmetric about +Y. Exact."""

    kind = "capped_torus"
    lib = ("sd_capped_torus",)

    def __init__(self, r1: float = 1.0, r2: float = 0.25, aperture: float = 270.0) -> None:
        a = v.scalar(self.kind, "r1", r1, positive=True)
        b = v.scalar(self.kind, "r2", r2, positive=True)
        ap = v.scalar(self.kind, "aperture", aperture, positive=True)
        v.fixed(self.kind, "the cut is compiled in", aperture=ap)
        if ap > 360:
            raise ParameterError(f"{self.kind}: parameter 'aperture' must be at most 360 degrees, got {ap:g}")
        super().__init__(r1=a, r2=b, aperture=ap)
        half = math.radians(ap) / 2
        self.sc = np.array([math.sin(half), math.cos(half)])
        self.ra, self.rb = a, b

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdCappedTorus({p}, {em.vec(self.sc)}, {em.num(self.ra)}, {em.num(self.rb)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        x, y, z = np.abs(p[..., 0]), p[..., 1], p[..., 2]
        ra, rb = float(self.ra), float(self.rb)
        cap = np.sqrt((x - self.sc[0] * ra) ** 2 + (y - self.sc[1] * ra) ** 2 + z * z)
        ring = np.hypot(np.hypot(x, y) - ra, z)
        return np.where(self.sc[1] * x > self.sc[0] * y, cap, ring) - rb

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        e = float(self.ra) + float(self.rb)
        return np.array([-e, -e, -float(self.rb)]), np.array([e, e, float(self.rb)])


class Gyroid(Primitive):
    """The gyroid sheet sin x cos y + sin y cos z + sin z cos x = 0 at ``frequency`` (radians
    per unit), ``thickness`` thick: |g| / (f sqrt 6) - t / 2, a 1-Lipschitz bound. Unbounded:
    intersect it with a solid."""

    kind = "gyroid"
    exact = False
    lib = ("sd_gyroid",)

    def __init__(self, frequency: float = 2 * math.pi, thickness: float = 0.1) -> None:
        f = v.scalar(self.kind, "frequency", frequency, positive=True)
        t = v.scalar(self.kind, "thickness", thickness, positive=True)
        super().__init__(frequency=f, thickness=t)
        self.f, self.t = f, t

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdGyroid({p}, {em.num(self.f)}, {em.num(self.t * 0.5)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        q = p * float(self.f)
        g = np.sum(np.sin(q) * np.cos(q[..., [1, 2, 0]]), axis=-1)
        return np.abs(g) / (float(self.f) * 2.44948974) - float(self.t) * 0.5

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(3, -INF), np.full(3, INF)


def tetrahedron(radius: float = 1.0) -> Tetrahedron:
    """Regular tetrahedron, faces ``radius`` from the centre (a bound outside).

    Args:
        radius: distance from the centre to each face, > 0.

    Example:
        >>> float(sg.tetrahedron(1).distance((0, 0, 0)))
        -1.0
    """
    return Tetrahedron(radius)


def dodecahedron(radius: float = 1.0) -> Dodecahedron:
    """Regular dodecahedron, faces ``radius`` from the centre (a bound outside).

    Args:
        radius: distance from the centre to each face, > 0.

    Example:
        >>> float(sg.dodecahedron(1).distance((0, 0, 0)))
        -1.0
    """
    return Dodecahedron(radius)


def icosahedron(radius: float = 1.0) -> Icosahedron:
    """Regular icosahedron, faces ``radius`` from the centre (a bound outside).

    Args:
        radius: distance from the centre to each face, > 0.

    Example:
        >>> float(sg.icosahedron(1).distance((0, 0, 0)))
        -1.0
    """
    return Icosahedron(radius)


def pyramid(height: float = 1.0, base: float = 1.0) -> Pyramid:
    """Square pyramid on the XZ plane, apex at y = ``height``. Exact.

    Args:
        height: the apex's height above the base, > 0.
        base: the side of the square base, centred on the origin, > 0.

    Example:
        >>> float(sg.pyramid(1, 1).distance((0, 2, 0)))
        1.0
    """
    return Pyramid(height, base)


def slab(x0: float | None = None, x1: float | None = None, y0: float | None = None, y1: float | None = None,
         z0: float | None = None, z1: float | None = None) -> Slab:
    """The region between the given axis-aligned planes (a bound near edges).

    Args:
        x0: the lower x limit (None: unlimited).
        x1: the upper x limit (None: unlimited).
        y0: the lower y limit.
        y1: the upper y limit.
        z0: the lower z limit.
        z1: the upper z limit.

    Example:
        >>> float(sg.slab(y0=0, y1=1).distance((5, 3, 0)))
        2.0
    """
    return Slab(x0, x1, y0, y1, z0, z1)


def tube(points: Sequence[Sequence[float]], radius: float = 0.1) -> Tube:
    """A tube along a polyline. Exact.

    Args:
        points: two or more points (x, y, z) the tube's centre line passes through.
        radius: the tube's radius, > 0.

    Example:
        >>> float(sg.tube([(0, 0, 0), (1, 0, 0), (1, 1, 0)], 0.1).distance((0.5, 0.5, 0)))
        0.4
    """
    return Tube(points, radius)


def bezier_tube(a: Sequence[float], b: Sequence[float], c: Sequence[float], radius: float = 0.1) -> BezierTube:
    """A tube along the quadratic Bezier curve a -> c with control point b. Exact.

    Args:
        a: the start point (x, y, z).
        b: the control point.
        c: the end point.
        radius: the tube's radius, > 0.

    Example:
        >>> float(sg.bezier_tube((0, 0, 0), (1, 1, 0), (2, 0, 0), 0.1).distance((0, -1, 0)))
        0.9
    """
    return BezierTube(a, b, c, radius)


def capped_torus(r1: float = 1.0, r2: float = 0.25, aperture: float = 270.0) -> CappedTorus:
    """A torus in the XY plane cut to ``aperture`` degrees about +Y. Exact.

    Args:
        r1: radius of the ring's centre line, > 0.
        r2: radius of the tube, > 0.
        aperture: the angle the ring spans, degrees, in (0, 360].

    Example:
        >>> float(sg.capped_torus(1, 0.25, 270).distance((0, 0, 0)))
        0.75
    """
    return CappedTorus(r1, r2, aperture)


def gyroid(frequency: float = 2 * math.pi, thickness: float = 0.1) -> Gyroid:
    """An infinite gyroid sheet (a bound); intersect it with a solid.

    Args:
        frequency: radians per unit length (2 pi: one period per unit), > 0.
        thickness: the sheet's thickness, > 0.

    Example:
        >>> part = sg.gyroid(6.283, 0.1) & sg.sphere(1)
        >>> part.exactness, float(part.distance((3, 0, 0)))
        ('bound', 2.0)
    """
    return Gyroid(frequency, thickness)
