"""Domain operators: repetition of a child over a grid of cells."""
from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..params import Live
from ..values import validate as v
from .base import BOUND, EXACT, IMPLICIT, INF, Node, Unary, fluent

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

# A child that keeps this share of its cell free on every side is evaluated once per
# point, with a wall bound; a child nearer its cell walls also in the neighbour cells.
WALL_GAP = 0.1


MAX_COUNT = 1_000_000  # copies per side and axis: the count is a GLSL int constant


class Repeat(Unary):
    """Copies of the child every ``period[i]`` along each axis with a non-zero period.

    ``count`` (per axis, None for endless) limits the copies to cells -count..count.
    Copies that reach their cell walls are not cut: the nearest neighbour cell on each
    repeated axis is evaluated too (2^k evaluations for k axes), which is exact while
    the child stays inside its own cell. A child well inside its cell (WALL_GAP) is
    evaluated once and capped by the distance to the next cell's copy.
    """

    kind = "repeat"

    def __init__(self, child: Node, period: float | Sequence[float],
                 count: int | Sequence[int] | None = None) -> None:
        if isinstance(period, Live) or isinstance(count, Live):
            raise ParameterError(f"{self.kind}: 'period' and 'count' cannot be live parameters (the cell "
                                 f"structure is compiled from them)")
        s = v.vector(self.kind, "period", period)
        if np.any(s < 0) or not s.any():
            raise ParameterError(f"{self.kind}: 'period' must be >= 0 per axis and not all 0, got {tuple(s)}")
        if count is None:
            n = np.full(3, -1)
        else:
            cnt = v.vector(self.kind, "count", count)
            if np.any(cnt < 0) or np.any(cnt != np.round(cnt)) or np.any(cnt > MAX_COUNT):
                raise ParameterError(f"{self.kind}: 'count' must be whole numbers in 0..{MAX_COUNT}, "
                                     f"got {tuple(cnt.tolist())}")
            n = cnt.astype(int)
        lo, hi = child.bounds
        axes = np.nonzero(s > 0)[0]
        extent = np.maximum(np.abs(lo), np.abs(hi))
        for ax in axes:
            if extent[ax] > s[ax] / 2 * (1 + 1e-9):
                raise ParameterError(
                    f"{self.kind}: the child {child.label()} reaches {extent[ax]:g} from its centre on axis "
                    f"{'xyz'[ax]}, beyond half the period ({s[ax] / 2:g}); use a period of at least "
                    f"{2 * extent[ax]:g}")
        super().__init__(child, period=s, count=None if count is None else n)
        self.s, self.n, self.axes = s, n, axes
        gap = s[axes] / 2 - extent[axes]
        self.gap = np.zeros(3)
        self.gap[axes] = gap
        self.cheap = bool(np.all(gap >= WALL_GAP * s[axes]))

    @property
    def exactness(self) -> str:
        if self.child.exactness == IMPLICIT:
            return IMPLICIT
        return EXACT if self.child.exactness == EXACT and not self.cheap else BOUND

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo, hi = self.child.bounds
        lo, hi = lo.copy(), hi.copy()
        for ax in self.axes:
            if self.n[ax] < 0:
                lo[ax], hi[ax] = -INF, INF
            else:
                lo[ax] -= self.n[ax] * self.s[ax]
                hi[ax] += self.n[ax] * self.s[ax]
        return lo, hi

    # -- shared by GLSL and numpy -------------------------------------------------------
    def _mask(self) -> np.ndarray:
        return (self.s > 0).astype(float)

    def _limit(self) -> np.ndarray:
        return np.where(self.n < 0, 1e30, self.n.astype(float))

    def _half_gap(self) -> np.ndarray:
        """Per axis, how far the next copy's bounds are from a cell's centre plane (1e30: none)."""
        return np.where((self.s > 0) & (self.n != 0), self.s / 2 + self.gap, 1e30)

    def _neighbours(self) -> list[np.ndarray]:
        """Per-axis 0/1 picks of the neighbour cells to visit besides the point's own."""
        picks = []
        for combo in itertools.product((0.0, 1.0), repeat=len(self.axes)):
            if any(combo):
                pick = np.zeros(3)
                pick[self.axes] = combo
                picks.append(pick)
        return picks

    def _emit(self, em: "Emitter", p: str) -> str:
        # an endless axis reads the point only modulo its period: the pending offset (the
        # shader origin, translations) is reduced modulo it in float64 before float32
        pt = em.point(p, period=np.where(self.n < 0, self.s, 0.0))
        inv = np.where(self.s > 0, 1.0 / np.where(self.s > 0, self.s, 1.0), 0.0)
        lim = em.vec(self._limit())
        period = em.vec(self.s)
        cell = em.assign("vec3", f"clamp(floor({pt} * {em.vec(inv)} + 0.5), -{lim}, {lim})")
        local = em.assign("vec3", f"{pt} - {period} * {cell}")
        fn = em.function(self.child)
        own = em.assign("float" if em.mode == "dist" else "vec4", f"{fn}({local})")
        if self.cheap:
            # the next copy is at least half a cell plus the gap away, measured from this
            # cell's walls; at the ends of a finite row only the inward neighbour exists
            half_gap = em.vec(self._half_gap())
            wall = em.assign("vec3", f"{half_gap} - abs({local})")
            wall = em.assign("vec3", f"mix({wall}, {half_gap} + {local}, vec3(equal({cell}, {lim})))")
            wall = em.assign("vec3", f"mix({wall}, {half_gap} - {local}, vec3(equal({cell}, -{lim})))")
            cap = f"min({wall}.x, min({wall}.y, {wall}.z))"
            if em.mode == "dist":
                return em.assign("float", f"min({own}, {cap})")
            return em.assign("vec4", f"vec4({own}.rgb, min({own}.w, {cap}))")
        side = em.assign("vec3", f"sign({local}) * {em.vec(self._mask())}")
        acc = own
        for pick in self._neighbours():
            nb = f"clamp({cell} + {side} * {em.vec(pick)}, -{lim}, {lim})"
            val = f"{fn}({pt} - {period} * {nb})"
            if em.mode == "dist":
                acc = em.assign("float", f"min({acc}, {val})")
            else:
                other = em.assign("vec4", val)
                acc = em.assign("vec4", f"({other}.w < {acc}.w) ? {other} : {acc}")
        return acc

    def _distance(self, p: np.ndarray) -> np.ndarray:
        inv = np.where(self.s > 0, 1.0 / np.where(self.s > 0, self.s, 1.0), 0.0)
        lim = self._limit()
        cell = np.clip(np.floor(p * inv + 0.5), -lim, lim)
        local = p - self.s * cell
        own = self.child._distance(local)
        if self.cheap:
            hg = self._half_gap()
            wall = hg - np.abs(local)
            wall = np.where(cell == lim, hg + local, wall)
            wall = np.where(cell == -lim, hg - local, wall)
            return np.minimum(own, wall.min(axis=-1))
        side = np.sign(local) * self._mask()
        acc = own
        for pick in self._neighbours():
            nb = np.clip(cell + side * pick, -lim, lim)
            acc = np.minimum(acc, self.child._distance(p - self.s * nb))
        return acc


@fluent()
def repeat(node: Node, period: float | Sequence[float], count: int | Sequence[int] | None = None) -> Repeat:
    """Repeat ``node`` on a grid.

    Args:
        node: the node placed in the cell around the origin; it must fit within half a
            period on each repeated axis.
        period: cell size: one number for all axes, or (px, py, pz) with 0 for an axis that
            is not repeated.
        count: None for endless copies, else copies per side on each axis (whole numbers,
            0..1e6): count 2 gives 5 copies along that axis.

    Keeps the child's exactness (copies that touch their cell walls are not cut).

    Example:
        >>> float(sg.repeat(sg.sphere(0.25), (1, 0, 0)).distance((3, 0, 0)))
        -0.25
    """
    return Repeat(node, period, count)
