"""Which children of a big union are instances, and of which type.

A hard union of at least GRID_MIN children is not written out as code when its children
are instances: any bounded node (a primitive or a small subtree, up to SUBTREE_MAX
distinct nodes) under rigid moves, a uniform scale and a colour. Children are grouped
into *types*:

- a primitive class whose parameters the shader can read from data (sphere radius, box
  size, capsule ends, ...): one type for all its instances, parameters per instance
  (sdfgl.compiler.data.slots);
- any other node (a subtree, or a primitive whose code needs fixed values): one type per
  distinct structure, one GLSL function shared by all its instances (so 1000 moved copies
  of a subtree are one function and 1000 transforms).

:func:`build` peels every child and sorts it into a type; :class:`sdfgl.compiler.data.grid.Grid`
lists them in cells.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...nodes.base import EXACT, IMPLICIT, Node, Primitive, boxes_of
from ...nodes.primitives import Sphere
from ...nodes.transforms import Material, Rotate, Scale, Translate
from ...nodes.traverse import WIDE, collector_paused, postorder
from ...params import Live
from . import grid_record
from .blend_lists import Blend, fits
from .grid import GRID_MIN, Grid
from .slots import primitive_slots, slot_values

SUBTREE_MAX = 64    # distinct nodes of a subtree that may become an instance type
MAX_TYPES = 16      # more distinct types than this stay code


def unwrap(node: Node) -> tuple[Node, np.ndarray, np.ndarray, float, tuple[float, float, float] | None] | None:
    """Peel rigid transforms, uniform scales and colours off ``node``: (inner node, t, R, s,
    colour) with world = t + s * R @ local; None if a live parameter is in the way."""
    t, r, s, color = _ZERO, _EYE, 1.0, None  # r stays _EYE (the object) when nothing rotates
    while isinstance(node, (Material, Translate, Rotate, Scale)):
        if any(isinstance(v, Live) for v in node.params.values()):
            return None
        if isinstance(node, Translate):
            t = t + (node.offset if r is _EYE and s == 1.0 else s * (r @ node.offset))
        elif isinstance(node, Rotate):
            r = r @ node.m
        elif isinstance(node, Scale):
            s = s * float(node.s)
        elif node.surface:  # packed primitives carry a colour only, not a full material
            return None
        else:
            color = node.rgb  # the innermost colour wins, as in code
        node = node.child
    return node, t, r, s, color


_ZERO, _EYE = np.zeros(3), np.eye(3)


@dataclass
class Packed:
    """A sphere under rigid moves: world centre ``t`` and radius ``scale * size[0]`` (the
    closed-form intersection of a lone sphere uses it)."""

    type: int
    scale: float
    t: np.ndarray
    size: np.ndarray


def pack(node: Node) -> Packed | None:
    """The sphere behind a chain of rigid transforms, uniform scales and colours, or None."""
    peeled = unwrap(node)
    if peeled is None or not isinstance(peeled[0], Sphere) or peeled[0].live_params():
        return None
    sph, t, r, s, _ = peeled
    return Packed(0, s, t + s * (r @ np.asarray(sph.c, dtype=float)), np.array([float(sph.r), 0.0, 0.0]))


class InstanceType:
    """Instances that share one piece of code."""

    def __init__(self, key: tuple, inner: Node, slots: list[str] | None, color_in_code: tuple | None) -> None:
        self.key, self.inner = key, inner
        self.slots = slots                  # attribute names read from data (primitive types)
        self.color_in_code = color_in_code  # the subtree's default colour when it has colours of its own
        self.members: list[int] = []        # indices into Grid.children
        self.affine = False                 # rotated or scaled members (a move layout of grid_record)
        self.scaled = False
        # every member has the same colour (None: the grid's default), so it is written in
        # code, not in each record (half the list texels of a sphere's record)
        self.one_color = False
        self.color: tuple | None = None

    @property
    def color_in_record(self) -> bool:
        """Whether each record carries its member's colour (three floats)."""
        return self.color_in_code is None and not self.one_color

    def layout(self, slot_sizes: list[int], move: str) -> tuple[int, int, int, int]:
        """(float offset of the scale, of the slots, of the colour, texels per record)."""
        n = grid_record.floats(move)
        scale_at = n
        n += 1 if self.scaled else 0
        slots_at = n
        n += sum(slot_sizes)
        color_at = n
        n += 3 if self.color_in_record else 0
        return scale_at, slots_at, color_at, -(-n // 4)


def _has_color(node: Node) -> bool:
    return any(isinstance(n, Material) for n in postorder(node))


def _small(node: Node) -> bool:
    count = 0
    for _ in postorder(node):
        count += 1
        if count > SUBTREE_MAX:
            return False
    return True


def _centred(sph: Node) -> Node:
    """A copy of a sphere with its centre at the origin."""
    out = type(sph).__new__(type(sph))
    out.__dict__.update(sph.__dict__)
    out.c = np.zeros(3)
    out.params = {**sph.params, "center": out.c}
    return out


def _peel(node: Node, classes: tuple) -> tuple | None:
    """unwrap() for a node without live parameters (checked by the caller): the same
    (inner, t, R, s, colour), with R None when nothing rotates."""
    translate, rotate, scale, material = classes
    t, r, s, color = None, None, 1.0, None
    while True:
        cls = type(node)
        if cls is translate:
            off = node.offset if r is None and s == 1.0 else s * ((r if r is not None else _EYE) @ node.offset)
            t = off if t is None else t + off
        elif cls is rotate:
            r = node.m if r is None else r @ node.m
        elif cls is scale:
            s = s * float(node.s)
        elif isinstance(node, material):
            if node.surface:  # packed primitives carry a colour only, not a full material
                return None
            color = node.rgb  # the innermost colour wins, as in code
        else:
            return node, _ZERO if t is None else t, r, s, color
        node = node.child


class ClassInfo:
    """What build() learns once per primitive class: its data slots and whether it fits."""

    def __init__(self, prim: Primitive) -> None:
        self.slots = primitive_slots(prim)
        self.ok = not (prim.lipschitz > 1.0 or prim.exactness == IMPLICIT)
        self.public = frozenset(k for k in prim.__dict__ if not k.startswith("_"))
        self.passed: list[frozenset] = []  # attribute-name sets that passed (a few: caches vary)

    def same_attributes(self, prim: Primitive) -> bool:
        """True if ``prim`` has the public attributes of the first instance (caches, whose
        names start with "_", may differ): then it has the same data slots."""
        keys = prim.__dict__.keys()
        for ok in self.passed:
            if keys == ok:
                return True
        if frozenset(k for k in keys if not k.startswith("_")) != self.public:
            return False
        if len(self.passed) < 8:
            self.passed.append(frozenset(keys))
        return True


def build(children: list[Node], min_children: int | None = None, single_cell: bool = False,
          blend: tuple[float, str] | None = None) -> Grid | None:
    """A grid for a union's children (each once) if at least ``min_children`` (default
    GRID_MIN) of them are instances (those that are not stay code beside it: Grid.rest).

    ``blend`` (k, kind) is a smooth union's: then every child must be an instance of one
    type whose field is exact (a blend folds in the union's order, so none can stay code
    beside the grid, and the cells prune by distances: sdfgl.compiler.data.blend_lists),
    and the blend no wider than a few spacings of the children.

    One pass over the children, no per-node property calls beyond the cached bounds and
    live-parameter lists: each child is peeled into (inner node, translation, rotation,
    scale, colour) and sorted into a type; Grid packs the gathered values with numpy."""
    if len(children) >= WIDE:  # a pass over many children that makes what outlives it
        with collector_paused():
            return _build(children, min_children, single_cell, blend)
    return _build(children, min_children, single_cell, blend)


def _build(children: list[Node], min_children: int | None, single_cell: bool,
           blend: tuple[float, str] | None) -> Grid | None:
    """The work of :func:`build`."""
    least = GRID_MIN if min_children is None else min_children
    if len(children) < least:
        return None
    classes = (Translate, Rotate, Scale, Material)
    boxes = boxes_of(children)  # (n, 2, 3)
    finite = np.isfinite(boxes).all(axis=(1, 2))
    types: dict[tuple, InstanceType] = {}
    info: dict[type, ClassInfo] = {}
    subtree: dict[int, tuple[bool, tuple | None]] = {}  # id(inner) -> (usable, colour in code)
    kept: list[Node] = []
    peeled: list[tuple] = []
    rows: list[int] = []
    for i, c in enumerate(children):
        if not finite[i]:
            continue
        live = c.__dict__.get("_live_cache")
        if live is None:
            live = c.live_params()
        if live:
            continue
        u = _peel(c, classes)
        if u is None:
            continue
        inner, tr, r, sc, color = u
        if isinstance(inner, Primitive):
            cls = type(inner)
            ci = info.get(cls)
            if ci is None:
                ci = info[cls] = ClassInfo(inner)
            if not ci.ok:
                continue
            slots = ci.slots
            if slots is not None and not ci.same_attributes(inner) and [n for n, _ in slot_values(inner)] != slots:
                slots = None
            if cls is Sphere and (inner.c[0] or inner.c[1] or inner.c[2]):
                # the centre joins the translation: a sphere is one texel (centre, radius)
                tr = tr + sc * (inner.c if r is None else r @ inner.c)
                inner = _centred(inner) if slots is None or ("prim", cls) not in types else inner
            key: tuple = ("prim", cls) if slots is not None else ("node", inner.key)
            color_in_code = None
        else:
            usable, color_in_code = subtree.get(id(inner), (None, None))
            if usable is None:
                usable = not (inner.live_params() or inner.exactness == IMPLICIT or inner.lipschitz > 1.0) \
                    and _small(inner)
                color_in_code = ("has colours",) if usable and _has_color(inner) else None
                subtree[id(inner)] = (usable, color_in_code)
            if not usable:
                continue
            if color_in_code is not None:
                color_in_code = color or ("default",)
            slots = None
            key = ("node", inner.key, color_in_code)
        t = types.get(key)
        if t is None:
            if len(types) >= MAX_TYPES:
                continue
            t = types[key] = InstanceType(key, inner, slots, color_in_code)
        t.members.append(len(kept))
        if sc != 1.0:
            t.scaled = t.affine = True
        if r is not None and not t.affine and not np.array_equal(r, _EYE):
            t.affine = True
        kept.append(c)
        peeled.append((inner, tr, _EYE if r is None else r, sc, color))
        rows.append(i)
    if len(kept) < least:
        return None
    for t in types.values():
        if t.color_in_code is None:
            _share_color(t, peeled)
    if blend is not None:
        wide = Blend.of(*blend)
        if len(kept) < len(children) or len(types) != 1 or any(u[0].exactness != EXACT for u in peeled) \
                or not fits(boxes, wide):
            return None
        return Grid(kept, peeled, list(types.values()), boxes=boxes[rows], blend=wide)
    rest = np.ones(len(children), dtype=bool)
    rest[rows] = False
    return Grid(kept, peeled, list(types.values()), single_cell, boxes[rows], rest=[children[i] for i in np.flatnonzero(rest)])


def _share_color(t: InstanceType, peeled: list[tuple]) -> None:
    """Mark ``t`` one-coloured where all its members have the same colour (peeled[i][4])."""
    first = peeled[t.members[0]][4]
    for i in t.members:
        c = peeled[i][4]
        if c is not first and c != first:
            return
    t.one_color, t.color = True, first


__all__ = ["Grid", "InstanceType", "Packed", "build", "pack", "unwrap"]
