"""2D figures named by their parameters: triangle, ellipse (a bound), arc, star, regular
(rounded) polygon and 2D capsule (the circle, rectangle and general polygon are in
:mod:`.shapes2d`, beside the Shape2D protocol). Formulas from Inigo Quilez's 2D distance
functions (MIT)."""
from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import BOUND
from .shapes2d import Shape2D

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

DEFAULT_SHARPNESS = 3.0  # a star's sharpness when neither it nor the inner radius is given


def _seg(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    pa, ba = q - a, b - a
    h = np.clip((pa @ ba) / (ba @ ba), 0.0, 1.0)
    return np.linalg.norm(pa - ba * h[..., None], axis=-1)


class Triangle(Shape2D):
    kind = "triangle"

    def __init__(self, p0: Sequence[float], p1: Sequence[float], p2: Sequence[float]) -> None:
        pts = [v.vector(self.kind, n, p, 2) for n, p in (("p0", p0), ("p1", p1), ("p2", p2))]
        e0, e2 = pts[1] - pts[0], pts[0] - pts[2]
        if abs(e0[0] * e2[1] - e0[1] * e2[0]) < 1e-12 * max(1.0, float(np.abs(pts).max()) ** 2):
            raise ParameterError(f"{self.kind}: the three points are collinear (no area)")
        super().__init__(p0=pts[0], p1=pts[1], p2=pts[2])
        self.p = pts

    def expr(self, em: "Emitter", q: str) -> str:
        em.require("sd2_triangle")
        return f"sd2Triangle({q}, {', '.join(em.vec(x) for x in self.p)})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        p0, p1, p2 = self.p
        e, vv = [p1 - p0, p2 - p1, p0 - p2], [q - p0, q - p1, q - p2]
        s = np.sign(e[0][0] * e[2][1] - e[0][1] * e[2][0])
        dist, side = [], []
        for ei, vi in zip(e, vv):
            pq = vi - ei * np.clip((vi @ ei) / (ei @ ei), 0.0, 1.0)[..., None]
            dist.append(np.sum(pq * pq, axis=-1))
            side.append(s * (vi[..., 0] * ei[1] - vi[..., 1] * ei[0]))
        # GLSL's min of vec2s is per component: the smallest squared distance, the smallest side
        return -np.sqrt(np.minimum.reduce(dist)) * np.sign(np.minimum.reduce(side))

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        pts = np.array(self.p)
        return pts.min(axis=0), pts.max(axis=0)


class Ellipse(Shape2D):
    """An axis-aligned ellipse with semi-axes ``radii``: (|q / r| - 1) min(r), a 1-Lipschitz bound."""

    kind = "ellipse"
    exactness = BOUND

    def __init__(self, radii: Sequence[float]) -> None:
        r = v.vector(self.kind, "radii", radii, 2, positive=True)
        super().__init__(radii=r)
        self.r = r

    def expr(self, em: "Emitter", q: str) -> str:
        return f"((length({q} / {em.vec(self.r)}) - 1.0) * {em.num(self.r.min())})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return (np.linalg.norm(q / self.r, axis=-1) - 1.0) * self.r.min()

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        return -self.r, self.r.copy()


class Arc(Shape2D):
    """An arc of ``radius`` and ``thickness``, ``aperture`` degrees wide, centred on +Y."""

    kind = "arc"

    def __init__(self, radius: float, aperture: float, thickness: float) -> None:
        r = v.scalar(self.kind, "radius", radius, positive=True)
        a = v.scalar(self.kind, "aperture", aperture, positive=True)
        t = v.scalar(self.kind, "thickness", thickness, positive=True)
        if a > 360:
            raise ParameterError(f"{self.kind}: parameter 'aperture' must be at most 360 degrees, got {a:g}")
        super().__init__(radius=r, aperture=a, thickness=t)
        half = math.radians(a) / 2
        self.sc = np.array([math.sin(half), math.cos(half)])
        self.ra, self.rb = float(r), float(t) / 2

    def expr(self, em: "Emitter", q: str) -> str:
        em.require("sd2_arc")
        return f"sd2Arc({q}, {em.vec(self.sc)}, {em.num(self.ra)}, {em.num(self.rb)})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        x, y = np.abs(q[..., 0]), q[..., 1]
        cap = np.hypot(x - self.sc[0] * self.ra, y - self.sc[1] * self.ra)
        ring = np.abs(np.hypot(x, y) - self.ra)
        return np.where(self.sc[1] * x > self.sc[0] * y, cap, ring) - self.rb

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        e = self.ra + self.rb
        return np.array([-e, -e]), np.array([e, e])


class Star(Shape2D):
    """A star of ``points`` tips at ``radius`` whose notches lie ``inner_radius`` from the
    centre; or, given instead, ``sharpness`` in [2, points] (2: a regular polygon, points: a
    star whose notches meet at the centre)."""

    kind = "star"

    def __init__(self, points: int, radius: float, inner_radius: float | None = None, *,
                 sharpness: float | None = None, inner: float | None = None) -> None:
        if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or not 3 <= points <= 1000:
            raise ParameterError(f"{self.kind}: parameter 'points' must be an integer 3..1000, got {points!r}")
        r = v.scalar(self.kind, "radius", radius, positive=True)
        if inner is not None:
            warnings.warn("star: the keyword 'inner' is the tips' sharpness and is now named 'sharpness' "
                          "(for the radius of the notches pass inner_radius)", DeprecationWarning, stacklevel=3)
            if sharpness is not None:
                raise ParameterError(f"{self.kind}: give 'sharpness' or the old 'inner', not both")
            sharpness = inner
        if inner_radius is not None and sharpness is not None:
            raise ParameterError(f"{self.kind}: give 'inner_radius' or 'sharpness', not both")
        if inner_radius is not None:
            m = self._sharpness_for(int(points), r, inner_radius)
        else:
            m = v.scalar(self.kind, "sharpness", DEFAULT_SHARPNESS if sharpness is None else sharpness)
            if not 2.0 <= m <= points:
                raise ParameterError(f"{self.kind}: parameter 'sharpness' must lie in [2, {points}], got {m:g}")
        super().__init__(points=float(points), radius=r, sharpness=m)
        self.n, self.r, self.m = float(points), float(r), float(m)

    @classmethod
    def _sharpness_for(cls, points: int, radius: float, inner_radius: object) -> float:
        """The sharpness m whose notches lie ``inner_radius`` from the centre: the edge from
        a tip meets the bisector between tips at r sin(pi/m - pi/n) / sin(pi/m)."""
        ri = v.scalar(cls.kind, "inner_radius", inner_radius, nonnegative=True)
        v.fixed(cls.kind, "the sharpness is computed from them", radius=radius, inner_radius=ri)
        an = math.pi / points
        most = float(radius) * math.cos(an)  # sharpness 2: the notches on the polygon's edges
        if ri > most:
            raise ParameterError(f"{cls.kind}: parameter 'inner_radius' must lie in [0, {most:g}] (radius * "
                                 f"cos(180 / points)) for radius {float(radius):g}, got {ri:g}; a sharpness in "
                                 f"[2, {points}] is passed as sharpness=")
        return math.pi / math.atan2(math.sin(an), math.cos(an) - ri / float(radius))

    def expr(self, em: "Emitter", q: str) -> str:
        em.require("sd2_star")
        return f"sd2Star({q}, {em.num(self.r)}, {em.num(self.n)}, {em.num(self.m)})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        an, en = math.pi / self.n, math.pi / self.m
        acs, ecs = np.array([math.cos(an), math.sin(an)]), np.array([math.cos(en), math.sin(en)])
        bn = np.mod(np.arctan2(q[..., 0], q[..., 1]), 2 * an) - an
        ln = np.linalg.norm(q, axis=-1)
        p = np.stack([ln * np.cos(bn), ln * np.abs(np.sin(bn))], axis=-1) - self.r * acs
        p = p + ecs * np.clip(-(p @ ecs), 0.0, self.r * acs[1] / ecs[1])[..., None]
        return np.linalg.norm(p, axis=-1) * np.sign(p[..., 0])

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(2, -self.r), np.full(2, self.r)


class Capsule2D(Shape2D):
    """The segment a b grown by ``radius``."""

    kind = "capsule2"

    def __init__(self, a: Sequence[float], b: Sequence[float], radius: float) -> None:
        pa, pb = v.vector(self.kind, "a", a, 2), v.vector(self.kind, "b", b, 2)
        r = v.scalar(self.kind, "radius", radius, positive=True)
        if np.array_equal(pa, pb):
            raise ParameterError(f"{self.kind}: 'a' and 'b' coincide (use sg.circle)")
        super().__init__(a=pa, b=pb, radius=r)
        self.a, self.b, self.r = pa, pb, float(r)

    def expr(self, em: "Emitter", q: str) -> str:
        em.require("sd2_segment")
        return f"(sd2Segment({q}, {em.vec(self.a)}, {em.vec(self.b)}) - {em.num(self.r)})"

    def distance2(self, q: np.ndarray) -> np.ndarray:
        return _seg(q, self.a, self.b) - self.r

    @property
    def bounds2(self) -> tuple[np.ndarray, np.ndarray]:
        return np.minimum(self.a, self.b) - self.r, np.maximum(self.a, self.b) + self.r


def triangle(p0: Sequence[float], p1: Sequence[float], p2: Sequence[float]) -> Triangle:
    """A 2D triangle through three points. Exact.

    Args:
        p0: the first corner (x, y).
        p1: the second corner.
        p2: the third corner (the three must not be collinear).

    Example:
        >>> float(sg.extrude(sg.triangle((0, 0), (1, 0), (0, 1)), 0.2).distance((0, -1, 0)))
        1.0
    """
    return Triangle(p0, p1, p2)


def ellipse(radii: Sequence[float]) -> Ellipse:
    """An axis-aligned 2D ellipse with semi-axes ``radii`` (a distance bound).

    Args:
        radii: the semi-axes (rx, ry), > 0.

    Example:
        >>> sg.ellipse((2, 1)).exactness
        'bound'
    """
    return Ellipse(radii)


def arc(radius: float, aperture: float, thickness: float) -> Arc:
    """A 2D arc ``aperture`` degrees wide, symmetric about +Y. Exact.

    Args:
        radius: radius of the arc's centre line, > 0.
        aperture: the arc's angular width in degrees.
        thickness: the arc's full thickness across the centre line, > 0.

    Example:
        >>> float(sg.extrude(sg.arc(1, 90, 0.1), 0.2).distance((0, 1, 0)))
        -0.05
    """
    return Arc(radius, aperture, thickness)


def star(points: int = 5, radius: float = 1.0, inner_radius: float | None = None, *,
         sharpness: float | None = None, inner: float | None = None) -> Star:
    """A 2D star with one tip at +Y. Exact.

    Args:
        points: the number of tips, >= 3.
        radius: distance from the centre to each tip, > 0.
        inner_radius: distance from the centre to each notch between two tips, in
            [0, radius * cos(180 / points)] (the upper end: a regular polygon).
        sharpness: instead of ``inner_radius``, from 2 (blunt: a polygon) to ``points``
            (sharp); the default, when neither is given, is 3.
        inner: the old name of ``sharpness`` (deprecated).

    Example:
        >>> float(sg.extrude(sg.star(5, 1, 0.4), 0.2).distance((0, 2, 0)))
        1.0
    """
    given = {k: x for k, x in (("inner_radius", inner_radius), ("sharpness", sharpness), ("inner", inner))
             if x is not None}  # only these are recorded (and so written to a scene document)
    return Star(points, radius, **given)


def regular_polygon(sides: int, radius: float = 1.0, rounding: float = 0.0) -> Shape2D:
    """A regular polygon with corners ``radius`` from the centre (one at +Y). Exact.

    Args:
        sides: the number of sides, 3..1000.
        radius: distance from the centre to each corner, > 0.
        rounding: radius of the rounded corners (the outer size stays the same), >= 0.

    Example:
        >>> float(sg.extrude(sg.regular_polygon(6, 1), 0.2).distance((0, 2, 0)))
        1.0
    """
    r = v.scalar("regular_polygon", "radius", radius, positive=True)
    rr = v.scalar("regular_polygon", "rounding", rounding, nonnegative=True)
    if not isinstance(sides, (int, np.integer)) or isinstance(sides, bool) or not 3 <= sides <= 1000:
        raise ParameterError(f"regular_polygon: parameter 'sides' must be an integer 3..1000, got {sides!r}")
    # rounding a polygon grows it by rr; shrink it first so the corners stay at the radius
    inner_r = r - rr
    if inner_r <= 0:
        raise ParameterError(f"regular_polygon: 'rounding' ({rr:g}) is too large for radius {r:g}")
    base = Star(int(sides), inner_r, sharpness=2.0)
    return base.round(rr) if rr > 0 else base


def capsule2(a: Sequence[float], b: Sequence[float], radius: float) -> Capsule2D:
    """A 2D capsule: the segment a b grown by ``radius``. Exact.

    Args:
        a: one end of the segment (x, y).
        b: the other end (x, y).
        radius: the capsule's radius, > 0.

    Example:
        >>> float(sg.extrude(sg.capsule2((0, 0), (1, 0), 0.25), 0.2).distance((0.5, 1, 0)))
        0.75
    """
    return Capsule2D(a, b, radius)
