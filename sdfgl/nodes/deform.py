"""Deformations whose Lipschitz factor exceeds 1: twist and bend.

The warped field f(T(p)) has a gradient up to ||J_T|| times the child's. Inside a box
padded around the result, the node divides by the largest ||J_T|| over that box (its
``stretch``), which makes the field there a 1-Lipschitz bound; outside the box it
returns the distance to the unpadded bounds, also a 1-Lipschitz bound. Only this
subtree's steps are shortened, and only by what its own geometry needs. The two bounds
meet at the box wall with a jump, never an overestimate.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..errors import ParameterError
from . import validate as v
from .base import BOUND, IMPLICIT, Node, Unary
from .primitives import Box

if TYPE_CHECKING:  # pragma: no cover
    from ..codegen import Emitter

PAD = 0.05  # the inside box grows by this fraction of the bounds' size


class _Warp(Unary):
    """Shared machinery: inside-box test, stretch division, box fallback."""

    lib: tuple[str, ...] = ()
    glsl_fn = ""
    axes: tuple[int, int] = (0, 2)  # the two coordinates the warp rotates

    def __init__(self, child: Node, rate: float) -> None:
        r = v.scalar(self.kind, "rate", rate)
        v.fixed(self.kind, "the step safety factor is compiled from it", rate=r)
        lo, hi = child.bounds
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            raise ParameterError(f"{self.kind}: the child {child.label()} is unbounded; a warp needs finite bounds")
        super().__init__(child, rate=r)
        self.k = math.radians(r)
        a, b = self.axes
        radius = math.hypot(max(abs(lo[a]), abs(hi[a])), max(abs(lo[b]), abs(hi[b])))
        self.radius = radius
        blo, bhi = self.bounds
        pad = PAD * float(np.max(bhi - blo)) + 1e-9
        self.box_lo, self.box_hi = blo - pad, bhi + pad
        far = math.hypot(*np.max(np.abs(np.stack([self.box_lo, self.box_hi]))[:, list(self.axes)], axis=0))
        self.stretch = self._stretch(far)

    def _stretch(self, r: float) -> float:
        raise NotImplementedError

    @property
    def exactness(self) -> str:
        return IMPLICIT if self.child.exactness == IMPLICIT else BOUND

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        lo, hi = lo.copy(), hi.copy()
        for ax in self.axes:  # the warp turns points about an axis: radius is kept
            lo[ax], hi[ax] = -self.radius, self.radius
        return lo, hi

    def _warp(self, p: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def _emit(self, em: "Emitter", p: str) -> str:
        em.require(*self.lib, "op_inside_box", "sd_box")
        pt = em.point(p)
        q = em.assign("vec3", f"{self.glsl_fn}({pt}, {em.num(self.k)})")
        inner = self.child.emit(em, q)
        blo, bhi = self.bounds
        centre, half = (blo + bhi) / 2, (bhi - blo) / 2
        outside = f"sdBox({pt} - {em.vec(centre)}, {em.vec(half)})"
        inside = f"opInsideBox({pt}, {em.vec(self.box_lo)}, {em.vec(self.box_hi)})"
        scale = em.num(1.0 / self.stretch)
        if em.mode == "dist":
            return em.assign("float", f"{inside} ? {inner} * {scale} : {outside}")
        return em.assign("vec4", f"vec4({inner}.rgb, {inside} ? {inner}.w * {scale} : {outside})")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        inner = self.child._distance(self._warp(p)) / self.stretch
        blo, bhi = self.bounds
        outside = Box(bhi - blo)._distance(p - (blo + bhi) / 2)
        inside = np.all((p >= self.box_lo) & (p <= self.box_hi), axis=-1)
        return np.where(inside, inner, outside)


class Twist(_Warp):
    """Twist about Y by ``rate`` degrees per unit of height."""

    kind = "twist"
    lib = ("op_twist",)
    glsl_fn = "opTwist"
    axes = (0, 2)

    def _stretch(self, r: float) -> float:
        h = abs(self.k) * r / 2  # largest singular value of the twist's Jacobian at radius r
        return h + math.sqrt(1 + h * h)

    def _warp(self, p: np.ndarray) -> np.ndarray:
        a = self.k * p[..., 1]
        c, s = np.cos(a), np.sin(a)
        return np.stack([c * p[..., 0] - s * p[..., 2], p[..., 1], s * p[..., 0] + c * p[..., 2]], axis=-1)


class Bend(_Warp):
    """Bend in the XY plane by ``rate`` degrees per unit along X."""

    kind = "bend"
    lib = ("op_bend",)
    glsl_fn = "opBend"
    axes = (0, 1)

    def _stretch(self, r: float) -> float:
        return 1.0 + abs(self.k) * r  # ||R + u e_x^T|| <= 1 + |u|, |u| = k r

    def _warp(self, p: np.ndarray) -> np.ndarray:
        a = self.k * p[..., 0]
        c, s = np.cos(a), np.sin(a)
        return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1], p[..., 2]], axis=-1)


def twist(node: Node, rate: float) -> Twist:
    """Twist ``node`` about the Y axis.

    Args:
        node: the node to twist.
        rate: degrees of turn per unit of height (a baked constant).

    A bound: the Lipschitz factor grows with rate and the node's radius; only this subtree's
    steps are shortened.

    Example:
        >>> sg.twist(sg.box((0.6, 2, 0.4)), 90).exactness
        'bound'
    """
    return Twist(node, rate)


def bend(node: Node, rate: float) -> Bend:
    """Bend ``node`` in the XY plane.

    Args:
        node: the node to bend.
        rate: degrees of bend per unit along X (a baked constant).

    A bound (Lipschitz factor > 1, this subtree only).

    Example:
        >>> sg.bend(sg.box((2, 0.3, 0.4)), 40).exactness
        'bound'
    """
    return Bend(node, rate)
