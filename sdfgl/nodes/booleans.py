"""Union, intersection and difference, hard or smooth (quadratic smooth min, IQ, MIT).

A smoothing radius ``k`` of 0 gives the hard operator; a ``k`` too small to be
represented in float32 (< 1e-30) is treated as 0, so the generated code never divides
by zero.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

import numpy as np

from ..errors import ParameterError
from ..params import Live
from ..values import validate as v
from .layouts import layout
from .base import BOUND, EXACT, IMPLICIT, Node, boxes_of, fluent, level_factor
from .grid_scope import grid_min_now
from .blend_reach import blend_growth

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter
    from ..compiler.data.grid import Grid

K_MIN = 1e-30


BLENDS = ("quadratic", "circular", "chamfer")
# how far each blend can lower min(a, b), as a share of k (grows the bounds)
BLEND_REACH = {"quadratic": 0.25, "circular": 1.0, "chamfer": 0.5}
# where each blend acts at all: |a - b| below this share of k
BLEND_WINDOW = {"quadratic": 1.0, "circular": 1.0 / (1.0 - np.sqrt(0.5)), "chamfer": 1.0}
BLEND_GLSL = {"circular": ("op_circular", "opCircular"), "chamfer": ("op_chamfer", "opChamfer")}
# how far apart a and b may lie for the blend to change min(a, b), as a share of k: beyond
# it each blend returns min(a, b) exactly (h = 0), in float64 and in float32
BLEND_SUPPORT = {"quadratic": 1.0, "circular": 1.0 / (1.0 - float(np.sqrt(0.5))), "chamfer": 1.0}


def smooth_min(a: np.ndarray, b: np.ndarray, k: float, blend: str = "quadratic") -> np.ndarray:
    """The float64 twin of the GLSL smooth minimum ``blend`` with radius ``k`` (elementwise)."""
    if blend == "chamfer":
        return np.minimum(np.minimum(a, b), (a + b - k) * 0.5)
    if blend == "circular":
        kk = k / (1.0 - np.sqrt(0.5))
        h = np.maximum(kk - np.abs(a - b), 0.0) / kk
        return np.minimum(a, b) - kk * 0.5 * (1.0 + h - np.sqrt(1.0 - h * (h - 2.0)))
    h = np.maximum(k - np.abs(a - b), 0.0) / k
    return np.minimum(a, b) - h * h * k * 0.25


def smooth_max(a: np.ndarray, b: np.ndarray, k: float, blend: str = "quadratic") -> np.ndarray:
    """The float64 twin of the smooth maximum: ``-smooth_min(-a, -b)``."""
    return -smooth_min(-a, -b, k, blend)


def smooth_glsl(em: "Emitter", a: str, b: str, k: object, blend: str, negate: bool = False) -> str:
    """GLSL for the blended min of the expressions a and b with radius ``k`` (a number or a
    live parameter) and kind ``blend`` (or the max, as -min(-a, -b), with ``negate``)."""
    if blend == "quadratic":
        em.require("op_smax" if negate else "op_smin")
        return f"{'opSmax' if negate else 'opSmin'}({a}, {b}, {em.num(k)})"
    lib, fn = BLEND_GLSL[blend]
    em.require(lib)
    if negate:
        return f"-{fn}(-{a}, -{b}, {em.num(k)})"
    return f"{fn}({a}, {b}, {em.num(k)})"


_STATE = ("_ctor_kw", "blend", "params", "k")  # the attributes a _Boolean's __init__ sets besides its children


class _Boolean(Node):
    """N-ary boolean folded left to right."""

    def __init__(self, *children: Node, k: float = 0.0, blend: str = "quadratic") -> None:
        if len(children) < 2:
            raise ParameterError(f"{self.kind}: needs at least two operands, got {len(children)}")
        if blend not in BLENDS:
            raise ParameterError(f"{self.kind}: 'blend' must be one of {', '.join(BLENDS)}, got {blend!r}")
        self.blend = blend
        kk = v.scalar(self.kind, "k", k, nonnegative=True)
        if isinstance(kk, Live):  # a live blend radius is always smooth, so it must stay > 0
            def check() -> None:
                if float(kk) < K_MIN:
                    raise ParameterError(f"{self.kind}: live parameter 'k' must stay >= {K_MIN:g} (the smooth "
                                         f"code is compiled in), got {float(kk):g}")
            v.watch(check, kk)
        else:
            kk = 0.0 if kk < K_MIN else kk
        params = {"k": kk} if blend == "quadratic" else {"k": kk, "blend": blend}
        super().__init__(children, **params)
        self.k = kk

    # children are kept in lists shared along a chain built by ``s = s | x`` (each step
    # appends to the back: O(1)) or, for hard unions and intersections, ``s = x | s``
    # (appends to the front list, read reversed); the tuple is made when first read
    @property  # type: ignore[override]
    def children(self) -> tuple[Node, ...]:
        kids = self.__dict__.get("_kids")
        if kids is None:
            back, n, front, m = self.__dict__["_seq"]
            kids = tuple(back[:n]) if not m else tuple(front[m - 1::-1]) + tuple(back[:n])
            self.__dict__["_kids"] = kids
        return kids

    @children.setter
    def children(self, value: tuple[Node, ...]) -> None:
        self.__dict__["_kids"] = tuple(value)

    def _chained(self, node: Node, front: bool = False) -> "_Boolean":
        """This n-ary node with ``node`` appended (the left fold of one more operand), or
        put first (``front``: only for operators where the order does not change the field)."""
        d = self.__dict__
        seq = d.get("_seq")
        if seq is None:
            kids = self.children
            seq = d["_seq"] = (list(kids), len(kids), [], 0)
        back, n, fr, m = seq
        if front:
            fr = fr if len(fr) == m else fr[:m]  # another chain already grew from this node: branch off a copy
            fr.append(node)
            m += 1
        else:
            back = back if len(back) == n else back[:n]
            back.append(node)
            n += 1
        out = type(self).__new__(type(self))
        od = out.__dict__
        for name in _STATE:  # what __init__ set; caches and the children stay behind
            if name in d:
                od[name] = d[name]
        od["_seq"] = (back, n, fr, m)
        return out

    @property
    def constructor(self) -> tuple[type, tuple, dict]:
        """(class, children, k/blend): a node grown by ``s = s | x`` describes itself as the
        flat n-ary call that builds it (for pickle and scene documents)."""
        _, _, kwargs = super().constructor
        return type(self), self.children, kwargs

    def _same_op(self, cls: type, k: object, blend: str) -> bool:
        if type(self) is not cls or self.blend != blend:
            return False
        if type(k) in (float, int) and type(self.k) is float and k == 0.0 and self.k == 0.0:  # hard, plain
            return True
        if isinstance(k, Live) or isinstance(self.k, Live):
            return k is self.k
        kk = float(k)
        return float(self.k) == (0.0 if kk < K_MIN else kk)

    @property
    def _hard(self) -> bool:
        return not isinstance(self.k, Live) and self.k == 0

    @property
    def exactness(self) -> str:
        kinds = {c.exactness for c in self.children}
        if IMPLICIT in kinds:
            return IMPLICIT
        return BOUND

    @property
    def lipschitz(self) -> float:
        return max(c.lipschitz for c in self.children)

    def _smooth(self, em: "Emitter", a: str, b: str, negate: bool = False) -> str:
        """GLSL for the blended min of a and b (or max, as -min(-a, -b))."""
        return smooth_glsl(em, a, b, self.k, self.blend, negate)

    def distinct_children(self) -> tuple[Node, ...]:
        """The children the shader evaluates: a hard union or intersection of equal children
        is one of them (min(a, a) = a), so copies built apart (same key) are written once;
        every other operation keeps all of them."""
        if not (self._hard and self.kind in ("union", "intersection")):
            return self.children
        out = distinct_by_key(self.children)
        return self.children if len(out) == len(self.children) else tuple(out)

    def _emit(self, em: "Emitter", p: str) -> str:
        children = self.distinct_children()
        acc = children[0].emit(em, p)
        for c in children[1:]:
            acc = self._combine(em, acc, em.guarded(c, p, self._idle_above(em, acc)))
        return acc

    def _idle_above(self, em: "Emitter", acc: str) -> str | None:
        """GLSL of the value above which a child's field cannot change the result combined so
        far (``acc``), for :meth:`sdfgl.compiler.emitter.Emitter.guarded`; None: every value can."""
        return None

    def _support(self) -> float | None:
        """The blend's support R: beyond it (|a - b| >= R) the smooth min is the min exactly, in
        float32 too; None for a live radius."""
        return None if isinstance(self.k, Live) else BLEND_SUPPORT[self.blend] * float(self.k)

    def _combine(self, em: "Emitter", a: str, b: str) -> str:
        raise NotImplementedError

    def _distance(self, p: np.ndarray) -> np.ndarray:
        acc = self.children[0]._distance(p)
        for c in self.children[1:]:
            acc = self._fold(acc, c._distance(p))
        return acc

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        raise NotImplementedError


def distinct_by_key(nodes: Sequence[Node]) -> list[Node]:
    """``nodes`` without those equal (same key) to one before them."""
    seen: set = set()
    return [c for c in nodes if not (c.key in seen or seen.add(c.key))]


def distinct_nodes(nodes: Sequence[Node]) -> list[Node]:
    """``nodes`` without repeats of one object or copies equal (same key) to one before them.
    Equal nodes have equal boxes, so a key is computed only for a node whose box's hash
    another shares: none for 10^5 children in as many places."""
    ids: set[int] = set()
    kids = [c for c in nodes if not (id(c) in ids or ids.add(id(c)))]
    if len(kids) < 2:
        return kids
    bits = np.ascontiguousarray(boxes_of(kids)).reshape(len(kids), 6).view(np.int64)
    hashes = (bits * _BOX_MIX).sum(axis=1)  # wraps; equal boxes have equal hashes
    ordered = np.sort(hashes)
    if not (ordered[1:] == ordered[:-1]).any():  # the common case: no two alike
        return kids
    _, inverse, counts = np.unique(hashes, return_inverse=True, return_counts=True)
    shared = counts[inverse.ravel()] > 1
    keys: set = set()
    return [c for c, alike in zip(kids, shared) if not alike or not (c.key in keys or keys.add(c.key))]


_BOX_MIX = np.array([0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0xD6E8FEB86659FD93,
                     0xFF51AFD7ED558CCD, 0xC4CEB9FE1A85EC53], dtype=np.uint64).view(np.int64)
"""Odd 64-bit multipliers (golden-ratio and hash-finaliser constants) that mix a box's six
float bit patterns into one hash."""


class Union(_Boolean):
    """Union (min). A hard union of many simple primitives is kept as data with a cell
    grid (sdfgl.compiler.data.grid): its field is then min(children, cap), a distance bound that
    is exact wherever the min is below the cap (about one grid cell). A smooth union of
    many instances of one type is kept as data too (sdfgl.compiler.data.blend_lists): each
    cell lists the children the blend may need there, folded in the union's order, so its
    field is min(the code's, cap), the code's wherever it is below the cap (two cells
    beyond the blend's support); the twin stays the full fold."""

    kind = "union"

    @property
    def grid(self) -> "Grid | None":
        """The grid of this union's instances under the grid_min in force (see
        grid_scope.grid_min_as), or None where it stays code (or no layout is registered)."""
        least = grid_min_now()
        name = "_grid" if least is None else f"_grid@{least}"
        d = self.__dict__
        if name not in d:
            build = layout("union")
            if build is None or isinstance(self.k, Live):
                d[name] = None
            elif self._hard:
                d[name] = build(self._distinct(), least)
            else:
                d[name] = build(list(self.children), least, blend=(float(self.k), self.blend))
        return d[name]

    def _distinct(self) -> list[Node]:
        """The children once each (:func:`distinct_nodes`), found once."""
        d = self.__dict__
        if "_grid_kids" not in d:  # a cache (CACHES: "_grid")
            d["_grid_kids"] = distinct_nodes(self.children)
        return d["_grid_kids"]

    def data_union(self) -> "Grid | None":
        """This union's grid (see :attr:`grid`): the instances it keeps as data."""
        return self.grid

    def _emit(self, em: "Emitter", p: str) -> str:
        grid = self.grid if em.use_grids else None
        if grid is None:
            return super()._emit(em, p)
        acc = em.grid_union(grid, p)
        for c in grid.rest:
            d = c.emit(em, p)
            em.narrow_free_way(grid, d)
            acc = self._combine(em, acc, d)
        return acc

    def _distance(self, p: np.ndarray) -> np.ndarray:
        grid = self.grid if self._hard else None  # a smooth union's twin is the full fold
        if grid is None:
            return super()._distance(p)
        d = grid.field(p)  # what the shader computes: the listed instances and the cap
        for c in grid.rest:
            d = np.minimum(d, c._distance(p))
        return d

    @property
    def exactness(self) -> str:
        # min() of exact fields is exact outside the solid (a bound inside); smoothing and
        # the grid's cap break it
        grid = self.grid if self._hard else None
        if grid is not None:  # its instances are bounded, not implicit, 1-Lipschitz (checked when built)
            return IMPLICIT if any(c.exactness == IMPLICIT for c in grid.rest) else BOUND
        if self._hard and all(c.exactness == EXACT for c in self.children):
            return EXACT
        return super().exactness

    @property
    def lipschitz(self) -> float:
        grid = self.grid if self._hard else None
        if grid is None:
            return super().lipschitz
        return max([1.0] + [c.lipschitz for c in grid.rest])

    def _idle_above(self, em: "Emitter", acc: str) -> str | None:
        a = acc if em.mode == "dist" else f"{acc}.w"
        if self._hard:
            return a  # min(a, b) is a where b > a
        support = self._support()
        return None if support is None else f"({a} + {em.num(support)})"  # smin(a, b) is a where b >= a + R

    def _combine(self, em: "Emitter", a: str, b: str) -> str:
        if em.mode == "dist":
            if self._hard:
                return em.assign("float", f"min({a}, {b})")
            return em.assign("float", self._smooth(em, a, b))
        if self._hard:
            return em.assign("vec4", f"({a}.w < {b}.w) ? {a} : {b}")
        em.require("op_smin_color")
        mixed = em.assign("vec4", f"opSminColor({a}, {b}, {em.num(self.k)})")
        if self.blend == "quadratic":
            return mixed
        return em.assign("vec4", f"vec4({mixed}.rgb, {self._smooth(em, f'{a}.w', f'{b}.w')})")

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.minimum(a, b) if self._hard else smooth_min(a, b, float(self.k), self.blend)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        if self._hard:
            boxes = boxes_of(self.children)
            return boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)
        return self.level_bounds(0.0)

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        if self._hard:  # min(f) < t needs some child below t
            boxes = np.array([c.level_bounds(t) for c in self.children])
            return boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)
        kids = self.children
        boxes = boxes_of(kids)
        lo, hi = boxes[:, 0], boxes[:, 1]
        k = float(self.k)
        g = level_factor(self)  # a union does not stretch: its children's largest, found in one walk
        grow = blend_growth(lo, hi, t, k * BLEND_REACH[self.blend], k * BLEND_WINDOW[self.blend], g)[:, None]
        return (lo - grow).min(axis=0), (hi + grow).max(axis=0)


class Intersection(_Boolean):
    kind = "intersection"

    def _combine(self, em: "Emitter", a: str, b: str) -> str:
        if em.mode == "dist":
            if self._hard:
                return em.assign("float", f"max({a}, {b})")
            return em.assign("float", self._smooth(em, a, b, negate=True))
        if self._hard:
            return em.assign("vec4", f"({a}.w > {b}.w) ? {a} : {b}")
        em.require("op_smax_color")
        mixed = em.assign("vec4", f"opSmaxColor({a}, {b}, {em.num(self.k)})")
        if self.blend == "quadratic":
            return mixed
        return em.assign("vec4", f"vec4({mixed}.rgb, {self._smooth(em, f'{a}.w', f'{b}.w', negate=True)})")

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.maximum(a, b) if self._hard else smooth_max(a, b, float(self.k), self.blend)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo = np.max([c.bounds[0] for c in self.children], axis=0)
        hi = np.min([c.bounds[1] for c in self.children], axis=0)
        return lo, np.maximum(hi, lo)


class Difference(_Boolean):
    """The first operand minus all the others."""

    kind = "difference"

    def _idle_above(self, em: "Emitter", acc: str) -> str | None:
        a = acc if em.mode == "dist" else f"{acc}.w"
        if self._hard:
            return f"-{a}"  # max(a, -b) is a where b > -a
        support = self._support()
        return None if support is None else f"({em.num(support)} - {a})"  # smax(a, -b) is a where b >= R - a

    def _combine(self, em: "Emitter", a: str, b: str) -> str:
        if em.mode == "dist":
            if self._hard:
                return em.assign("float", f"max({a}, -{b})")
            return em.assign("float", self._smooth(em, a, f"(-{b})", negate=True))
        neg = f"vec4({b}.rgb, -{b}.w)"
        if self._hard:
            return em.assign("vec4", f"({a}.w > -{b}.w) ? {a} : {neg}")
        em.require("op_smax_color")
        mixed = em.assign("vec4", f"opSmaxColor({a}, {neg}, {em.num(self.k)})")
        if self.blend == "quadratic":
            return mixed
        return em.assign("vec4", f"vec4({mixed}.rgb, {self._smooth(em, f'{a}.w', f'(-{b}.w)', negate=True)})")

    def _fold(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.maximum(a, -b) if self._hard else smooth_max(a, -b, float(self.k), self.blend)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.children[0].bounds


class Product(Node):
    """The product a * b of two fields: zero on both surfaces, but not a distance.

    The "product union" of Monzón González's thesis: an implicit field with no Lipschitz bound, which
    only the Newton and reference marchers may render. Its solid (a * b < 0) is where
    exactly one operand is inside.
    """

    kind = "product"

    def __init__(self, a: Node, b: Node) -> None:
        super().__init__((a, b))

    @property
    def exactness(self) -> str:
        return IMPLICIT

    @property
    def lipschitz(self) -> float:
        return float("inf")

    def _emit(self, em: "Emitter", p: str) -> str:
        a = self.children[0].emit(em, p)
        b = self.children[1].emit(em, p)
        if em.mode == "dist":
            return em.assign("float", f"{a} * {b}")
        # colour of the nearer surface
        return em.assign("vec4", f"vec4(abs({a}.w) < abs({b}.w) ? {a}.rgb : {b}.rgb, {a}.w * {b}.w)")

    def _distance(self, p: np.ndarray) -> np.ndarray:
        return self.children[0]._distance(p) * self.children[1]._distance(p)

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        los, his = zip(*(c.bounds for c in self.children))
        return np.min(los, axis=0), np.max(his, axis=0)


def product(a: Node, b: Node) -> Node:
    """The "product union" of Monzón González's thesis: the implicit field a * b, zero on both surfaces.

    Args:
        a: first node.
        b: second node.

    Implicit (no distance guarantee): render with ``method="newton"`` or
    ``"forward_newton"``; the sphere-tracing methods refuse it.

    Example:
        >>> sg.product(sg.sphere(1), sg.box(1)).exactness
        'implicit'
    """
    return Product(a, b)


def _build(cls: type, nodes: tuple, k: object, blend: str) -> Node:
    """The n-ary node: an operand that is the same operator with the same blend is
    spliced in from the left (``s = s | x`` in a loop stays one flat node, O(1) a step);
    a hard union or intersection of one node object with itself is that node."""
    if (len(nodes) == 2 and nodes[0] is nodes[1] and cls is not Difference and isinstance(nodes[0], Node)
            and not isinstance(k, Live) and float(k) < K_MIN):
        return nodes[0]
    first = nodes[0] if nodes else None
    if (len(nodes) >= 2 and isinstance(first, _Boolean) and first._same_op(cls, k, blend)
            and isinstance(k, (int, float, Live)) and blend in BLENDS):
        rest = nodes[1:]
        for n in rest:
            if not isinstance(n, Node) or n is first:
                break
        else:
            out = first
            for n in rest:
                out = out._chained(n)
            return out
    last = nodes[-1] if len(nodes) == 2 else None
    if (isinstance(last, _Boolean) and cls is not Difference and last._same_op(cls, k, blend) and last._hard
            and isinstance(first, Node) and first is not last):
        # x | s (a right-deep chain): min and max are associative, so x joins s's operands first
        return last._chained(first, front=True)
    return cls(*nodes, k=k, blend=blend)


@fluent("union", "__or__")
def union(*nodes: Node, k: float = 0.0, blend: str = "quadratic") -> Node:
    """Union of two or more nodes (``a | b``), optionally blended; 2D shapes give a 2D union.

    Args:
        nodes: two or more nodes; colours are kept per part (and mixed across a blend).
        k: blend radius in scene units, >= 0 (0: a hard min; may be a live ``sg.param``).
        blend: "quadratic" (smooth minimum), "circular" (a quarter-circle fillet) or
            "chamfer" (a 45-degree bevel).

    A bound: exact outside for a hard union of exact fields, a bound inside and when blended.

    Example:
        >>> float(sg.union(sg.sphere(1), sg.sphere(1, (3, 0, 0))).distance((1.5, 0, 0)))
        0.5
    """
    if _all_2d(nodes):
        from .shapes2d_ops import union as union2
        return union2(*nodes, k=k, blend=blend)  # type: ignore[return-value]
    return _build(Union, nodes, k, blend)


@fluent("intersection", "__and__")
def intersection(*nodes: Node, k: float = 0.0, blend: str = "quadratic") -> Node:
    """Intersection of two or more nodes (``a & b``) or 2D shapes, optionally blended.

    Args:
        nodes: two or more nodes.
        k: blend radius in scene units, >= 0: rounds the seam.
        blend: "quadratic", "circular" or "chamfer" (see :func:`union`).

    A bound.

    Example:
        >>> float((sg.sphere(1) & sg.box(1)).distance((2, 0, 0)))
        1.5
    """
    if _all_2d(nodes):
        from .shapes2d_ops import intersection as intersection2
        return intersection2(*nodes, k=k, blend=blend)  # type: ignore[return-value]
    return _build(Intersection, nodes, k, blend)


@fluent("difference", "__sub__")
def difference(*nodes: Node, k: float = 0.0, blend: str = "quadratic") -> Node:
    """The first node (or 2D shape) minus all the others (``a - b``), optionally blended.

    Args:
        nodes: the node to cut, then the nodes cut away.
        k: blend radius in scene units, >= 0: rounds the cut.
        blend: "quadratic", "circular" or "chamfer" (see :func:`union`).

    A bound.

    Example:
        >>> float((sg.box(2) - sg.sphere(0.5)).distance((0, 0, 0)))
        0.5
    """
    if _all_2d(nodes):
        from .shapes2d_ops import difference as difference2
        return difference2(*nodes, k=k, blend=blend)  # type: ignore[return-value]
    return _build(Difference, nodes, k, blend)


def _all_2d(nodes: tuple) -> bool:
    if not nodes or isinstance(nodes[0], Node):  # the common case, without the import
        return False
    from .shapes2d import Shape2D
    return all(isinstance(n, Shape2D) for n in nodes)
