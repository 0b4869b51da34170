"""The Emitter: collects the straight-line GLSL of one map()-like function.

map() is straight-line code (loops only inside the library functions of nodes that need
them) with every parameter baked in as a float32 constant (or a uniform, for sg.param);
every line remembers which node wrote it, so a compile error can name it.
"""
from __future__ import annotations

import contextlib
from typing import TYPE_CHECKING, Any, Iterator, Sequence

import numpy as np

from .. import shaderlib
from ..errors import ParameterError
from ..params import Live, Param
from .source import comment_text, glsl_float
from .tables import DataPool, OriginOffsets, reduce_modulo

if TYPE_CHECKING:  # pragma: no cover
    from ..nodes.base import Node

DEFAULT_COLOR = (0.7, 0.68, 0.64)
# what a surface is made of where no node says otherwise (today's look: sdfgl.look)
DEFAULT_SURFACE = {"albedo": DEFAULT_COLOR, "specular": 0.25, "shininess": 48.0, "metallic": 0.0,
                   "emission": (0.0, 0.0, 0.0)}
# colour-mode passes: the vec3 each carries beside the distance
CHANNELS = {"albedo": ("albedo",), "surface": ("specular", "shininess", "metallic"), "emission": ("emission",)}
FLOAT32_MAX = float(np.finfo(np.float32).max)
# a node with this many constant rows (polygon vertices) keeps them as data, in a texture
DATA_MIN = 64


class Emitter:
    """Collects the straight-line GLSL of one map()-like function.

    Point variables may carry a pending float64 offset (from translations and from the
    shader origin); it is folded in float64 and written out once, when a node needs
    the point itself. This keeps scenes far from the origin exact to float32 rounding.
    """

    def __init__(self, mode: str, parent: "Emitter | None" = None, params: list[Param] | None = None,
                 channel: str = "albedo") -> None:
        if mode not in ("dist", "color") or channel not in CHANNELS:
            raise ValueError(mode)
        self.mode = mode
        # in colour mode, which vec3 of the surface travels with the distance (see CHANNELS)
        self.channel = parent.channel if parent else channel
        self.lines: list[tuple[str, str]] = []  # (code, owner path)
        # library files and helper functions are shared with the emitter of map() itself
        self.libs: list[str] = parent.libs if parent else []
        self.functions: dict[tuple, tuple[str, list[tuple[str, str]]]] = parent.functions if parent else {}
        self.params: list[Param] = parent.params if parent else (params if params is not None else [])
        self._path: list[str] = list(parent._path) if parent else []
        # the materials (dicts of the fields they set) of the nodes around the current one
        self._colors: list[dict[str, Any]] = list(parent._colors) if parent else [DEFAULT_SURFACE]
        self._count = 0
        # point name -> (base point, pending float64 offset, live offsets still to subtract,
        # the rotation the offset is turned by: point = base + frame @ (offset - lives), None: I)
        self._shifts: dict[str, tuple[str, np.ndarray, tuple[Live, ...], np.ndarray | None]] = {}
        self._turned_origins: set[str] = set()  # turned copies of origin_base (see rotate())
        self._materialized: dict[Any, str] = {}
        # the point that carries a moving shader origin (the root of map() when the origin is a
        # uniform, see OriginOffsets); None: the origin, if any, is folded into constants
        self.origin_base: str | None = None
        self.origins: OriginOffsets | None = parent.origins if parent else None
        self.shared_keys: set = parent.shared_keys if parent else set()
        self.helpers: dict[str, str] = parent.helpers if parent else {}
        self.detail = parent.detail if parent else False  # emitting the normals-only field
        # id of the grid or mesh whose free way along the ray map() leaves (see analysis.ray_free)
        self.ray_free: int | None = parent.ray_free if parent else None
        self.grids: dict[int, tuple[str, Any, tuple[float, float, float]]] = parent.grids if parent else {}
        self.use_grids = parent.use_grids if parent else True
        self.data: DataPool = parent.data if parent else DataPool()  # tables the shader reads
        self.data_min = parent.data_min if parent else DATA_MIN  # constants in one node above which they are data
        self._defining: set = set(parent._defining) if parent else set()
        self.results: dict = {}  # (node id, point, colour) -> (node, result variable), in this function
        self.highlight: Node | None = parent.highlight if parent else None  # the "select" debug view's subtree
        # id of a node -> GLSL of the value above which its caller needs no distance (Emitter.guarded):
        # this function's own, so a shared subtree's function never reads another's variables
        self.distance_cap: dict[int, str] = {}

    # -- bookkeeping -------------------------------------------------------------------
    def enter(self, node: Node) -> None:
        self._path.append(node.label())

    def leave(self) -> None:
        self._path.pop()

    @property
    def owner(self) -> str:
        return " > ".join(self._path) if self._path else "(scene)"

    def require(self, *libs: str) -> None:
        """Include ``shaders/lib/<name>.glsl`` (and what it requires) once."""
        for name in libs:
            if name in self.libs:
                continue
            self.require(*shaderlib.requires(name))
            self.libs.append(name)

    def assign(self, glsl_type: str, expr: str) -> str:
        """Emit ``type vN = expr;`` and return ``vN``."""
        name = f"v{self._count}"
        self._count += 1
        self.lines.append((f"    {glsl_type} {name} = {expr};", self.owner))
        return name

    def function(self, node: Node) -> str:
        """Name of a GLSL function computing ``node`` at its argument (emitted once per subtree)."""
        key = (node.key, self.mode, self.channel, self.current(), self.detail)
        if key not in self.functions:
            sub = Emitter(self.mode, parent=self)
            sub._defining.add(node.key)
            result = node.emit(sub, "p")
            prefix = "n" if self.detail else ("d" if self.mode == "dist" else self.channel[0])
            name = f"{prefix}{len(self.functions)}_{node.kind}"
            rtype = "float" if self.mode == "dist" else "vec4"
            lines = [(f"{rtype} {name}(vec3 p) {{", self.owner), *sub.lines,
                     (f"    return {result};", self.owner), ("}", self.owner)]
            self.functions[key] = (name, lines)
        return self.functions[key][0]

    def guarded(self, node: Node, p: str, idle_above: str | None) -> str:
        """``node``'s result at ``p``, its code written inside a branch taken only where the
        lower bound of its field from its box is not above ``idle_above`` (GLSL: a hard union's
        result so far, or its negation in a difference; None: no test). Where the branch is
        not taken the result is that bound, which the caller's min or max then discards (it
        keeps its other operand, by a strict comparison in colour mode as well). Written so
        only where :func:`sdfgl.compiler.guards.worth_guarding` says the test pays (and not
        in the select view, which must see the node everywhere)."""
        from .guards import cap_target, guard_box, worth_guarding
        if idle_above is None or self.highlight is not None or not worth_guarding(node):
            return node.emit(self, p)
        centre, half, inv_g = guard_box(node)
        self.require("op_box_gap")
        gap = self.assign("float", f"opBoxGap({self.point(self.shift(p, -centre))}, {self.vec(half)}) * "
                                   f"{self.num(inv_g)}")
        out = self.assign("float", gap) if self.mode == "dist" else self.assign("vec4", f"vec4(0.0, 0.0, 0.0, {gap})")
        self.lines.append((f"    if (!({gap} > {idle_above})) {{  // near enough to matter", self.owner))
        start = len(self.lines)
        known = (dict(self._materialized), dict(self.results))  # what the branch makes stays in it
        found = cap_target(node)
        if found is not None:  # it may stop searching just above that value too (above: no ties in colour mode)
            target, offset = found
            self.distance_cap[id(target)] = f"(max({idle_above}, 0.0) * 1.001 + {self.num(offset + 1e-20)})"
        result = node.emit(self, p)
        if found is not None:
            del self.distance_cap[id(found[0])]
        self.lines.append((f"    {out} = {result};", self.owner))
        self.lines[start:] = [("    " + code, owner) for code, owner in self.lines[start:]]
        self.lines.append(("    }", self.owner))
        self._materialized, self.results = known
        return out

    def table(self, values: np.ndarray) -> int:
        """The index of the first texel of ``values`` (rows of up to 4 floats, one texel
        each) in the shader's one data texture; GLSL reads texel i with dataFetch(i)."""
        rows = np.asarray(values, dtype=np.float32).reshape(len(values), -1)
        texels = np.zeros((len(rows), 4), dtype=np.float32)
        texels[:, :rows.shape[1]] = rows
        self.require("data_table")
        return self.data.add(texels)

    @staticmethod
    def comment(text: object) -> str:
        """``text`` made safe to write in a ``//`` comment (see :func:`comment_text`)."""
        return comment_text(text)

    def helper(self, name: str, code: str | list[tuple[str, str]]) -> None:
        """Include a generated helper function (e.g. a polygon of N vertices) once; ``code``
        may be (line, owner) pairs, so compile errors name the owner of each line."""
        self.helpers.setdefault(name, code)

    def grid_name(self, grid: Any) -> str:
        """The GLSL prefix of a union kept as data (its textures are the ShaderSource's data)."""
        if id(grid) not in self.grids:
            self.grids[id(grid)] = (f"g{len(self.grids)}", grid, self.field("albedo"))
        return self.grids[id(grid)][0]

    def narrow_free_way(self, grid: Any, distance: str) -> None:
        """Beside ``grid``'s union, a child written as code bounds the free way along the ray
        by its distance (shaders/templates/grid_ray.glsl; map() of the ray-free grid only)."""
        if self.leaves_free_way(grid):
            self.lines.append((f"    gFree = min(gFree, {distance});", self.owner))

    def leaves_free_way(self, holder: Any) -> bool:
        """Whether this pass's map() leaves ``holder``'s free way along the ray (a grid's or a
        mesh's: see analysis.ray_free): the distance pass of the image, not the normals' field."""
        return id(holder) == self.ray_free and self.mode == "dist" and not self.detail

    def ask_free_way(self, holder: Any, way: str) -> None:
        """In map() of the image, set gFree to ``way`` (GLSL) when the march asks for it
        (gFreeAsk: shaders/lib/ray_free.glsl), where ``holder`` leaves the free way."""
        if self.leaves_free_way(holder):
            self.require("ray_free")
            self.lines.append((f"    if (gFreeAsk) gFree = {way};", self.owner))

    def mark(self, node: Node, result: str) -> str:
        """Record the distance of the highlighted subtree in the global gSel (map() only); return ``result``."""
        if node is self.highlight and self.mode == "dist" and not self.detail:
            self.lines.append((f"    gSel = min(gSel, abs({result}));", self.owner))
        return result

    def grid_union(self, grid: Any, p: str) -> str:
        """The union kept as data at point ``p``: its distance, or (vec3, distance) in colour
        mode (packed primitives carry colours only: other channels are the current ones)."""
        from .data.grid_code import emit  # the data strategies build on this module
        self._mark_member(grid.children, p)
        return emit(grid, self, p)

    def _mark_member(self, members: list[Node], p: str) -> None:
        """The select view inside a union kept as data: the member that is (or holds) the highlighted
        node is written out as code too, so that its distance reaches gSel (members are data)."""
        if self.highlight is None or self.mode != "dist" or self.detail:
            return
        for member in members:
            stack = [member]
            while stack:
                n = stack.pop()
                if n is self.highlight:
                    member.emit(self, p)
                    return
                stack.extend(n.children)

    # -- literals ----------------------------------------------------------------------
    def num(self, x: float | Live) -> str:
        """A float: a constant, or the expression of a live value over its uniform."""
        if isinstance(x, Live):
            return x.glsl(self)
        if not abs(float(x)) <= FLOAT32_MAX:
            raise ParameterError(f"{self.owner}: value {x!r} does not fit in a float32 shader constant")
        return glsl_float(x)

    def vec(self, v: Sequence[float] | Live) -> str:
        """A vecN: constants, or a live value (a live scalar is broadcast to vec3)."""
        if isinstance(v, Live):
            return f"vec3({v.glsl(self)})" if v.dims == 1 else v.glsl(self)
        vals = list(v)
        return f"vec{len(vals)}({', '.join(self.num(x) for x in vals)})"

    def literal(self, x: object) -> str:
        """A constant inside a live expression: a float or a 3-vector."""
        return self.vec(np.asarray(x, dtype=np.float64)) if np.ndim(x) else self.num(float(x))  # type: ignore[arg-type]

    def uniform_for(self, p: Param) -> str:
        """The uniform that carries live parameter ``p`` (declared by generate())."""
        if p not in self.params:
            self.params.append(p)
        return f"uP{self.params.index(p)}"

    # -- points with a pending float64 offset ------------------------------------------
    def shift(self, p: str, delta: np.ndarray) -> str:
        """A point name standing for ``p + delta``; nothing is emitted yet."""
        base, off, lives, frame = self._shifts.get(p, (p, np.zeros(3), (), None))
        step = np.asarray(delta, dtype=np.float64)
        name = f"{base}@{len(self._shifts)}"
        self._shifts[name] = (base, off + (step if frame is None else frame.T @ step), lives, frame)
        return name

    def shift_live(self, p: str, offset: Live) -> str | None:
        """A point name standing for ``p - offset`` (a live offset) when ``p`` carries the
        moving shader origin: origin, constant and live parts are then summed in float64 on
        the CPU each frame into one uniform. None elsewhere (the caller writes the sum)."""
        base, off, lives, frame = self._shifts.get(p, (p, np.zeros(3), (), None))
        if self.origins is None or not self._carries_origin(base) or frame is not None:
            return None
        name = f"{base}@{len(self._shifts)}"
        self._shifts[name] = (base, off, (*lives, offset), frame)
        return name

    def rotate(self, p: str, m: np.ndarray) -> str | None:
        """A point name standing for ``m^T p`` (a rotation, world = m @ local) when ``p`` has a
        pending offset: the small base point is turned in GLSL, the offset in float64 (it
        stays pending, so a fold or a translation below still meets it exactly). None where
        ``p`` has no pending offset or carries live ones (the caller turns the point)."""
        if p not in self._shifts or self._shifts[p][2]:
            return None
        base, off, _, frame = self._shifts[p]
        m = np.asarray(m, dtype=np.float64)
        # GLSL's mat3 constructor is column-major, so the row-major entries of m build m^T
        turned = self.assign("vec3", f"mat3({', '.join(self.num(x) for x in m.ravel())}) * {base}")
        if self._carries_origin(base):
            self._turned_origins.add(turned)
        name = f"{turned}@{len(self._shifts)}"
        self._shifts[name] = (turned, off, (), m.T if frame is None else m.T @ frame)
        return name

    def _carries_origin(self, base: str) -> bool:
        return base == self.origin_base or base in self._turned_origins

    def point(self, p: str, along: np.ndarray | None = None, period: np.ndarray | None = None) -> str:
        """A GLSL expression for point ``p``, writing out a pending offset once.

        ``along`` (a unit axis): the caller reads only dot(point, along) (a plane), so only the
        offset's component along it is added; the point stays small however far the plane's
        anchor and the origin lie apart, and so does its float32 rounding. ``period`` (per
        axis, 0 for none): the caller reads the point only modulo these periods (endless
        repetition), so the offset is reduced modulo them in float64 first: the fold then
        runs at the size of a cell, not at the distance from the world origin."""
        if p not in self._shifts:
            return p
        axis = None if along is None else np.asarray(along, dtype=np.float64)
        cells = None if period is None or not np.any(period) else np.asarray(period, dtype=np.float64)
        key = (p, None if axis is None else axis.tobytes(), None if cells is None else cells.tobytes())
        if key not in self._materialized:
            base, off, lives, frame = self._shifts[p]
            if self.origins is not None and self._carries_origin(base):
                code = self.assign("vec3", f"{base} + {self.origins.uniform(off, lives, axis, cells, frame)}")
            else:
                off = off if frame is None else frame @ off
                off = off if axis is None else (off @ axis) * axis
                off = off if cells is None else reduce_modulo(off, cells)
                code = base if not off.any() else self.assign("vec3", f"{base} + {self.vec(off)}")
            self._materialized[key] = code
        return self._materialized[key]

    # -- colour and material -----------------------------------------------------------
    @contextlib.contextmanager
    def colored(self, fields: dict[str, Any]) -> Iterator[None]:
        """Inside, the material fields in ``fields`` apply where no inner node sets them."""
        self._colors.append(fields)
        try:
            yield
        finally:
            self._colors.pop()

    def field(self, name: str) -> Any:
        """The value of material field ``name`` here (the innermost node that sets it wins)."""
        for f in reversed(self._colors):
            if name in f:
                return f[name]
        raise KeyError(name)

    def current(self) -> Any:
        """The vec3 of this pass's channel here: a colour, or (specular, shininess, metallic)."""
        names = CHANNELS[self.channel]
        return self.field(names[0]) if len(names) == 1 else tuple(self.field(n) for n in names)

    def with_color(self, d: str) -> str:
        """In colour mode pair distance ``d`` with the current channel value; else return ``d``."""
        if self.mode == "dist":
            return d
        return self.assign("vec4", f"vec4({self.vec(self.current())}, {d})")

    def scale_distance(self, r: str, factor: str) -> str:
        """Multiply a result's distance by ``factor`` (keeping its colour)."""
        if self.mode == "dist":
            return self.assign("float", f"{r} * {factor}")
        return self.assign("vec4", f"vec4({r}.rgb, {r}.w * {factor})")
