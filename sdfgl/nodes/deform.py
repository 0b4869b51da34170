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
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import axes
from ..values import validate as v
from .base import BOUND, IMPLICIT, Node, Unary, fluent
from .primitives import Box

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

PAD = 0.05  # the inside box grows by this fraction of the bounds' size


class _Warp(Unary):
    """Shared machinery: inside-box test, stretch division, box fallback."""

    lib: tuple[str, ...] = ()
    glsl_fn = ""
    default_axis = "y"
    # per axis: (the two coordinates the warp rotates, the coordinate the angle follows)
    planes: dict[str, tuple[tuple[int, int], int]] = {}

    def __init__(self, child: Node, rate: float, axis: str | Sequence[float]) -> None:
        r = v.scalar(self.kind, "rate", rate)
        v.fixed(self.kind, "the step safety factor is compiled from it", rate=r)
        axis = axes.coordinate_name(self.kind, "axis", axis)
        lo, hi = child.bounds
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            raise ParameterError(f"{self.kind}: the child {child.label()} is unbounded; a warp needs finite bounds")
        # the default axis keeps the original parameters (and so the node's key and label)
        super().__init__(child, rate=r, **({} if axis == self.default_axis else {"axis": axis}))
        self.axis = axis
        self.axes, self.along = self.planes[axis]
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

    def level_stretch(self) -> float:
        return self.stretch  # the warped distance is divided by it

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        lo, hi = lo.copy(), hi.copy()
        for ax in self.axes:  # the warp turns points about an axis: radius is kept
            lo[ax], hi[ax] = -self.radius, self.radius
        return lo, hi

    def _warp(self, p: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def _warp_glsl(self, em: "Emitter", pt: str) -> str:
        """The warped point (a GLSL variable) at point ``pt``: the library function for the
        default axis, else the same rotation of the other coordinate pair, inline."""
        if self.axis == self.default_axis:
            return em.assign("vec3", f"{self.glsl_fn}({pt}, {em.num(self.k)})")
        a, b = ("xyz"[i] for i in self.axes)
        ang = em.assign("float", f"{em.num(self.k)} * {pt}.{'xyz'[self.along]}")
        cs = em.assign("vec2", f"vec2(cos({ang}), sin({ang}))")
        q = em.assign("vec3", pt)
        em.lines.append((f"    {q}.{a}{b} = vec2({cs}.x * {pt}.{a} - {cs}.y * {pt}.{b}, "
                         f"{cs}.y * {pt}.{a} + {cs}.x * {pt}.{b});", em.owner))
        return q

    def _warp(self, p: np.ndarray) -> np.ndarray:
        a, b = self.axes
        ang = self.k * p[..., self.along]
        c, s = np.cos(ang), np.sin(ang)
        q = p.copy()
        q[..., a] = c * p[..., a] - s * p[..., b]
        q[..., b] = s * p[..., a] + c * p[..., b]
        return q

    def _emit(self, em: "Emitter", p: str) -> str:
        em.require(*self.lib, "op_inside_box", "sd_box")
        pt = em.point(p)
        q = self._warp_glsl(em, pt)
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
    """Twist about ``axis`` (default Y) by ``rate`` degrees per unit along it."""

    kind = "twist"
    lib = ("op_twist",)
    glsl_fn = "opTwist"
    planes = {"y": ((0, 2), 1), "z": ((0, 1), 2), "x": ((1, 2), 0)}

    def __init__(self, child: Node, rate: float, axis: str | Sequence[float] = "y") -> None:
        super().__init__(child, rate, axis)

    def _stretch(self, r: float) -> float:
        h = abs(self.k) * r / 2  # largest singular value of the twist's Jacobian at radius r
        return h + math.sqrt(1 + h * h)



class Bend(_Warp):
    """Bend about ``axis`` by ``rate`` degrees per unit: about Z (the default) the XY plane
    turns by rate * x; about X the YZ plane by rate * y; about Y the ZX plane by rate * z."""

    kind = "bend"
    lib = ("op_bend",)
    glsl_fn = "opBend"
    default_axis = "z"
    planes = {"z": ((0, 1), 0), "x": ((1, 2), 1), "y": ((2, 0), 2)}

    def __init__(self, child: Node, rate: float, axis: str | Sequence[float] = "z") -> None:
        super().__init__(child, rate, axis)

    def _stretch(self, r: float) -> float:
        return 1.0 + abs(self.k) * r  # ||R + u e_x^T|| <= 1 + |u|, |u| = k r



class Taper(_Warp):
    """The cross-section across coordinate axis ``axis`` scaled by s(u) = 1 + rate (u - origin)
    along it (u: the coordinate along the axis); s must stay positive over the solid."""

    kind = "taper"

    def __init__(self, child: Node, rate: float, axis: str | Sequence[float] = "y", origin: float = 0.0) -> None:
        r = v.scalar(self.kind, "rate", rate)
        o = v.scalar(self.kind, "origin", origin)
        v.fixed(self.kind, "the step safety factor is compiled from it", rate=r, origin=o)
        self.ax = axes.coordinate(self.kind, "axis", axis)
        lo, hi = child.bounds
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            raise ParameterError(f"{self.kind}: the child {child.label()} is unbounded; a taper needs finite bounds")
        Unary.__init__(self, child, rate=r, axis="xyz"[self.ax], origin=o)
        self.k, self.o = float(r), float(o)
        blo, bhi = self.bounds
        pad = PAD * float(np.max(bhi - blo)) + 1e-9
        self.box_lo, self.box_hi = blo - pad, bhi + pad
        s_ends = [self._s(self.box_lo[self.ax]), self._s(self.box_hi[self.ax])]
        if min(s_ends) <= 0:
            raise ParameterError(f"{self.kind}: the scale 1 + rate (u - origin) reaches {min(s_ends):g} within the "
                                 f"solid; it must stay > 0 (a smaller rate, or another origin)")
        perp = [i for i in range(3) if i != self.ax]
        corners = np.abs(np.stack([self.box_lo, self.box_hi]))[:, perp]
        far = float(np.hypot(*corners.max(axis=0)))
        s_min = min(s_ends)
        # ||J|| <= max(1, 1/s) + |s'| |p_perp| / s^2 over the box
        self.stretch = max(1.0, 1.0 / s_min) + abs(self.k) * far / s_min ** 2

    def _s(self, u: float | np.ndarray) -> float | np.ndarray:
        return 1.0 + self.k * (u - self.o)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        sa, sb = self._s(lo[self.ax]), self._s(hi[self.ax])
        out_lo, out_hi = lo.copy(), hi.copy()
        for j in range(3):
            if j != self.ax:
                vals = [lo[j] * sa, lo[j] * sb, hi[j] * sa, hi[j] * sb]
                out_lo[j], out_hi[j] = min(vals), max(vals)
        return out_lo, out_hi

    def _warp_glsl(self, em: "Emitter", pt: str) -> str:
        s = em.assign("float", f"1.0 + {em.num(self.k)} * ({pt}.{'xyz'[self.ax]} - {em.num(self.o)})")
        div = ", ".join("1.0" if i == self.ax else s for i in range(3))
        return em.assign("vec3", f"{pt} / vec3({div})")

    def _warp(self, p: np.ndarray) -> np.ndarray:
        s = self._s(p[..., self.ax])
        q = p / s[..., None]
        q[..., self.ax] = p[..., self.ax]
        return q


@fluent()
def taper(node: Node, rate: float, axis: str | Sequence[float] = "y", origin: float = 0.0) -> Taper:
    """Scale ``node``'s cross-section across ``axis`` by 1 + rate (u - origin) along it.

    Args:
        node: the node to taper; it must be bounded.
        rate: change of the scale per unit along the axis (a baked constant); the scale
            must stay > 0 over the node.
        axis: "x", "y", "z" or a vector along one of them (``sg.Y``, (0, 1, 0)).
        origin: the coordinate u along the axis where the scale is 1.

    A bound (Lipschitz factor > 1, this subtree only).

    Example:
        >>> sg.taper(sg.box(1), 0.3).exactness
        'bound'
    """
    return Taper(node, rate, axis, origin)


@fluent()
def twist(node: Node, rate: float, axis: str | Sequence[float] = "y") -> Twist:
    """Twist ``node`` about a coordinate axis.

    Args:
        node: the node to twist.
        rate: degrees of turn per unit along the axis (a baked constant).
        axis: "x", "y", "z" or a vector along one of them (``sg.X``).

    A bound: the Lipschitz factor grows with rate and the node's radius; only this subtree's
    steps are shortened.

    Example:
        >>> sg.twist(sg.box((0.6, 2, 0.4)), 90).exactness
        'bound'
    """
    return Twist(node, rate, axis)


@fluent()
def bend(node: Node, rate: float, axis: str | Sequence[float] = "z") -> Bend:
    """Bend ``node`` about a coordinate axis (the default "z" bends in the XY plane).

    Args:
        node: the node to bend.
        rate: degrees of bend per unit along the bent direction (a baked constant; see Bend).
        axis: "x", "y", "z" or a vector along one of them (``sg.X``).

    A bound (Lipschitz factor > 1, this subtree only).

    Example:
        >>> sg.bend(sg.box((2, 0.3, 0.4)), 40).exactness
        'bound'
    """
    return Bend(node, rate, axis)
