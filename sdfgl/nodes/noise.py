"""Noise: fBm gradient noise as a displacement of any node, or as a field of its own.

The displacement's gradient bound (amplitude x frequency x the fBm's) is added to the
child's, and only this subtree's field is divided by the sum. ``normal_octaves`` adds
the trick of Monzón González's thesis: more octaves in a second field used only for normals, so a
surface shows fine detail while it is marched with few octaves (terrain, water).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..errors import ParameterError
from ..noise import fbm3, fbm_lipschitz, fbm_max
from ..values import validate as v
from .base import BOUND, IMPLICIT, Node, Primitive, Unary, fluent

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter


def _octaves(node: str, name: str, n: object, lo: int = 0) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not lo <= n <= 16:
        raise ParameterError(f"{node}: '{name}' must be a whole number {lo}..16, got {n!r}")
    return int(n)



class Displace(Unary):
    """child + amplitude * fbm(frequency * p), divided by its gradient bound."""

    kind = "displace"
    costly = True

    def __init__(self, child: Node, amplitude: float, frequency: float = 1.0, octaves: int = 4,
                 normal_octaves: int | None = None) -> None:
        v.fixed(self.kind, "the step factor depends on it", amplitude=amplitude, frequency=frequency)
        a = v.scalar(self.kind, "amplitude", amplitude, nonnegative=True)
        f = v.scalar(self.kind, "frequency", frequency, positive=True)
        n = _octaves(self.kind, "octaves", octaves)
        m = n if normal_octaves is None else _octaves(self.kind, "normal_octaves", normal_octaves)
        if child.exactness == IMPLICIT:
            raise ParameterError(f"{self.kind}: the child {child.label()} is implicit (no distance bound)")
        super().__init__(child, amplitude=a, frequency=f, octaves=n, normal_octaves=m)
        self.a, self.f, self.n, self.m = a, f, n, m
        self.factor = 1.0 + a * f * fbm_lipschitz(n)  # the child is 1-Lipschitz

    @property
    def exactness(self) -> str:
        return BOUND

    def _detail_here(self) -> bool:
        return self.m != self.n

    def _emit(self, em: "Emitter", p: str) -> str:
        em.require("noise3")
        pt = em.point(p)
        r = self.child.emit(em, p)
        octaves = self.m if em.detail else self.n
        if octaves == 0:
            return r
        noise = f"{em.num(self.a)} * fbm3({pt} * {em.num(self.f)}, {octaves})"
        scale = em.num(1.0 / self.factor)
        if em.mode == "dist":
            return em.assign("float", f"({r} + {noise}) * {scale}")
        return em.assign("vec4", f"vec4({r}.rgb, ({r}.w + {noise}) * {scale})")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        d = self.child._distance(p)
        if self.n == 0:
            return d
        return (d + self.a * fbm3(p * self.f, self.n)) / self.factor

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.level_bounds(0.0)

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        # (f + a fbm) / factor < t needs f < factor t + a max|fbm|
        return self.child.level_bounds(self.factor * t + float(self.a) * fbm_max(self.n))

    def level_stretch(self) -> float:
        return self.factor


class NoiseField(Primitive):
    """The field (offset + amplitude * fbm(frequency * p)) / its gradient bound: a bound of
    its zero level set (solid where the sum is negative)."""

    kind = "noise"
    costly = True
    lib = ("noise3",)
    exact = False

    def __init__(self, frequency: float = 1.0, octaves: int = 4, amplitude: float = 1.0, offset: float = 0.0) -> None:
        v.fixed(self.kind, "the step factor depends on it", frequency=frequency, amplitude=amplitude, offset=offset)
        f = v.scalar(self.kind, "frequency", frequency, positive=True)
        n = _octaves(self.kind, "octaves", octaves, lo=1)
        a = v.scalar(self.kind, "amplitude", amplitude, positive=True)
        o = v.scalar(self.kind, "offset", offset)
        super().__init__(frequency=f, octaves=n, amplitude=a, offset=o)
        self.f, self.n, self.a, self.o = f, n, a, o
        self.factor = a * f * fbm_lipschitz(n)

    def _expr(self, em: "Emitter", p: str) -> str:
        return (f"({em.num(self.o)} + {em.num(self.a)} * fbm3({p} * {em.num(self.f)}, {self.n})) "
                f"* {em.num(1.0 / self.factor)}")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return (self.o + self.a * fbm3(p * self.f, self.n)) / self.factor

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(3, -np.inf), np.full(3, np.inf)


@fluent()
def displace(node: Node, amplitude: float, frequency: float = 1.0, octaves: int = 4,
             normal_octaves: int | None = None) -> Displace:
    """Displace ``node``'s surface by fractal (fBm) gradient noise.

    Args:
        node: the node.
        amplitude: largest displacement in scene units, > 0.
        frequency: noise frequency in cycles per unit, > 0.
        octaves: octaves marched, a whole number >= 1.
        normal_octaves: octaves used for shading normals (>= octaves; more shade finer
            detail than is marched, that thesis's terrain and water trick). None: same as octaves.

    A bound; only this subtree's steps shrink.

    Example:
        >>> sg.displace(sg.sphere(1), 0.05, 4.0, 3).exactness
        'bound'
    """
    return Displace(node, amplitude, frequency, octaves, normal_octaves)


def noise(frequency: float = 1.0, octaves: int = 4, amplitude: float = 1.0, offset: float = 0.0) -> NoiseField:
    """fBm noise as a field of its own: solid where offset + amplitude * fbm(frequency * p) < 0.

    Args:
        frequency: cycles per unit, > 0.
        octaves: octaves, a whole number >= 1.
        amplitude: amplitude, > 0.
        offset: level shift.

    A bound; unbounded (intersect it with a box).

    Example:
        >>> (sg.noise(1.5, 3) & sg.box(2)).exactness
        'bound'
    """
    return NoiseField(frequency, octaves, amplitude, offset)
