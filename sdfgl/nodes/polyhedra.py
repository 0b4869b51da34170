"""Solids bounded by planes: the regular tetrahedron, dodecahedron and icosahedron (the
largest distance to their face planes), the square pyramid, and the axis-aligned slab with
any of its six sides open. Formulas after Inigo Quilez's distance functions (MIT) and the
classic face-plane solids."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from .base import INF, Primitive

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

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

    def level_stretch(self) -> float:
        return float(self.circum)  # the largest face-plane distance is at least distance / (R / r)

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

    def level_stretch(self) -> float:
        return math.sqrt(3.0)  # the largest of three plane distances is at least distance / sqrt(3)

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
