"""Solids swept along a curve: a tube along a polyline, a tube along a quadratic Bezier
curve, and the capped torus (a tube along a circular arc). Formulas after Inigo Quilez's
distance functions (MIT)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import INF, Primitive
from .bezier import quadratic_distance2

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter


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
        em.helper(f"sdTube{n}", shaderlib.read("templates/sd_tube").replace("TUBEN", str(n)))
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
        return np.sqrt(quadratic_distance2(pos, self.a, self.b, self.c)) - self.r

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
