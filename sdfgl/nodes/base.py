"""The scene-graph node: parameters, GLSL emission, float64 twin, Lipschitz factor, bounds.

Every concrete node keeps these five things together in one class, so the GPU code and
the numpy reference cannot drift apart unnoticed (the parity tests hold them equal).
"""
from __future__ import annotations

import threading
import weakref
from typing import TYPE_CHECKING, Any, Callable, ClassVar, Sequence, TypeVar

import numpy as np

from ..errors import ParameterError
from ..params import Live, Param, owns_checks
from . import facts  # noqa: F401 - registers the live parameters, detail and material fields as facts
from .grid_scope import grid_min_as, grid_min_now
from .record import Recorded
from .traverse import SHALLOW, WIDE, cached, collector_paused, depth, fact, postorder, run_deep

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter

EXACT = "exact"        # |f| is the Euclidean distance to the surface (outside, at least)
BOUND = "bound"        # |f| <= distance and the gradient norm is <= lipschitz
IMPLICIT = "implicit"  # a level set with no distance guarantee (e.g. product union)

INF = float("inf")


def as_points(points: object) -> np.ndarray:
    """Return points as a float64 array of shape (..., 3)."""
    try:
        p = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise ParameterError(f"points must be numbers of shape (..., 3), got {type(points).__name__}") from None
    if p.ndim == 0 or p.shape[-1] != 3:
        raise ParameterError(f"points must have shape (..., 3), got {p.shape}")
    return p


def _vec3(x: Any) -> np.ndarray:
    a = np.array(x, dtype=np.float64)
    return a if a.shape == (3,) else np.array(np.broadcast_to(a, (3,)))


class _Token:
    """Stands for one structure in the keys of its parents (keys stay flat, hashing O(1))."""

    __slots__ = ("__weakref__",)


_TOKENS: "weakref.WeakValueDictionary[tuple, _Token]" = weakref.WeakValueDictionary()
_TWIN = threading.local()  # the per-call memo of the float64 twin over a DAG


def _memo_property(name: str, fget: Callable[["Node"], Any]) -> property:
    """A node property computed once per node, bottom-up (no recursion, a DAG costs once);
    memoised per grid_min (a union kept as data has a grid's cap: a bound, not exact)."""
    base_slot, busy = f"_m_{name}", f"_busy_{name}"

    def get(self: "Node") -> Any:
        d = self.__dict__
        least = grid_min_now()
        slot = base_slot if least is None else f"{base_slot}@{least}"
        if slot in d:
            return d[slot]
        if d.get(busy):  # a super() call while this node is being computed
            return fget(self)
        live = d.get("_live_cache")
        if live is None:
            live = fact(self, "_live_cache")
        if live:
            return fget(self)
        if depth(self) <= SHALLOW or all(slot in c.__dict__ for c in self.children):
            # shallow: compute directly (children memoise as they are asked, only those needed);
            # this property is the one self's class resolves (a super() call found busy above)
            d[busy] = True
            try:
                d[slot] = fget(self)
            finally:
                del d[busy]
            return d[slot]
        for n in postorder(self, skip=lambda n: slot in n.__dict__):
            n.__dict__[busy] = True
            try:
                n.__dict__[slot] = getattr(n, name)
            finally:
                del n.__dict__[busy]
        return d[slot]
    return property(get, doc=fget.__doc__)


def _memo_distance(fn: Callable[["Node", np.ndarray], np.ndarray]) -> Callable[["Node", np.ndarray], np.ndarray]:
    """While Node.distance() evaluates a DAG, a node met again at the same point array
    returns its result instead of evaluating its subtree again."""
    def dist(self: "Node", p: np.ndarray) -> np.ndarray:
        memo = getattr(_TWIN, "memo", None)
        if memo is None:
            return fn(self, p)
        k = (id(self), id(p))
        hit = memo.get(k)
        if hit is not None and hit[0] is p:
            return hit[1]
        out = fn(self, p)
        memo[k] = (p, out)  # p is held, so its id stays unique for the call
        return out
    dist.__wrapped__ = fn  # type: ignore[attr-defined]
    return dist


def box_of(node: "Node") -> np.ndarray:
    """``node.bounds`` without the defensive copies: a read-only (2, 3) array (lo, hi).

    Computed once per node without live parameters, children first; a graph deeper than
    SHALLOW fills its cache bottom-up (no recursion). The cache is one array, not a tuple,
    so a 10^5-node scene leaves no extra objects for the cyclic garbage collector."""
    d = node.__dict__
    hit = d.get("_bounds_cache")
    if hit is not None:
        return hit
    live = d.get("_live_cache")
    if live is None:
        live = fact(node, "_live_cache")
    kids = node.children
    if kids and not live and depth(node) > SHALLOW and not all("_bounds_cache" in c.__dict__ for c in kids):
        with collector_paused():
            for n in postorder(node, skip=lambda n: "_bounds_cache" in n.__dict__):
                if n is not node:
                    box_of(n)
    if len(kids) >= WIDE:  # its children's boxes, and theirs, are made now: a big walk
        with collector_paused():
            b = node._bounds
    else:
        b = node._bounds
    # a (2, 3) float64 array made by _bounds (Translate's) is kept as it is; else one array is made
    if type(b) is np.ndarray and b.shape == (2, 3) and b.dtype == np.float64 and b.flags.owndata:
        out = b
    else:
        try:  # (lo, hi) of two 3-vectors: one array in one call
            out = np.array(b, dtype=np.float64)
        except (TypeError, ValueError):  # rows of different shapes (a scalar and a vector)
            out = None
        if out is None or out.shape != (2, 3):
            out = np.empty((2, 3))
            out[0], out[1] = _vec3(b[0]), _vec3(b[1])
    out.flags.writeable = False
    if not live:
        d["_bounds_cache"] = out
    return out


BATCH = 64  # the fewest nodes of one class that boxes_of hands to the class's batch_bounds


def boxes_of(nodes: Sequence["Node"]) -> np.ndarray:
    """``box_of`` of each node as one (n, 2, 3) array (a wide union's children): cached boxes are
    read, the others made by class in batches where it can (:meth:`Node.batch_bounds`), else one
    by one. A batch's box is cached (a read-only row) only on a node known to hold no live
    parameter, so a live parameter's box is always its current one."""
    hits = [c.__dict__.get("_bounds_cache") for c in nodes]
    missing = [i for i, hit in enumerate(hits) if hit is None]
    if not missing:
        return np.array(hits) if hits else np.empty((0, 2, 3))
    out = np.empty((len(nodes), 2, 3))
    if len(missing) < len(nodes):
        have = np.ones(len(nodes), dtype=bool)
        have[missing] = False
        out[have] = [hit for hit in hits if hit is not None]
    todo: dict[type, list[int]] = {}
    for i in missing:
        todo.setdefault(type(nodes[i]), []).append(i)
    for cls, rows in todo.items():
        group = [nodes[i] for i in rows]
        got = cls.batch_bounds(group) if len(group) >= BATCH else None
        if got is None:
            out[rows] = [box_of(c) for c in group]
            continue
        out[rows] = got
        got.flags.writeable = False  # its rows, kept as the nodes' boxes, are read-only views
        for c, box in zip(group, list(got)):  # list(): the row views made in one call
            d = c.__dict__
            if d.get("_live_cache") == ():
                d["_bounds_cache"] = box
    return out


class Node(Recorded, register=False):
    """Base class of every scene-graph node. Nodes are immutable after construction.

    Operators and methods build new nodes (fogleman/sdf style): ``a | b``, ``a & b``,
    ``a - b``, ``.translate``, ``.rotate``, ``.scale``, ``.color`` and the rest. Each is a
    function of the node family's module registered here with :func:`fluent` (the table
    :data:`FLUENT` lists them). Every node has ``distance(points)`` (the float64 twin of the
    generated GLSL), ``exactness``, ``lipschitz`` and ``bounds``.

    A subclass that sets ``kind`` is registered under it (see :mod:`sdfgl.nodes.record`):
    pickle and scene documents rebuild it from its constructor's arguments.

    Example:
        >>> s = (sg.sphere(1) & sg.box(1.5)).translate((0, 1, 0)).color(0.9, 0.3, 0.2)
        >>> s.exactness, float(s.distance((0, 3, 0)))
        ('bound', 1.25)
    """
    kind: ClassVar[str] = "node"
    costly: ClassVar[bool] = False  # its GLSL costs far more than a box test (see compiler.guards)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "__init__" in cls.__dict__:  # live-parameter checks made while building belong to the node
            cls.__init__ = owns_checks(cls.__init__)  # type: ignore[method-assign]
        for name in ("exactness", "lipschitz"):
            prop = cls.__dict__.get(name)
            if isinstance(prop, property) and prop.fget is not None:
                setattr(cls, name, _memo_property(name, prop.fget))
        if "_distance" in cls.__dict__:
            cls._distance = _memo_distance(cls.__dict__["_distance"])  # type: ignore[method-assign]

    def __init__(self, children: Sequence["Node"] = (), **params: object) -> None:
        for c in children:
            if not isinstance(c, Node):
                i = next(i for i, c in enumerate(children) if not isinstance(c, Node))
                raise ParameterError(f"{self.kind}: operand {i} must be an sdfgl node, got {type(c).__name__} {c!r}")
        self.children: tuple[Node, ...] = tuple(children)
        self.params: dict[str, object] = params

    # -- identity -----------------------------------------------------------------------
    @property
    def key(self) -> tuple:
        """Structural key: equal keys mean equal fields (used to share code and caches)."""
        return cached(self, "_key", lambda n: n._make_key())

    @property
    def token(self) -> _Token:
        """One object per distinct structure: equal tokens mean equal keys."""
        key = self.key
        tok = self.__dict__.get("_token")
        if tok is None:
            tok = _TOKENS.get(key)
            if tok is None:
                tok = _TOKENS[key] = _Token()
            self.__dict__["_token"] = tok
        return tok

    def _make_key(self) -> tuple:
        def freeze(v: object) -> object:
            if isinstance(v, Live):
                return ("live", id(v))
            if isinstance(v, np.ndarray):
                return tuple(v.ravel().tolist())
            if isinstance(v, (list, tuple)):
                return tuple(freeze(x) for x in v)
            return v
        # children by token: the key stays flat however deep the graph (hash and == are cheap)
        return (self.kind, tuple((k, freeze(v)) for k, v in sorted(self.params.items())),
                tuple(c.token for c in self.children))

    def label(self) -> str:
        """Short human-readable name used in error messages and shader comments."""
        def fmt(v: object) -> str:
            if isinstance(v, Live):  # by name, not value: the source must not change with it
                return f"param:{v.label}" if isinstance(v, Param) else "param-expr"
            if isinstance(v, np.ndarray):
                return "(" + ", ".join(f"{x:g}" for x in v.ravel()) + ")"
            if isinstance(v, float):
                return f"{v:g}"
            return str(v)
        args = ", ".join(f"{k}={fmt(v)}" for k, v in self.params.items())
        return f"{self.kind}({args})"

    def __repr__(self) -> str:
        """label[children...]; a subtree object met again prints as ``@N``, its first
        occurrence as ``@N=...`` (so a DAG prints in the size of its distinct nodes)."""
        counts: dict[int, int] = {}
        for n in postorder(self):
            for c in n.children:
                counts[id(c)] = counts.get(id(c), 0) + 1
        names: dict[int, int] = {}
        out: list[str] = []
        stack: list[object] = [self]
        while stack:
            item = stack.pop()
            if isinstance(item, str):
                out.append(item)
                continue
            n = item  # type: ignore[assignment]
            assert isinstance(n, Node)
            if id(n) in names:
                out.append(f"@{names[id(n)]}")
                continue
            tag = ""
            if counts.get(id(n), 0) > 1 and n.children:
                names[id(n)] = len(names) + 1
                tag = f"@{names[id(n)]}="
            if not n.children:
                out.append(tag + n.label())
                continue
            out.append(f"{tag}{n.label()}[")
            stack.append("]")
            for i, c in enumerate(reversed(n.children)):
                stack.append(c)
                if i < len(n.children) - 1:
                    stack.append(", ")
        return "".join(out)

    def to_dict(self) -> dict:
        """This scene as a JSON-ready document (docs/scene-format.md); ``sg.from_dict`` reads it back."""
        from ..scene_io import to_dict
        return to_dict(self)

    def _repr_png_(self) -> bytes | None:
        """A small render, shown inline by Jupyter (``sg.set_preview(False)`` turns it off)."""
        from ..web.notebook import preview_png
        return preview_png(self)

    def save(self, path: str, units: str | None = None, **mesh_options: Any) -> Any:
        """Mesh this node and write it (fogleman/sdf's ``f.save("out.stl")``); returns the Mesh.

        ``units`` (3MF only: "mm" by default, "cm", "inch", ...) says what a scene unit is;
        ``mesh_options`` are those of :func:`sdfgl.mesh` (step, resolution, samples, bounds, mode)."""
        from ..mesh import mesh
        m = mesh(self, **mesh_options)
        m.save(path, **({} if units is None else {"units": units}))
        return m

    # -- the five things every node provides ----------------------------------------------
    def emit(self, em: "Emitter", p: str) -> str:
        """Append GLSL for this node's field at point variable ``p``; return the result variable.

        In ``em.mode == "dist"`` the result is a float distance; in ``"color"`` mode it is a
        vec4 (rgb, distance).
        """
        # the same subtree at the same point, met again in one function: its value is reused
        memo = (id(self), p, em.current() if em.mode == "color" else None)
        hit = em.results.get(memo)
        if hit is not None:
            return hit[1]
        if self.children and em.shared_keys and self.key in em.shared_keys and self.key not in em._defining:
            # a subtree that occurs more than once in the scene is one GLSL function
            fn = em.function(self)
            out = em.mark(self, em.assign("float" if em.mode == "dist" else "vec4", f"{fn}({em.point(p)})"))
        else:
            em.enter(self)
            try:
                out = em.mark(self, self._emit(em, p))
            finally:
                em.leave()
        em.results[memo] = (self, out)  # the node is held, so its id stays unique
        return out

    def _emit(self, em: "Emitter", p: str) -> str:
        raise NotImplementedError

    # -- what the compiler asks a node, so that it never tests a node's class ----------------
    def data_union(self) -> Any:
        """The instances this node keeps as data (a hard union's grid, see
        sdfgl.compiler.data), or None: every other node is written as code."""
        return None

    def distance_keeping(self) -> tuple["Node", np.ndarray | None] | None:
        """(child, rotation R with world = R @ local, or None for no turn) where this node
        passes its one child on with distances kept (a translation, a rotation, a colour or
        material); None for every other node."""
        return None

    def analytic_plane(self) -> tuple[np.ndarray, np.ndarray] | None:
        """(unit normal, a point on it) where this node is a plane with constant parameters
        (a marcher may meet it in closed form); None for every other node."""
        return None

    def distance(self, points: object) -> np.ndarray:
        """The float64 twin of the generated map(): field values at (..., 3) points.

        The answer is a function of the scene alone: unions are kept as data as under the
        default settings, whatever settings (grid_min, code budget) the scene was compiled
        with."""
        p = as_points(points)

        def twin() -> np.ndarray:
            with grid_min_as(None):
                return self._distance(p)
        if not self.is_dag:
            return run_deep(self, twin)
        _TWIN.memo = {}
        try:
            return run_deep(self, lambda: _with_memo(_TWIN.memo, twin))
        finally:
            _TWIN.memo = None

    @property
    def is_dag(self) -> bool:
        """True if some node object is reached by more than one path (a shared subtree)."""
        hit = self.__dict__.get("_dag")
        if hit is None:
            seen: set[int] = set()
            hit = False
            for n in postorder(self):
                for c in n.children:
                    if id(c) in seen:
                        hit = True
                    seen.add(id(c))
            self.__dict__["_dag"] = hit
        return hit

    @property
    def exactness(self) -> str:
        """``"exact"``, ``"bound"`` or ``"implicit"``: what kind of field distance() is."""
        raise NotImplementedError

    @property
    def lipschitz(self) -> float:
        """Upper bound of the gradient norm of distance() (1 for exact and bound fields)."""
        return 1.0 if self.exactness != IMPLICIT else INF

    @property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Conservative axis-aligned box (lo, hi) holding the solid; components may be inf.

        With live parameters, the box for their current values; without, it is computed once."""
        lo, hi = box_of(self)
        return lo.copy(), hi.copy()

    @property
    def _bounds(self) -> tuple[Any, Any]:
        raise NotImplementedError

    @classmethod
    def batch_bounds(cls, nodes: Sequence["Node"]) -> np.ndarray | None:
        """The boxes of many nodes of this class at once, an (n, 2, 3) array equal to their
        ``box_of`` rows, or None where the class cannot (:func:`boxes_of` then goes one by one)."""
        return None

    def level_bounds(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        """A box holding every point where this node's field is below ``t`` (>= 0).

        Offsets and blends, which lower a field, grow their bounds by it. By default the
        bounds grown by ``t`` times :func:`level_factor`; nodes that know better override it."""
        lo, hi = box_of(self)
        grow = t * level_factor(self)
        return lo - grow, hi + grow

    def level_stretch(self) -> float:
        """How much this node itself divides its children's distances (see :func:`level_factor`)."""
        return 1.0

    @property
    def has_detail(self) -> bool:
        """True if some node shades with a more detailed field than it marches (see Displace)."""
        return fact(self, "_detail")

    def _detail_here(self) -> bool:
        """True if this node itself shades with more detail than it marches."""
        return False

    def live_params(self) -> list["Param"]:
        """The live parameters anywhere in this subtree (the tree is immutable: found once)."""
        hit = self.__dict__.get("_live_cache")
        return list(hit if hit is not None else fact(self, "_live_cache"))


FluentT = TypeVar("FluentT", bound=Callable[..., Any])

FLUENT: dict[str, Callable[..., Any]] = {}
"""Node's modelling methods and operators by name, each the function its family registered."""


def fluent(*names: str) -> Callable[[FluentT], FluentT]:
    """Register a function of a node as a :class:`Node` method (fogleman/sdf's op registry).

    ``@fluent()`` over ``def twist(node, rate, axis="y")`` in the module of the twist node
    makes ``s.twist(90)`` call ``twist(s, 90)``. ``names`` register it under other names
    instead (an operator such as ``"__or__"``, or a method named otherwise than the
    function). The function is returned unchanged: it stays its module's function, and its
    signature and docstring are the method's (``help(sg.Node.twist)``)."""
    def register(fn: FluentT) -> FluentT:
        for name in names or (fn.__name__,):
            old = FLUENT.get(name)
            if old is not None and (old.__module__, old.__qualname__) != (fn.__module__, fn.__qualname__):
                raise TypeError(f"Node.{name} is registered by {old.__module__}.{old.__qualname__} already")
            FLUENT[name] = fn
            setattr(Node, name, fn)
        return fn
    return register


CACHES = ("_m_", "_key", "_token", "_depth", "_bounds_cache", "_live_cache", "_detail", "_dag", "_grid", "_kids", "_level",
           "_seq", "_fields", "_facts", "_loops")


def level_factor(node: Node) -> float:
    """How slowly ``node``'s field can rise outside its bounds: at a point ``g * t`` or more
    outside ``node.bounds``, with g this factor, the field is at least ``t``.

    1 for a leaf (an exact field is at least the distance to the solid, so to its box; a
    bounded leaf's field is taken to rise as fast) and the largest of the children's times
    :meth:`Node.level_stretch` above them (a non-uniform scale, a warp that divides by its
    stretch, a displacement divided by its gradient bound). Computed once per node."""
    hit = node.__dict__.get("_level")
    if hit is not None:
        return hit
    live = node.__dict__.get("_live_cache")
    if live is None:
        live = fact(node, "_live_cache")
    if live:  # the factor follows the live values: not cached
        return _level_from(node, [level_factor(c) for c in node.children])
    return cached(node, "_level", _level_below)


def _level_below(n: Node) -> float:
    """level_factor of ``n`` from its children's (cached) factors."""
    return _level_from(n, [c.__dict__["_level"] for c in n.children])


def _level_from(node: Node, below: list[float]) -> float:
    return float(node.level_stretch()) * max(below, default=1.0)


def _with_memo(memo: dict, fn: Callable[[], np.ndarray]) -> np.ndarray:
    """Run ``fn`` with the twin's DAG memo set in this thread (the deep thread has its own)."""
    old = getattr(_TWIN, "memo", None)
    _TWIN.memo = memo
    try:
        return fn()
    finally:
        _TWIN.memo = old


class Unary(Node):
    """A node with one child whose exactness and Lipschitz factor it keeps unless it says otherwise."""

    def __new__(cls, child: object = None, *args: object, **kwargs: object) -> "Unary":
        # subclasses read the child (bounds, exactness) before Node.__init__ checks it
        if not isinstance(child, Node):
            raise ParameterError(f"{cls.kind}: the operand must be an sdfgl node, got {type(child).__name__} "
                                 f"{child!r}"[:200])
        return super().__new__(cls, child, *args, **kwargs)

    def __init__(self, child: Node, **params: object) -> None:
        # __new__ checked the child; no children tuple is kept (one object less per node
        # for the garbage collector): ``children`` is made from ``child`` when read
        self.child = child
        self.params: dict[str, object] = params

    @classmethod
    def unchecked(cls, child: Node, args: tuple, **params: object) -> "Unary":
        """This class over ``child`` with checked parameters (a fold): ``args`` (after the child)
        rebuild it, ``params`` is its parameter dict; the caller sets the class's attributes."""
        n = cls.__new__(cls, child, *args)
        n.child, n.params = child, params
        return n

    @property  # type: ignore[override]
    def children(self) -> tuple[Node, ...]:
        return (self.child,)

    @property
    def exactness(self) -> str:
        return self.child.exactness

    @property
    def lipschitz(self) -> float:
        return self.child.lipschitz


class Primitive(Node):
    """A leaf: a closed-form field. Subclasses give ``_expr`` (GLSL) and ``_distance`` (numpy)."""

    lib: ClassVar[tuple[str, ...]] = ()
    exact: ClassVar[bool] = True

    @property
    def exactness(self) -> str:
        return EXACT if self.exact else BOUND

    def _expr(self, em: "Emitter", p: str) -> str:
        raise NotImplementedError

    def _emit(self, em: "Emitter", p: str) -> str:
        em.require(*self.lib)
        d = em.assign("float", self._expr(em, em.point(p)))
        return em.with_color(d)
