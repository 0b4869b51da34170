"""Big unions as data: instances of a few types, listed per type in the cells of a uniform grid.

A hard union of at least GRID_MIN children is not written out as code when its children
are instances: any bounded node (a primitive or a small subtree, up to SUBTREE_MAX
distinct nodes) under rigid moves, a uniform scale and a colour. Children are grouped
into *types*:

- a primitive class whose parameters the shader can read from data (sphere radius, box
  size, capsule ends, ...): one type for all its instances, parameters per instance;
- any other node (a subtree, or a primitive whose code needs fixed values): one type per
  distinct structure, one GLSL function shared by all its instances (so 1000 moved copies
  of a subtree are one function and 1000 transforms).

Each grid cell lists, per type, the instances whose bounds come within MARGIN (half a
cell) of it, with the instance's data (inverse transform, parameters, colour) inline in the list,
so the shader runs one tight loop per type over what is near a point: no type branches
run masked, and a list entry costs one to four texel fetches (shaders/grid_union.glsl
finds the cell). The field is min(listed, cap), where every unlisted instance is at least
``cap`` away; the float64 twin computes min(all children, cap) with the same cap.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import SdfglError
from ..params import Live
from . import bvh, grid_record, ray_entry
from .base import IMPLICIT, Node, Primitive
from .traverse import postorder

if TYPE_CHECKING:  # pragma: no cover
    from ..codegen import Emitter

GRID_MIN = 32       # fewer children than this are written out as code (see the benchmark)
SUBTREE_MAX = 64    # distinct nodes of a subtree that may become an instance type
LIST_WIDTH = 1024   # texels per row of the cell and list textures (a power of two)
MAX_DIMS = 64       # cells per axis at most
MAX_TYPES = 16      # more distinct types than this stay code
# chosen on the growth scene (1024 spheres; see the closing note of issue 12)
CELL_FACTOR = 0.5  # cell edge / (volume per instance)^(1/3)
MARGIN = 0.5       # in cells: how near an instance's bounds must come to a cell to be listed


def unwrap(node: Node) -> tuple[Node, np.ndarray, np.ndarray, float, tuple[float, float, float] | None] | None:
    """Peel rigid transforms, uniform scales and colours off ``node``: (inner node, t, R, s,
    colour) with world = t + s * R @ local; None if a live parameter is in the way."""
    from .transforms import Material, Rotate, Scale, Translate
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
_ZERO.flags.writeable = False
_EYE.flags.writeable = False


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
    from .primitives import Sphere
    peeled = unwrap(node)
    if peeled is None or not isinstance(peeled[0], Sphere) or peeled[0].live_params():
        return None
    sph, t, r, s, _ = peeled
    return Packed(0, s, t + s * (r @ np.asarray(sph.c, dtype=float)), np.array([float(sph.r), 0.0, 0.0]))


# -- parameters read from data --------------------------------------------------------
class _SlotRead(Exception):
    """A node's code used a parameter's value in Python: that parameter cannot be data."""


class Slot(Live):
    """A parameter of a primitive type read from an instance's texels in the shader."""

    def __init__(self, expr: str, dims: int) -> None:
        super().__init__("slot")
        self.expr, self._dims = expr, dims

    @property
    def value(self) -> Any:
        raise _SlotRead()

    @property
    def dims(self) -> int:
        return self._dims

    def roots(self) -> list:
        return []

    def glsl(self, em: "Emitter") -> str:
        return self.expr


def _slot_values(prim: Primitive) -> list[tuple[str, np.ndarray]]:
    """The numeric attributes of a primitive that its code may read from data."""
    out = []
    for name, val in prim.__dict__.items():
        if name in ("params", "children") or name.startswith("_"):
            continue
        if name == "c" and type(prim).__name__ == "Sphere":
            continue  # folded into the translation (see build)
        if isinstance(val, (float, np.floating)) and not isinstance(val, bool):
            out.append((name, np.array([float(val)])))
        elif isinstance(val, np.ndarray) and val.dtype.kind == "f" and val.ndim == 1 and 2 <= val.size <= 4:
            out.append((name, val.astype(np.float64)))
    return out


def _component(base: int, i: int) -> str:
    """GLSL for float ``i`` of a record read into texels d0, d1, ... starting at float ``base``."""
    k = base + i
    return f"d{k // 4}.{'xyzw'[k % 4]}"


def _slot_expr(base: int, n: int) -> str:
    parts = [_component(base, i) for i in range(n)]
    return parts[0] if n == 1 else f"vec{n}({', '.join(parts)})"


# -- types and instances --------------------------------------------------------------
class _Type:
    """Instances that share one piece of code."""

    def __init__(self, key: tuple, inner: Node, slots: list[str] | None, color_in_code: tuple | None) -> None:
        self.key, self.inner = key, inner
        self.slots = slots                  # attribute names read from data (primitive types)
        self.color_in_code = color_in_code  # the subtree's default colour when it has colours of its own
        self.members: list[int] = []        # indices into Grid.children
        self.affine = False                 # rotated or scaled members (a move layout of grid_record)
        self.scaled = False

    def layout(self, slot_sizes: list[int], move: str) -> tuple[int, int, int, int]:
        """(float offset of the scale, of the slots, of the colour, texels per record)."""
        n = grid_record.floats(move)
        scale_at = n
        n += 1 if self.scaled else 0
        slots_at = n
        n += sum(slot_sizes)
        color_at = n
        n += 0 if self.color_in_code is not None else 3
        return scale_at, slots_at, color_at, -(-n // 4)


def _has_color(node: Node) -> bool:
    from .transforms import Material
    return any(isinstance(n, Material) for n in postorder(node))


def _small(node: Node) -> bool:
    count = 0
    for _ in postorder(node):
        count += 1
        if count > SUBTREE_MAX:
            return False
    return True


class Grid:
    """The instances of one union, their types and the cell lists over their bounds."""

    def __init__(self, children: list[Node], peeled: list[tuple], types: list[_Type], single_cell: bool = False,
                 boxes: np.ndarray | None = None) -> None:
        """``single_cell`` makes one cell list every instance: a plain data-driven loop
        (the uber-shader the benchmark compares against); ``boxes`` (n, 2, 3) are the
        children's bounds when the caller has them."""
        self.children, self.types = children, types
        self.peeled = peeled  # (inner, t, R, s, colour) per child
        if boxes is None:
            boxes = np.array([_bounds_of(c) for c in children])
        los, his = boxes[:, 0], boxes[:, 1]
        lo, hi = los.min(axis=0), his.max(axis=0)
        extent = np.maximum(hi - lo, 1e-9)
        cell = CELL_FACTOR * float(np.prod(extent) / len(children)) ** (1 / 3)
        cell = float(extent.max()) * 1.001 if single_cell else max(cell, float(extent.max()) / MAX_DIMS)
        self.dims = np.minimum(np.ceil(extent / cell).astype(int), MAX_DIMS)
        self.cell, self.lo = cell, lo
        self.margin = MARGIN * cell
        self.centre = lo + 0.5 * self.dims * cell  # data and code are relative to it (float32 precision)
        self._los, self._his = los, his
        self._ball_at, self._ball_r = _balls(peeled, boxes) if peeled and not single_cell else (None, None)
        self._textures: dict[tuple, dict[str, np.ndarray]] = {}

    # -- the twin's cap (the same number the shader computes) --------------------------
    def cap(self, p: np.ndarray) -> np.ndarray:
        """The distance below which every unlisted instance lies, at (..., 3) points."""
        rel = (p - self.lo) / self.cell
        cell = np.clip(np.floor(rel), 0, self.dims - 1)
        cell_lo = self.lo + cell * self.cell
        # outside the clamped cell only outside the grid box, by the distance to the box
        out = np.sqrt(np.sum(np.maximum(np.maximum(cell_lo - p, p - (cell_lo + self.cell)), 0.0) ** 2, axis=-1))
        return np.maximum(self.margin - out, out)

    def field(self, p: np.ndarray) -> np.ndarray:
        """The float64 twin of the shader's loop: min over the instances listed in each
        point's cell, and the cap (for exact instances, min(all, cap))."""
        flat = p.reshape(-1, 3)
        cell = np.clip(np.floor((flat - self.lo) / self.cell), 0, self.dims - 1).astype(np.int64)
        d = self.cap(flat)
        a, b = self._ranges()
        for i, c in enumerate(self.children):
            m = np.all((cell >= a[i]) & (cell <= b[i]), axis=1)
            if m.any() and self._ball_at is not None:
                at = cell[m]
                m[m] = self._near_ball(at[:, 0], at[:, 1], at[:, 2], np.full(len(at), i))
            if m.any():
                d[m] = np.minimum(d[m], c._distance(flat[m]))
        return d.reshape(p.shape[:-1])

    def _ranges(self) -> tuple[np.ndarray, np.ndarray]:
        """Per instance, the first and last cell (per axis) whose list holds it."""
        a = np.clip(np.floor((self._los - self.margin - self.lo) / self.cell).astype(np.int64), 0, self.dims - 1)
        b = np.clip(np.floor((self._his + self.margin - self.lo) / self.cell).astype(np.int64), 0, self.dims - 1)
        return a, b

    # -- data ------------------------------------------------------------------------
    def _entries(self) -> tuple[np.ndarray, np.ndarray]:
        """(cell index, child index) of every list entry, sorted by cell."""
        a, b = self._ranges()
        n = b - a + 1
        counts = n.prod(axis=1)
        child = np.repeat(np.arange(len(self.children)), counts)
        start = np.concatenate([[0], np.cumsum(counts)[:-1]])
        local = np.arange(counts.sum()) - np.repeat(start, counts)
        nx, ny = np.repeat(n[:, 0], counts), np.repeat(n[:, 1], counts)
        x = np.repeat(a[:, 0], counts) + local % nx
        y = np.repeat(a[:, 1], counts) + (local // nx) % ny
        z = np.repeat(a[:, 2], counts) + local // (nx * ny)
        if self._ball_at is not None:
            keep = self._near_ball(x, y, z, child)
            x, y, z, child = x[keep], y[keep], z[keep], child[keep]
        cells = (z * self.dims[1] + y) * self.dims[0] + x
        order = np.argsort(cells, kind="stable")
        return cells[order], child[order]

    def _near_ball(self, x: np.ndarray, y: np.ndarray, z: np.ndarray, child: np.ndarray) -> np.ndarray:
        """Whether each instance ``child`` (n,) lies within the margin of cell (x, y, z) by its
        ball and by the Euclidean gap between its box and the cell (see _balls): the per-axis
        cell ranges alone list a sphere in cells near its box's corners (22 % of the growth
        scene's entries), and a box by its corners too (5 % of 1000 robot copies'). The
        cap's promise holds: an unlisted instance is at least the margin from the cell, by
        its box or by its ball."""
        ball2 = np.zeros(len(child))
        box2 = np.zeros(len(child))
        for axis, index in enumerate((x, y, z)):
            lo = self.lo[axis] + index * self.cell
            at = self._ball_at[:, axis][child]
            g = np.maximum(np.maximum(lo - at, at - (lo + self.cell)), 0.0)
            ball2 += g * g
            g = np.maximum(np.maximum(lo - self._his[child, axis], self._los[child, axis] - (lo + self.cell)), 0.0)
            box2 += g * g
        reach = self._ball_r[child] + self.margin
        return (ball2 <= reach * reach) & (box2 <= self.margin * self.margin)

    def records(self, t: _Type, default_color: tuple[float, float, float]) -> np.ndarray:
        """float32 (members, texels, 4): each member's move (grid_record), parameters, colour."""
        sizes = [len(v) for _, v in _slot_values(t.inner)] if t.slots is not None else []
        peeled = [self.peeled[i] for i in t.members]
        rot = np.array([u[2] for u in peeled])
        move = grid_record.kind(t, rot)
        scale_at, slots_at, color_at, texels = t.layout(sizes, move)
        out = np.zeros((len(t.members), texels * 4), dtype=np.float64)
        tr = np.array([u[1] for u in peeled]) - self.centre
        s = np.array([u[3] for u in peeled], dtype=np.float64)
        out[:, :grid_record.floats(move)] = grid_record.encode(move, tr, rot, s)
        if t.scaled:
            out[:, scale_at] = s
        if t.slots is not None:
            pos = slots_at
            for name, size in zip(t.slots, sizes):
                out[:, pos:pos + size] = np.array([np.ravel(u[0].__dict__[name]) for u in peeled], dtype=np.float64)
                pos += size
        if t.color_in_code is None:
            out[:, color_at:color_at + 3] = [u[4] if u[4] is not None else default_color for u in peeled]
        return out.astype(np.float32).reshape(len(t.members), texels, 4)

    def textures(self, default_color: tuple[float, float, float]) -> dict[str, np.ndarray]:
        """float32 RGBA arrays (rows, LIST_WIDTH, 4): per cell and type (first texel, count)
        pairs, and the list records."""
        key = tuple(default_color)
        if key in self._textures:
            return self._textures[key]
        cells, child = self._entries()
        type_of = np.zeros(len(self.children), dtype=np.int64)
        local = np.zeros(len(self.children), dtype=np.int64)
        for ti, t in enumerate(self.types):
            type_of[t.members] = ti
            local[t.members] = np.arange(len(t.members))
        etype = type_of[child]
        order = np.lexsort((etype, cells))  # by cell, then type
        cells, child, etype = cells[order], child[order], etype[order]
        recs = [self.records(t, default_color) for t in self.types]
        size = np.array([r.shape[1] for r in recs])
        width = size[etype]
        offset = np.concatenate([[0], np.cumsum(width)[:-1]])
        total = int(width.sum())
        lst = np.zeros((max(1, -(-total // LIST_WIDTH)) * LIST_WIDTH, 4), dtype=np.float32)
        if total >= 2 ** 24:
            raise SdfglError(f"union: {total} list texels exceed the float32 index limit of 2^24; "
                             "use fewer or larger instances")
        for ti, r in enumerate(recs):
            sel = np.nonzero(etype == ti)[0]
            rows = offset[sel][:, None] + np.arange(r.shape[1])[None, :]
            lst[rows.ravel()] = r[local[child[sel]]].reshape(-1, 4)
        ntypes = len(self.types)
        per_cell = -(-ntypes // 2)
        ncell = int(np.prod(self.dims))
        table = np.zeros((ncell, per_cell * 2, 2), dtype=np.float64)
        flat = cells * ntypes + etype
        counts = np.bincount(flat, minlength=ncell * ntypes)
        firsts = np.zeros(ncell * ntypes, dtype=np.int64)
        firsts[flat[::-1]] = offset[::-1]  # the first entry of each (cell, type) group
        table[:, :ntypes, 0] = firsts.reshape(ncell, ntypes)
        table[:, :ntypes, 1] = counts.reshape(ncell, ntypes)
        cell_tex = np.zeros((-(-ncell * per_cell // LIST_WIDTH) * LIST_WIDTH, 4), dtype=np.float32)
        cell_tex[:ncell * per_cell] = table.reshape(ncell * per_cell, 4)
        out = {"Cells": cell_tex.reshape(-1, LIST_WIDTH, 4), "List": lst.reshape(-1, LIST_WIDTH, 4)}
        self._textures[key] = out
        return out

    # -- code ------------------------------------------------------------------------
    def emit(self, em: "Emitter", p: str) -> str:
        """Call this grid's union function at point ``p``: (rgb, d) in colour mode, else d
        (through the cells, or with setting grid="bvh" the hierarchy of nodes/bvh.py)."""
        gid = em.grid_name(self)
        channel = "Color" if em.channel == "albedo" else em.channel.capitalize()
        fn = f"{gid}{channel if em.mode == 'color' else ('Detail' if em.detail else 'Dist')}"
        key = ("grid", gid, em.mode, em.channel, em.detail)
        if key not in em.functions:
            color = em.mode == "color"
            owner = f"union of {len(self.children)} instances ({gid})"
            loops: list[tuple[str, str]] = []
            entries: list[tuple[str, str]] = []  # after the grid's helpers: they call its ray tests
            for ti, t in enumerate(self.types):
                loops += self._loop(em, t, ti, color, owner, entries)
            make = bvh.of(self).emit_function if em.use_grids == "bvh" else self._cell_function
            em.functions[key] = (fn, make(em, fn, color, loops, owner))
            for name, code in entries:
                em.helper(name, code)
        pt = em.point(em.shift(p, -self.centre))
        return em.assign("vec4" if em.mode == "color" else "float", f"{fn}({pt})")

    def _cell_function(self, em: "Emitter", fn: str, color: bool, loops: list[tuple[str, str]],
                       owner: str) -> list[tuple[str, str]]:
        """The union function ``fn``: find p's cell, then run the per-type ``loops`` over its lists."""
        from .. import shaderlib
        gid = em.grid_name(self)
        tex = self.textures(em.grids[id(self)][2])
        em.require("data_table")
        cells, lists = em.data.add(tex["Cells"]), em.data.add(tex["List"])
        head = shaderlib.read("templates/grid_union").replace("GRIDID", gid)
        defs = (f"#define {gid}_LO vec3({', '.join(em.num(x) for x in self.lo - self.centre)})\n"
                f"#define {gid}_CELL {em.num(self.cell)}\n"
                f"#define {gid}_MARGIN {em.num(self.margin)}\n"
                f"#define {gid}_DIMS ivec3({', '.join(str(int(x)) for x in self.dims)})\n"
                f"#define {gid}_PER_CELL {-(-len(self.types) // 2)}\n"
                f"#define {gid}_CELLS {cells}\n#define {gid}_LIST {lists}")
        ray = self._ray_free(em, color)
        if ray:
            head += "\n" + shaderlib.read("templates/grid_ray").replace("GRIDID", gid)
        em.helper(f"{gid}_grid", defs + "\n" + head)
        rtype = "vec4" if color else "float"
        best = "vec4(0.0, 0.0, 0.0, cap)" if color else "cap"
        fetch = [(f"    vec4 s{j} = dataFetch({gid}_CELLS + cell + {j});", owner) for j in range(-(-len(self.types) // 2))]
        free = [(f"    float free = {gid}Exit(p, gRayInv, cellLo);", owner),
                ("    bool inGrid = free >= 0.0;  // outside the grid box gFree is the field's value", owner)] if ray else []
        done = [("    gFree = inGrid ? max(free, best) : best;", owner)] if ray else []
        return [(f"{rtype} {fn}(vec3 p) {{", owner),
                ("    float cap;", owner),
                ("    vec3 cellLo;", owner),
                (f"    int cell = {gid}Cell(p, cap, cellLo) * {gid}_PER_CELL;", owner),
                (f"    {rtype} best = {best};", owner),
                *free, *fetch, *loops, *done,
                ("    return best;", owner), ("}", owner)]

    def _ray_free(self, em: "Emitter", color: bool) -> bool:
        """Whether this grid's distance function also leaves the free way along the ray
        (shaders/grid_ray.glsl): for the marchers' primary rays where the scene is this union."""
        return not color and not em.detail and em.ray_free_grid == id(self)

    def _free_way(self, em: "Emitter", t: _Type, move: str, d: str) -> str:
        """GLSL for how far along the ray from q (the point in a listed instance's frame, whose
        distance is ``d``) nothing of that instance lies: an unscaled sphere's entry (q is
        relative to its centre, its radius |q| - d), a subtree's entry into its bounding box
        (translated: the ray's direction is the world's in its frame; turned: the direction
        turned into its frame, ``_boxed``; the nearest such instance is refined by its parts
        after the loop: _refined_entry), any other instance its distance (a primitive's
        bounds depend on its data)."""
        from .primitives import Sphere
        gid = em.grid_name(self)
        if move == "translate" and type(t.inner) is Sphere:
            return f"{gid}RayBall(q, gRayDir, length(q) - ({d}))"
        if self._boxed(t, move):
            lo, hi = _bounds_of(t.inner)
            return f"{gid}RayBox(q, {_ray(move)[1]}, {em.vec(lo)}, {em.vec(hi)})"
        return d

    @staticmethod
    def _boxed(t: _Type, move: str) -> bool:
        """Whether type ``t``'s instances bound the free way by their box: subtrees and
        primitives of fixed size, translated or turned (a quaternion record) and unscaled."""
        from .primitives import Sphere
        return t.slots is None and type(t.inner) is not Sphere and not t.scaled and move in ("translate", "quat")

    def _loop(self, em: "Emitter", t: _Type, ti: int, color: bool, owner: str,
              entries: list[tuple[str, str]]) -> list[tuple[str, str]]:
        """The loop over the (cell, type ti) list: fetch, transform, evaluate, keep the min
        (and the free way: a refined entry's function goes to ``entries``, as (name, code))."""
        from ..codegen import Emitter
        sizes = [len(v) for _, v in _slot_values(t.inner)] if t.slots is not None else []
        move = grid_record.kind(t, np.array([self.peeled[i][2] for i in t.members]))
        scale_at, slots_at, color_at, texels = t.layout(sizes, move)
        need = texels if color else -(-(color_at if t.color_in_code is None else texels * 4) // 4)
        need = max(need, 1)
        gid = em.grid_name(self)
        span = f"s{ti // 2}"
        lines = [f"    {{  // type {ti}: {t.inner.label()[:60]} x {len(t.members)}"]
        first, count = (f"{span}.x", f"{span}.y") if ti % 2 == 0 else (f"{span}.z", f"{span}.w")
        lines.append(f"    int first = int({first});")
        lines.append(f"    int count = int({count});")
        refined = self._refined_entry(em, t, ti, move, color, entries)
        if refined:
            lines.append("    float enterNear = 3.0e38;  // the smallest box entry, and its instance's point")
            lines.append("    vec3 qNear = vec3(0.0);")
            if move == "quat":  # ... and the ray in its frame
                lines.append("    vec3 dirNear = gRayDir;")
                lines.append("    vec3 invNear = gRayInv;")
        lines.append("    for (int k = 0; k < count; k++) {")
        lines.append(f"        int e = {gid}_LIST + first + k * {texels};")
        for j in range(need):
            lines.append(f"        vec4 d{j} = dataFetch(e + {j});")
        lines.append(grid_record.glsl(move, _component(scale_at, 0) if t.scaled else None))
        out = [(line, owner) for line in lines]
        # the type's field at q
        if t.slots is not None:
            template = _template(t.inner, t.slots, slots_at)
            sub = Emitter("dist", parent=em)
            sub._count = 0
            d = template._emit(sub, "q")
            out += [("    " + code, owner) for code, _ in sub.lines]
            result_color = None
        elif color and t.color_in_code is not None:
            own = em.grids[id(self)][2] if t.color_in_code == ("default",) else t.color_in_code
            with em.colored({"albedo": own}):
                name = em.function(t.inner)
            out.append((f"        vec4 r = {name}(q);", owner))
            d, result_color = "r.w", "r.rgb"
        else:
            mode = em.mode
            em.mode = "dist"
            try:
                name = em.function(t.inner)
            finally:
                em.mode = mode
            out.append((f"        float dd = {name}(q);", owner))
            d, result_color = "dd", None
        if t.scaled:
            d = f"({d}) * {_component(scale_at, 0)}"
        if color:
            rgb = result_color or (_slot_expr(color_at, 3) if em.channel == "albedo" else em.vec(em.current()))
            out.append((f"        float dist = {d};", owner))
            out.append((f"        if (dist < best.w) best = vec4({rgb}, dist);", owner))
        else:
            out.append((f"        best = min(best, {d});", owner))
            turned = self._ray_free(em, color) and self._boxed(t, move) and move == "quat"
            if turned:  # the ray's direction in the instance's frame (the record's quaternion), and 1 / it
                out += [(line, owner) for line in (
                    "        vec3 dirQ = gRayDir + 2.0 * cross(d0.xyz, cross(d0.xyz, gRayDir) + d0.w * gRayDir);",
                    "        vec3 invQ = 1.0 / (dirQ + vec3(equal(dirQ, vec3(0.0))) * 1e-30);")]
            if refined:
                out += [(line, owner) for line in (
                    f"        float enter = {self._free_way(em, t, move, d)};",
                    "        free = min(free, enter < enterNear ? enterNear : enter);  // every entry but the smallest",
                    "        bool nearer = enter < enterNear;",
                    "        qNear = nearer ? q : qNear;",
                    *(["        dirNear = nearer ? dirQ : dirNear;", "        invNear = nearer ? invQ : invNear;"]
                      if turned else []),
                    "        enterNear = min(enterNear, enter);")]
            elif self._ray_free(em, color):
                out.append((f"        free = min(free, {self._free_way(em, t, move, d)});", owner))
        out.append(("    }", owner))
        if refined:
            ray = "invNear, dirNear" if move == "quat" else "gRayInv, gRayDir"
            out.append((f"    free = min(free, max(enterNear, {refined}(qNear, {ray})));  // the nearest by its parts", owner))
        out.append(("    }", owner))
        return out

    def _refined_entry(self, em: "Emitter", t: _Type, ti: int, move: str, color: bool,
                       entries: list[tuple[str, str]]) -> str | None:
        """The name of the GLSL function for where the ray enters type ``t`` by its parts
        (nodes/ray_entry.py; its code goes to ``entries``), where the free way may refine its
        nearest instance that way: a subtree entered by its box (``_boxed``) that holds parts
        with room between them; else None. Only the instance with the smallest box entry is
        refined, once a call after the list's loop: every entry test costs about what a call
        saves. The function takes the point, 1 / the direction and the direction, all in
        the instance's frame."""
        if not self._ray_free(em, color) or not self._boxed(t, move):
            return None
        found = ray_entry.pieces(t.inner)
        if found is None:
            return None
        gid = em.grid_name(self)
        name = f"{gid}Enter{ti}"
        entries.append((name, f"float {name}(vec3 q, vec3 inv, vec3 dir) {{\n"
                              f"    return {ray_entry.entry_glsl(em, gid, found, 'q', 'inv', 'dir')};\n}}"))
        return name


def _ray(move: str) -> tuple[str, str]:
    """The GLSL of the ray's direction and 1 / it in a listed instance's frame (see _loop)."""
    return ("dirQ", "invQ") if move == "quat" else ("gRayDir", "gRayInv")


def _template(prim: Node, slots: list[str], at: int) -> Node:
    """A copy of ``prim`` whose slot attributes are read from the record's texels."""
    tpl = type(prim).__new__(type(prim))
    tpl.__dict__.update(prim.__dict__)
    pos = at
    for name, val in _slot_values(prim):
        if name in slots:
            tpl.__dict__[name] = Slot(_slot_expr(pos, len(val)), len(val))
            pos += len(val)
    return tpl


def _balls(peeled: list[tuple], boxes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A ball holding each instance (centres (n, 3), radii (n,)): a sphere itself (the ball
    its world box ``boxes`` (n, 2, 3) is drawn round), any other node the ball round its
    own box, moved with the instance (a rotated instance's ball is tighter than its world box)."""
    from .primitives import Sphere
    centre = (boxes[:, 0] + boxes[:, 1]) / 2
    radius = (boxes[:, 1, 0] - boxes[:, 0, 0]) / 2
    for i, (inner, t, r, s, _) in enumerate(peeled):
        if type(inner) is not Sphere:
            lo, hi = _bounds_of(inner)
            centre[i] = t + s * (r @ ((lo + hi) / 2))
            radius[i] = s * float(np.linalg.norm(hi - lo)) / 2
    return centre, radius


def _bounds_of(node: Node) -> np.ndarray:
    """node.bounds without the defensive copies: (lo, hi) rows, read only."""
    from .base import box_of
    return box_of(node)


def _centred(sph: Node) -> Node:
    """A copy of a sphere with its centre at the origin."""
    out = type(sph).__new__(type(sph))
    out.__dict__.update(sph.__dict__)
    out.c = np.zeros(3)
    out.params = {**sph.params, "center": out.c}
    return out


def _primitive_slots(prim: Primitive) -> list[str] | None:
    """The attributes of ``prim`` the shader can read from data, or None if its code needs
    a fixed value (then each distinct primitive is its own type)."""
    from ..codegen import Emitter
    names = [name for name, _ in _slot_values(prim)]
    try:
        _template(prim, names, 0)._emit(Emitter("dist"), "q")
    except _SlotRead:
        return None
    except Exception:  # noqa: BLE001 - any other failure: keep the values as code
        return None
    return names


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


class _ClassInfo:
    """What build() learns once per primitive class: its data slots and whether it fits."""

    def __init__(self, prim: Primitive) -> None:
        self.slots = _primitive_slots(prim)
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


def build(children: list[Node], min_children: int | None = None, single_cell: bool = False) -> Grid | None:
    """A grid for a union's children if at least ``min_children`` (default GRID_MIN) of
    them are instances (those that are not stay code beside it).

    One pass over the children, no per-node property calls beyond the cached bounds and
    live-parameter lists: each child is peeled into (inner node, translation, rotation,
    scale, colour) and sorted into a type; Grid packs the gathered values with numpy."""
    least = GRID_MIN if min_children is None else min_children
    if len(children) < least:
        return None
    from .base import box_of
    from .primitives import Sphere
    from .transforms import Material, Rotate, Scale, Translate
    classes = (Translate, Rotate, Scale, Material)
    boxes = np.array([box_of(c) for c in children])  # (n, 2, 3)
    finite = np.isfinite(boxes).all(axis=(1, 2))
    types: dict[tuple, _Type] = {}
    info: dict[type, _ClassInfo] = {}
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
                ci = info[cls] = _ClassInfo(inner)
            if not ci.ok:
                continue
            slots = ci.slots
            if slots is not None and not ci.same_attributes(inner) and [n for n, _ in _slot_values(inner)] != slots:
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
            t = types[key] = _Type(key, inner, slots, color_in_code)
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
    return Grid(kept, peeled, list(types.values()), single_cell, boxes[rows])


__all__ = ["GRID_MIN", "Grid", "build", "pack", "unwrap"]
