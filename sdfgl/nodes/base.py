"""The scene-graph node: parameters, GLSL emission, float64 twin, Lipschitz factor, bounds.

Every concrete node keeps these five things together in one class, so the GPU code and
the numpy reference cannot drift apart unnoticed (the parity tests hold them equal).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar, Sequence

import numpy as np

from ..errors import ParameterError
from ..params import Live, Param, owns_checks
from .record import Recorded

if TYPE_CHECKING:  # pragma: no cover
    from ..codegen import Emitter

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


class Node(Recorded, register=False):
    """Base class of every scene-graph node. Nodes are immutable after construction.

    Operators and methods build new nodes (fogleman/sdf style): ``a | b``, ``a & b``,
    ``a - b``, ``.translate``, ``.rotate``, ``.scale``, ``.color`` and the rest. Every node
    has ``distance(points)`` (the float64 twin of the generated GLSL), ``exactness``,
    ``lipschitz`` and ``bounds``.

    A subclass that sets ``kind`` is registered under it (see :mod:`sdfgl.nodes.record`):
    pickle and scene documents rebuild it from its constructor's arguments.

    Example:
        >>> s = (sg.sphere(1) & sg.box(1.5)).translate((0, 1, 0)).color(0.9, 0.3, 0.2)
        >>> s.exactness, float(s.distance((0, 3, 0)))
        ('bound', 1.25)
    """

    kind: ClassVar[str] = "node"

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "__init__" in cls.__dict__:  # live-parameter checks made while building belong to the node
            cls.__init__ = owns_checks(cls.__init__)  # type: ignore[method-assign]

    def __init__(self, children: Sequence["Node"] = (), **params: object) -> None:
        for i, c in enumerate(children):
            if not isinstance(c, Node):
                raise ParameterError(f"{self.kind}: operand {i} must be an sdfgl node, got {type(c).__name__} {c!r}")
        self.children: tuple[Node, ...] = tuple(children)
        self.params: dict[str, object] = params

    # -- identity -----------------------------------------------------------------------
    @property
    def key(self) -> tuple:
        """Structural key: equal keys mean equal fields (used to share code and caches)."""
        cached = self.__dict__.get("_key")
        if cached is None:
            cached = self.__dict__["_key"] = self._make_key()
        return cached

    def _make_key(self) -> tuple:
        def freeze(v: object) -> object:
            if isinstance(v, Live):
                return ("live", id(v))
            if isinstance(v, np.ndarray):
                return tuple(v.ravel().tolist())
            if isinstance(v, (list, tuple)):
                return tuple(freeze(x) for x in v)
            return v
        return (self.kind, tuple((k, freeze(v)) for k, v in sorted(self.params.items())),
                tuple(c.key for c in self.children))

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
        if not self.children:
            return self.label()
        return f"{self.label()}[{', '.join(repr(c) for c in self.children)}]"

    def to_dict(self) -> dict:
        """This scene as a JSON-ready document (docs/scene-format.md); ``sg.from_dict`` reads it back."""
        from ..scene_io import to_dict
        return to_dict(self)

    def _repr_png_(self) -> bytes | None:
        """A small render, shown inline by Jupyter (``sg.set_preview(False)`` turns it off)."""
        from ..web.notebook import preview_png
        return preview_png(self)

    # -- the five things every node provides ----------------------------------------------
    def emit(self, em: "Emitter", p: str) -> str:
        """Append GLSL for this node's field at point variable ``p``; return the result variable.

        In ``em.mode == "dist"`` the result is a float distance; in ``"color"`` mode it is a
        vec4 (rgb, distance).
        """
        if self.key in em.shared_keys and self.key not in em._defining:
            # a subtree that occurs more than once in the scene is one GLSL function
            fn = em.function(self)
            return em.mark(self, em.assign("float" if em.mode == "dist" else "vec4", f"{fn}({em.point(p)})"))
        em.enter(self)
        try:
            return em.mark(self, self._emit(em, p))
        finally:
            em.leave()

    def _emit(self, em: "Emitter", p: str) -> str:
        raise NotImplementedError

    def distance(self, points: object) -> np.ndarray:
        """The float64 twin of the generated map(): field values at (..., 3) points."""
        return self._distance(as_points(points))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        raise NotImplementedError

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
        cached = self.__dict__.get("_bounds_cache")
        if cached is None:
            lo, hi = self._bounds
            cached = (np.array(np.broadcast_to(np.asarray(lo, dtype=np.float64), (3,))),
                      np.array(np.broadcast_to(np.asarray(hi, dtype=np.float64), (3,))))
            if not self.live_params():
                self.__dict__["_bounds_cache"] = cached
        return cached[0].copy(), cached[1].copy()

    @property
    def _bounds(self) -> tuple[Any, Any]:
        raise NotImplementedError

    @property
    def has_detail(self) -> bool:
        """True if some node shades with a more detailed field than it marches (see Displace)."""
        return any(c.has_detail for c in self.children)

    def live_params(self) -> list["Param"]:
        """The live parameters anywhere in this subtree (the tree is immutable: found once)."""
        cached = self.__dict__.get("_live_cache")
        if cached is None:
            cached = self.__dict__["_live_cache"] = self._find_live_params()
        return list(cached)

    def _find_live_params(self) -> list["Param"]:
        out: list[Param] = []
        for v in self.params.values():
            if isinstance(v, Live):
                out += [p for p in v.roots() if p not in out]
        for c in self.children:
            out += [p for p in c.live_params() if p not in out]
        return out

    # -- modelling API (fogleman/sdf style) ---------------------------------------------
    def save(self, path: str, **mesh_options: Any) -> Any:
        """Mesh this node and write it (fogleman/sdf's ``f.save("out.stl")``); returns the Mesh.

        ``mesh_options`` are those of :func:`sdfgl.mesh` (step, resolution, samples, bounds, mode)."""
        from ..mesh import mesh
        m = mesh(self, **mesh_options)
        m.save(path)
        return m

    def __or__(self, other: "Node") -> "Node":
        from .booleans import union
        return union(self, other)

    def __and__(self, other: "Node") -> "Node":
        from .booleans import intersection
        return intersection(self, other)

    def __sub__(self, other: "Node") -> "Node":
        from .booleans import difference
        return difference(self, other)

    def union(self, *others: "Node", k: float = 0.0, blend: str = "quadratic") -> "Node":
        """``self | others`` with blend radius ``k`` and ``blend`` style, as :func:`sdfgl.union`."""
        from .booleans import union
        return union(self, *others, k=k, blend=blend)

    def intersection(self, *others: "Node", k: float = 0.0, blend: str = "quadratic") -> "Node":
        """``self & others`` with blend radius ``k`` and ``blend`` style, as :func:`sdfgl.intersection`."""
        from .booleans import intersection
        return intersection(self, *others, k=k, blend=blend)

    def difference(self, *others: "Node", k: float = 0.0, blend: str = "quadratic") -> "Node":
        """``self - others`` with blend radius ``k`` and ``blend`` style, as :func:`sdfgl.difference`."""
        from .booleans import difference
        return difference(self, *others, k=k, blend=blend)

    def translate(self, offset: Sequence[float]) -> "Node":
        from .transforms import Translate
        return Translate(self, offset)

    def rotate(self, angle: float, axis: Sequence[float] = (0.0, 0.0, 1.0)) -> "Node":
        """Rotate by ``angle`` degrees about ``axis`` (through the origin)."""
        from .transforms import Rotate
        return Rotate.axis_angle(self, angle, axis)

    def orient(self, axis: Sequence[float]) -> "Node":
        """Rotate so that the node's Y axis points along ``axis``."""
        from .transforms import Rotate
        return Rotate.orient(self, axis)

    def scale(self, factor: float | Sequence[float]) -> "Node":
        """Scale uniformly (exactness kept) or per axis (the result is a bound)."""
        from .transforms import scale
        return scale(self, factor)

    def twist(self, rate: float, axis: str = "y") -> "Node":
        """Twist about ``axis`` (x, y or z) by ``rate`` degrees per unit along it (a bound; steps
        shortened here only)."""
        from .deform import Twist
        return Twist(self, rate, axis)

    def bend(self, rate: float, axis: str = "z") -> "Node":
        """Bend about ``axis`` by ``rate`` degrees per unit: about Z the XY plane turns by
        rate * x, about X the YZ plane by rate * y, about Y the ZX plane by rate * z (a bound)."""
        from .deform import Bend
        return Bend(self, rate, axis)

    def taper(self, rate: float, axis: str | Sequence[float] = "y", origin: float = 0.0) -> "Node":
        """Scale the cross-section across ``axis`` ("x", "y" or "z") by 1 + rate (u - origin)
        along it (a bound; only this subtree's steps shrink)."""
        from .deform import Taper
        return Taper(self, rate, axis, origin)

    def dilate(self, radius: float) -> "Node":
        """Grow by ``radius`` (f - r; the same node as :meth:`round`)."""
        return self.round(radius)

    def erode(self, radius: float) -> "Node":
        """Shrink by ``radius`` (f + r; a bound)."""
        from .operators import Erode
        return Erode(self, radius)

    def shear(self, amount: float, along: str = "x", by: str = "y") -> "Node":
        """Move coordinate ``along`` by ``amount`` times coordinate ``by`` (a bound; only this
        subtree's steps shrink)."""
        from .operators import Shear
        return Shear(self, amount, along, by)

    def repeat(self, period: float | Sequence[float], count: int | Sequence[int] | None = None) -> "Node":
        """Copies every ``period`` along the axes with a non-zero period; ``count`` limits them."""
        from .domain import Repeat
        return Repeat(self, period, count)

    def mirror(self, normal: Sequence[float] = (1.0, 0.0, 0.0), point: Sequence[float] = (0.0, 0.0, 0.0)) -> "Node":
        """This node on the side ``normal`` points to, plus its reflection in that plane."""
        from .shaping import Mirror
        return Mirror(self, normal, point)

    def symmetric(self, axes: str = "x") -> "Node":
        """Mirror across the coordinate planes named in ``axes`` (e.g. "xz")."""
        from .shaping import symmetric
        return symmetric(self, axes)

    def repeat_polar(self, count: int) -> "Node":
        """``count`` copies (this node placed around +X) turned evenly about Y."""
        from .shaping import PolarRepeat
        return PolarRepeat(self, count)

    def elongate(self, length: float | Sequence[float]) -> "Node":
        """Stretch by ``length`` along each axis, inserted at the centre planes."""
        from .shaping import Elongate
        return Elongate(self, length)

    def round(self, radius: float) -> "Node":
        """Grow by ``radius`` (f - r): rounded edges."""
        from .shaping import Round
        return Round(self, radius)

    def shell(self, thickness: float) -> "Node":
        """A shell ``thickness`` thick around the surface (|f| - t/2)."""
        from .shaping import Shell
        return Shell(self, thickness)

    def displace(self, amplitude: float, frequency: float = 1.0, octaves: int = 4,
                 normal_octaves: int | None = None) -> "Node":
        """Displace the surface by fBm noise (a bound; only this subtree's steps shrink)."""
        from .noise import Displace
        return Displace(self, amplitude, frequency, octaves, normal_octaves)

    def color(self, r: float | Sequence[float], g: float | None = None, b: float | None = None) -> "Node":
        """Give every part of this node that has no colour of its own the colour (r, g, b)."""
        from .transforms import Material
        rgb = r if g is None and b is None else (r, g, b)
        return Material(self, rgb)

    def material(self, color: object = None, *, specular: object = None, roughness: object = None,
                 shininess: object = None, metallic: object = None, emission: object = None) -> "Node":
        """Give every part of this node that does not set them itself these material fields.

        ``color`` as for :meth:`color`; ``specular`` (>= 0, default 0.25) scales the
        highlight; ``roughness`` in [0.05, 1] or ``shininess`` (the Blinn-Phong exponent,
        1..10000, default 48) sets its size; ``metallic`` in [0, 1] tints the highlight by
        the colour and removes the diffuse part; ``emission`` a colour added unlit. Fields
        left out keep what an outer node (or the default) says.
        """
        from .material import SurfaceMaterial
        return SurfaceMaterial(self, color, specular=specular, roughness=roughness, shininess=shininess,
                               metallic=metallic, emission=emission)


class Unary(Node):
    """A node with one child whose exactness and Lipschitz factor it keeps unless it says otherwise."""

    def __new__(cls, child: object = None, *args: object, **kwargs: object) -> "Unary":
        # subclasses read the child (bounds, exactness) before Node.__init__ checks it
        if not isinstance(child, Node):
            raise ParameterError(f"{cls.kind}: the operand must be an sdfgl node, got {type(child).__name__} "
                                 f"{child!r}"[:200])
        return super().__new__(cls, child, *args, **kwargs)

    def __init__(self, child: Node, **params: object) -> None:
        super().__init__((child,), **params)
        self.child = child

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
