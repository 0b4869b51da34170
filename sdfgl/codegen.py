"""Scene graph -> GLSL fragment shader.

map() is straight-line code (loops only inside the library functions of nodes that need
them) with every parameter baked in as a float32 constant (or a uniform, for sg.param); only
the library functions the scene uses are included; settings become #defines, and the
code of a feature that is off (shadows, AO, ground, extra outputs) is not in the source.
Every generated line remembers which node wrote it, so a compile error can name it.
"""
from __future__ import annotations

import contextlib
import hashlib
import dataclasses
from dataclasses import dataclass
from typing import Any, Iterator, Sequence

import numpy as np

from . import shaderlib
from .errors import ParameterError
from .gl.dialect import Dialect, dialect as _dialect
from .nodes.base import IMPLICIT, Node, grid_min_as
from .nodes.traverse import FACTS, fact, run_deep
from .params import Live, Param
from .look.lights import DEFAULT_LIGHTS
from .look.shading import background_code, shade_function, shadow_code, shadow_kinds
from .settings import DEFAULT_OMEGA, DISTANCE_METHODS, Settings

DEFAULT_COLOR = (0.7, 0.68, 0.64)
# what a surface is made of where no node says otherwise (today's look: sdfgl.look)
DEFAULT_SURFACE = {"albedo": DEFAULT_COLOR, "specular": 0.25, "shininess": 48.0, "metallic": 0.0,
                   "emission": (0.0, 0.0, 0.0)}
# colour-mode passes: the vec3 each carries beside the distance
CHANNELS = {"albedo": ("albedo",), "surface": ("specular", "shininess", "metallic"), "emission": ("emission",)}
# evaluate targets: the material channel function each runs at given points (with map())
EVALUATE_CHANNELS = {"evaluate_color": "mapColor", "evaluate_surface": "mapSurface", "evaluate_emission": "mapEmission"}
FLOAT32_MAX = float(np.finfo(np.float32).max)
# Stand-in for an infinite bound inside GLSL: finite in float32, so no inf*0 arises.
GLSL_FAR = 1e30
# a node with this many constant rows (polygon vertices) keeps them as data, in a texture
DATA_MIN = 64
BUDGET_DATA_MIN = 8  # the same, when map() is over the code budget
BUDGET_GRID_MIN = 8  # over the budget, unions of this many instances become data
MAX_CODE_SIZE = 3_000_000  # characters of scene code refused even as data (the driver would take many minutes)
DATA_WIDTH = 1024  # texels per row of a data table (a power of two)
# methods that share a loop file, told apart by a #define
MARCH_FILES = {"sphere": "relaxed", "enhanced": "relaxed", "forward_newton": "newton"}


def glsl_float(x: float) -> str:
    """A GLSL float literal that round-trips the float32 value of ``x``."""
    f = float(np.float32(x))
    s = f"{f:.9g}"
    if not any(ch in s for ch in ".e"):
        s += ".0"
    return s


class DataPool:
    """The float32 texels of every table a shader reads (grid lists, polygon vertices), in
    one texture: one sampler however many tables (drivers allow only a few samplers)."""

    def __init__(self) -> None:
        self.chunks: list[np.ndarray] = []
        self.size = 0
        self._index: dict[bytes, int] = {}

    def add(self, texels: np.ndarray) -> int:
        """Append (n, 4) float32 texels (once per content); return the first one's index."""
        arr = np.ascontiguousarray(texels, dtype=np.float32).reshape(-1, 4)
        key = hashlib.sha1(arr.tobytes()).digest() + len(arr).to_bytes(8, "little")
        if key not in self._index:
            self._index[key] = self.size
            self.chunks.append(arr)
            self.size += len(arr)
        return self._index[key]

    def texture(self) -> tuple[tuple[str, np.ndarray], ...]:
        """("uData", (rows, DATA_WIDTH, 4)) or nothing."""
        if not self.chunks:
            return ()
        if self.size >= 2 ** 24:
            raise ParameterError(f"scene: its data tables hold {self.size} texels, over the limit of 2^24 "
                                 f"(float32 indices); use fewer or smaller instances")
        flat = np.zeros((-(-self.size // DATA_WIDTH) * DATA_WIDTH, 4), dtype=np.float32)
        flat[:self.size] = np.concatenate(self.chunks)
        return (("uData", flat.reshape(-1, DATA_WIDTH, 4)),)


OriginEntry = tuple  # (float64 offset, live offsets to subtract, unit axis to project on or None)


class OriginOffsets:
    """The uniforms uOrg0, uOrg1, ... of a shader whose origin moves (unbounded scenes and
    scenes with live parameters, see :func:`moving_origin`): each is ``origin + offset -
    sum(live offsets)`` for a point met in map() (the root itself, a translation, a grid's
    centre), summed in float64 on the CPU at every draw. The float32 point a node sees is
    then one rounding away from exact wherever the origin is, and moving the camera or a
    parameter (which moves the origin) changes uniforms, never the source."""

    def __init__(self) -> None:
        self.entries: list[OriginEntry] = []
        self._index: dict[tuple, int] = {}

    def uniform(self, offset: np.ndarray, lives: tuple[Live, ...], along: np.ndarray | None = None) -> str:
        """The uniform's name for this offset (one per distinct offset); ``along``: only its
        component along this unit axis is kept (see Emitter.point)."""
        key = (np.asarray(offset, dtype=np.float64).tobytes(), tuple(id(x) for x in lives),
               None if along is None else along.tobytes())
        if key not in self._index:
            self._index[key] = len(self.entries)
            self.entries.append((np.array(offset, dtype=np.float64), lives, along))
        return f"uOrg{self._index[key]}"



def origin_values(entries: Sequence[OriginEntry], origin: np.ndarray) -> dict[str, tuple]:
    """The uOrgN uniform values for the shader origin ``origin`` (float64), at the current
    parameter values."""
    out = {}
    for i, (off, lives, along) in enumerate(entries):
        v = np.asarray(origin, dtype=np.float64) + off
        for live in lives:
            v = v - np.broadcast_to(np.asarray(live.value, dtype=np.float64), (3,))
        if along is not None:
            v = (v @ along) * along
        out[f"uOrg{i}"] = tuple(float(x) for x in v)
    return out


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
        # point name -> (base point, pending float64 offset, live offsets still to subtract)
        self._shifts: dict[str, tuple[str, np.ndarray, tuple[Live, ...]]] = {}
        self._materialized: dict[Any, str] = {}
        # the point that carries a moving shader origin (the root of map() when the origin is a
        # uniform, see OriginOffsets); None: the origin, if any, is folded into constants
        self.origin_base: str | None = None
        self.origins: OriginOffsets | None = parent.origins if parent else None
        self.shared_keys: set = parent.shared_keys if parent else set()
        self.helpers: dict[str, str] = parent.helpers if parent else {}
        self.detail = parent.detail if parent else False  # emitting the normals-only field
        self.ray_free_grid: int | None = parent.ray_free_grid if parent else None  # see ray_free_grid()
        self.grids: dict[int, tuple[str, Any, tuple[float, float, float]]] = parent.grids if parent else {}
        self.use_grids = parent.use_grids if parent else True
        self.data: DataPool = parent.data if parent else DataPool()  # tables the shader reads
        self.data_min = parent.data_min if parent else DATA_MIN  # constants in one node above which they are data
        self._defining: set = set(parent._defining) if parent else set()
        self.results: dict = {}  # (node id, point, colour) -> (node, result variable), in this function
        self.highlight: Node | None = parent.highlight if parent else None  # the "select" debug view's subtree

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

    def table(self, values: np.ndarray) -> int:
        """The index of the first texel of ``values`` (rows of up to 4 floats, one texel
        each) in the shader's one data texture; GLSL reads texel i with dataFetch(i)."""
        rows = np.asarray(values, dtype=np.float32).reshape(len(values), -1)
        texels = np.zeros((len(rows), 4), dtype=np.float32)
        texels[:, :rows.shape[1]] = rows
        self.require("data_table")
        return self.data.add(texels)

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
        by its distance (shaders/grid_ray.glsl; map() of the ray-free grid only)."""
        if id(grid) == self.ray_free_grid and self.mode == "dist" and not self.detail:
            self.lines.append((f"    gFree = min(gFree, {distance});", self.owner))

    def mark(self, node: Node, result: str) -> str:
        """Record the distance of the highlighted subtree in the global gSel (map() only); return ``result``."""
        if node is self.highlight and self.mode == "dist" and not self.detail:
            self.lines.append((f"    gSel = min(gSel, abs({result}));", self.owner))
        return result

    def grid_union(self, grid: Any, p: str) -> str:
        """The union kept as data at point ``p``: its distance, or (vec3, distance) in colour
        mode (packed primitives carry colours only: other channels are the current ones)."""
        self._mark_member(grid.children, p)
        return grid.emit(self, p)

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
        base, off, lives = self._shifts.get(p, (p, np.zeros(3), ()))
        name = f"{base}@{len(self._shifts)}"
        self._shifts[name] = (base, off + np.asarray(delta, dtype=np.float64), lives)
        return name

    def shift_live(self, p: str, offset: Live) -> str | None:
        """A point name standing for ``p - offset`` (a live offset) when ``p`` carries the
        moving shader origin: origin, constant and live parts are then summed in float64 on
        the CPU each frame into one uniform. None elsewhere (the caller writes the sum)."""
        base, off, lives = self._shifts.get(p, (p, np.zeros(3), ()))
        if self.origins is None or base != self.origin_base:
            return None
        name = f"{base}@{len(self._shifts)}"
        self._shifts[name] = (base, off, (*lives, offset))
        return name

    def point(self, p: str, along: np.ndarray | None = None) -> str:
        """A GLSL expression for point ``p``, writing out a pending offset once.

        ``along`` (a unit axis): the caller reads only dot(point, along) (a plane), so only the
        offset's component along it is added; the point stays small however far the plane's
        anchor and the origin lie apart, and so does its float32 rounding."""
        if p not in self._shifts:
            return p
        key = p if along is None else (p, np.asarray(along, dtype=np.float64).tobytes())
        if key not in self._materialized:
            base, off, lives = self._shifts[p]
            axis = None if along is None else np.asarray(along, dtype=np.float64)
            if self.origins is not None and base == self.origin_base:
                code = self.assign("vec3", f"{base} + {self.origins.uniform(off, lives, axis)}")
            else:
                off = off if axis is None else (off @ axis) * axis
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


@dataclass(frozen=True)
class ShaderSource:
    """A generated fragment shader plus the owner (node path or file) of every line.

    ``params`` are the live parameters behind uniforms uP0, uP1, ...; ``live_bounds`` says
    the scene box is a uniform (it moves with the parameters)."""

    text: str
    owners: tuple[str, ...]
    params: tuple[Param, ...] = ()
    live_bounds: bool = False
    data: tuple[tuple[str, np.ndarray], ...] = ()  # sampler name -> float32 RGBA texels (rows, width, 4)
    code_size: int = 0  # characters of scene code (map(), mapColor(), their functions and helpers)
    grid_min: int = 0   # the fewest instances a union kept as data had to have
    choice: str = "code"  # how the scene was written: "code", or "data (...)" when over the budget
    data_unions: int = 0  # unions kept as data (grids) in this shader
    # a moving origin (see moving_origin): the offsets behind uOrg0, uOrg1, ... (origin_values
    # turns them into uniform values); the source then does not depend on the origin
    origin_offsets: tuple[OriginEntry, ...] | None = None

    def owner_of(self, line: int) -> str:
        """Who wrote 1-based source line ``line``."""
        return self.owners[line - 1] if 1 <= line <= len(self.owners) else "(unknown line)"


class _Builder:
    def __init__(self) -> None:
        self.lines: list[str] = []
        self.owners: list[str] = []

    def add(self, text: str, owner: str) -> None:
        for line in text.rstrip("\n").split("\n"):
            self.lines.append(line)
            self.owners.append(owner)

    def add_file(self, name: str) -> None:
        self.add(shaderlib.read(name), f"shaders/{name}.glsl")

    def build(self, params: Sequence[Param] = (), live_bounds: bool = False,
              data: Sequence[tuple[str, np.ndarray]] = ()) -> ShaderSource:
        return ShaderSource("\n".join(self.lines) + "\n", tuple(self.owners), tuple(params), live_bounds,
                            tuple(data))

    def size_since(self, start: int) -> int:
        """Characters added since line ``start``."""
        return sum(len(x) + 1 for x in self.lines[start:])


def _helpers(b: _Builder, em: Emitter, done: set[str]) -> None:
    for name, lines in em.functions.values():
        if name not in done:
            done.add(name)
            for code, owner in lines:
                b.add(code, owner)


def _function(b: _Builder, signature: str, em: Emitter, result: str, ret: str) -> None:
    b.add(signature + " {", "(codegen)")
    for code, owner in em.lines:
        b.add(code, owner)
    b.add(f"    return {ret.format(result)};\n}}", "(codegen)")


def scene_frame(scene: Node) -> tuple[np.ndarray, np.ndarray, float]:
    """Finite stand-ins for the scene bounds (inf -> GLSL_FAR) and a length scale."""
    lo, hi = scene.bounds
    finite = np.isfinite(lo) & np.isfinite(hi)
    ext = (hi - lo)[finite]
    scale = float(ext.max()) if ext.size and ext.max() > 0 else 1.0
    return np.where(np.isfinite(lo), lo, -GLSL_FAR), np.where(np.isfinite(hi), hi, GLSL_FAR), scale


def unbounded(scene: Node) -> bool:
    """True where the scene box is infinite on some side: only then does max_dist limit a ray."""
    lo, hi = scene.bounds
    return not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)))


def analytic_shape(scene: Node) -> tuple[str, np.ndarray] | None:
    """("sphere", (centre, radius)) or ("plane", (normal, offset)) in world space when the
    scene is one sphere or plane under rigid transforms, uniform scales and colours."""
    from .nodes.grid import pack, unwrap
    from .nodes.primitives import Plane
    q = pack(scene)
    if q is not None and q.type == 0:
        return "sphere", np.array([*q.t, q.scale * q.size[0]])
    peeled = unwrap(scene)
    if peeled is None or not isinstance(peeled[0], Plane):
        return None
    plane, t, r, s, _ = peeled
    if any(isinstance(v, Live) for v in plane.params.values()):
        return None
    n = r @ plane._unit_normal()
    point = t + s * (r @ np.asarray(plane.o, dtype=float))
    return "plane", np.array([*n, float(n @ point)])


def analytic_relative(kind: str, v: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """An analytic shape's vec4 relative to the shader origin."""
    return v - np.array([*origin, 0.0]) if kind == "sphere" else np.array([*v[:3], v[3] - v[:3] @ origin])


def max_steps_of(settings: Settings, scale: float, lo: np.ndarray, hi: np.ndarray) -> int:
    """The loop limit the shader gets: max_steps, or enough fixed steps for "reference"."""
    if settings.method != "reference":
        return settings.max_steps
    ext = hi - lo
    diag = float(np.linalg.norm(np.where(ext >= GLSL_FAR, settings.max_dist, ext)))
    return max(settings.max_steps, int(diag / ref_step(settings, scale)) + 2)


def ref_step(settings: Settings, scale: float) -> float:
    """The fixed step of the "reference" method."""
    return settings.ref_step if settings.ref_step is not None else scale / 512.0


BOUNDS_PAD = 1e-3  # the ray clip box grows by this share of the scene size


def _defines(scene: Node, settings: Settings, origin: np.ndarray, live: bool, projection: str,
             moving: bool = False) -> list[str]:
    lo, hi, scale = scene_frame(scene)
    pad = BOUNDS_PAD * scale
    bounds = (["#define BOUNDS_LO uBoundsLo", "#define BOUNDS_HI uBoundsHi"] if live else [
        f"#define BOUNDS_LO vec3({', '.join(glsl_float(x) for x in lo - pad - origin)})",
        f"#define BOUNDS_HI vec3({', '.join(glsl_float(x) for x in hi + pad - origin)})"])
    d = [
        f"#define AA {settings.aa}",
        f"#define MAX_STEPS {max_steps_of(settings, scale, lo, hi)}",
        f"#define HIT_{settings.hit.upper()}",
        f"#define HIT_SCALE {glsl_float(settings.hit_scale)}",
        f"#define MAX_DIST {glsl_float(settings.max_dist if unbounded(scene) else GLSL_FAR)}",
        "#define SCENE_SCALE uSceneScale" if live else f"#define SCENE_SCALE {glsl_float(scale)}",
        *bounds,
    ]
    if settings.method in DEFAULT_OMEGA:
        omega = settings.omega if settings.omega is not None else DEFAULT_OMEGA[settings.method]
        d.append(f"#define OMEGA {glsl_float(omega)}")
    if settings.method == "reference":
        d.append(f"#define REF_STEP {glsl_float(ref_step(settings, scale))}")
    if settings.method in ("enhanced", "forward_newton"):
        d.append(f"#define {settings.method.upper()}")
    if settings.method in ("newton", "forward_newton"):
        d.append(f"#define NEWTON_CAP {glsl_float(settings.newton_cap if settings.newton_cap else 1e30)}")
    shape = analytic_shape(scene) if settings.analytic else None
    if shape is not None:
        kind, v = shape
        v = analytic_relative(kind, v, origin)
        d.append(f"#define ANALYTIC_{kind.upper()} " +
                 ("uAnalytic" if moving else f"vec4({', '.join(glsl_float(x) for x in v)})"))
    if settings.shadows:
        d += ["#define SHADOWS", f"#define SHADOWS_{settings.shadows.upper()}"]
    if settings.ao:
        d.append("#define AO")
    if scene.exactness == IMPLICIT:
        d.append("#define IMPLICIT_FIELD")
    if settings.ground:
        ground_y = lo[1] if lo[1] > -GLSL_FAR else 0.0
        d += ["#define GROUND", "#define GROUND_Y uGroundY" if live else f"#define GROUND_Y {glsl_float(ground_y - origin[1])}"]
    if settings.debug:
        d += ["#define DEBUG_VIEW", f"#define DEBUG_{settings.debug.upper()}"]
    d += [f"#define DEFAULT_SPECULAR {glsl_float(DEFAULT_SURFACE['specular'])}",
          f"#define DEFAULT_SHININESS {glsl_float(DEFAULT_SURFACE['shininess'])}"]
    if projection == "orthographic":
        d.append("#define ORTHOGRAPHIC")
    if settings.alpha:
        d.append("#define ALPHA")
    if settings.fog is not None:
        d.append(f"#define FOG_DISTANCE {glsl_float(settings.fog)}")
    aux = [o for o in settings.outputs if o != "color"]
    if aux:
        d.append("#define AUX_OUTPUTS")
    for loc, name in enumerate(aux, start=1):
        d += [f"#define OUT_{name.upper()}", f"#define LOC_{name.upper()} {loc}"]
    return d


def ray_free_grid(scene: Node, settings: Settings) -> tuple[Any, np.ndarray] | None:
    """The grid whose free way along the ray (shaders/grid_ray.glsl) the marcher may step,
    and the rotation R (world = R @ local) from the grid's frame to the world's: the scene's
    own union kept as data under translations, rotations and materials only (they keep
    distances; the marcher turns its direction by R^T), any child beside the instances
    bounding the way by its distance, marched by march_relaxed.glsl (sphere tracing and its
    relaxed variants: the marcher that reads gFree). None elsewhere."""
    from .nodes.booleans import Union
    from .nodes.transforms import Material, Rotate, Translate
    if MARCH_FILES.get(settings.method, settings.method) != "relaxed" or settings.grid is not True \
            or not settings.free_way:
        return None
    node, turn = scene, np.eye(3)
    while isinstance(node, (Translate, Rotate, Material)) and not node.live_params():
        if isinstance(node, Rotate):
            turn = turn @ node.m
        node = node.children[0]
    grid = node.grid if isinstance(node, Union) else None
    # children beside the grid (a floor) bound the way by their distance (Union._emit): the
    # scene is a distance bound wherever a distance marcher runs (an implicit one is refused)
    return None if grid is None else (grid, turn)


def _free_way_defines(free_way: tuple[Any, np.ndarray] | None) -> list[str]:
    """The defines of the free way along the ray: RAY_FREE, and RAY_FREE_TURN (R^T, which
    turns the ray's direction into the grid's frame) where the union is rotated."""
    if free_way is None:
        return []
    turn = free_way[1]
    if np.array_equal(turn, np.eye(3)):
        return ["#define RAY_FREE"]
    # GLSL's mat3 constructor is column-major: R's row-major entries build R^T
    return ["#define RAY_FREE", f"#define RAY_FREE_TURN mat3({', '.join(glsl_float(float(x)) for x in turn.ravel())})"]


def shared_subtrees(scene: Node, use_grids: bool = True) -> set:
    """Keys of composite subtrees that occur more than once (each becomes one GLSL function)."""
    from .nodes.booleans import Union
    counts: dict = {}
    stack = [scene]
    while stack:
        n = stack.pop()
        if n.children and n is not scene:  # the scene itself occurs once
            counts[n.key] = counts.get(n.key, 0) + 1
            if counts[n.key] > 1:
                continue  # its inside is counted once; the function holds it
        grid = n.grid if use_grids and isinstance(n, Union) else None
        if grid is not None:  # instances are data: only their types' code and the other children
            inside = {id(c) for c in grid.children}
            stack.extend(c for c in n.children if id(c) not in inside)
            stack.extend(t.inner for t in grid.types if t.slots is None)
            continue
        stack.extend(n.children)
    return {k for k, c in counts.items() if c > 1}


def material_channels(scene: Node) -> list[str]:
    """The colour passes the scene needs besides albedo: "surface" where some node sets
    specular, shininess or metallic, "emission" where some node sets an emission."""
    names = fact(scene, "_fields")
    return [ch for ch in ("surface", "emission") if any(f in names for f in CHANNELS[ch])]


def _vec3_literal(v: Sequence[float]) -> str:
    return f"vec3({', '.join(glsl_float(float(x)) for x in v)})"


def _material_fields(n: Node) -> frozenset:
    """The material fields some Material at or under ``n`` sets (children's cached values);
    a Material (and only a Material) has a ``fields`` dict."""
    fields = n.__dict__.get("fields")
    own = frozenset(fields) if fields else _NONE
    kids = [f for c in n.children if (f := c.__dict__["_fields"])]
    return own.union(*kids) if kids else own


_NONE: frozenset = frozenset()
FACTS["_fields"] = _material_fields


def _surface_function(channels: Sequence[str]) -> str:
    """GLSL of ``Surface sceneSurface(vec3 p)``: the material at a hit."""
    spec = "sf.x, sf.y, sf.z" if "surface" in channels else "DEFAULT_SPECULAR, DEFAULT_SHININESS, 0.0"
    emis = "mapEmission(p)" if "emission" in channels else "vec3(0.0)"
    head = "    vec3 sf = mapSurface(p);\n" if "surface" in channels else ""
    return f"Surface sceneSurface(vec3 p) {{\n{head}    return Surface(mapColor(p), {spec}, {emis});\n}}"


def _emit_map(scene: Node, mode: str, origin: np.ndarray, params: list[Param], shared: set,
              grids: dict, use_grids: bool, helpers: dict, data: DataPool, data_min: int,
              origins: OriginOffsets | None, detail: bool = False, channel: str = "albedo",
              highlight: Node | None = None, ray_free_id: int | None = None) -> tuple[Emitter, str]:
    em = Emitter(mode, params=params, channel=channel)
    em.ray_free_grid = ray_free_id
    em.origins = origins
    em.data = data
    em.data_min = data_min
    em.highlight = highlight
    em.helpers = helpers
    em.detail = detail
    em.shared_keys = shared
    em.grids = grids
    em.use_grids = use_grids
    if origins is not None:  # the origin is a uniform: every point from the root gets one
        em.origin_base = "p"
        p = em.shift("p", np.zeros(3))
    else:
        p = em.shift("p", origin) if origin.any() else "p"
    return em, scene.emit(em, p)


def moving_origin(scene: Node, target: str = "render", dialect: str = "desktop") -> bool:
    """Whether the shader origin of ``scene`` is a uniform (uOrgN offsets, bounds as
    uniforms): rendering on the desktop an unbounded scene (the origin follows the eye) or
    one with live parameters (it follows the box's centre). Elsewhere the origin is folded
    into constants (a bounded scene is anchored at its fixed centre)."""
    if target != "render" or dialect != "desktop":
        return False
    lo, hi = scene.bounds
    return not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))) or bool(scene.live_params())


def generate(scene: Node, settings: Settings, origin: Sequence[float] = (0.0, 0.0, 0.0),
             target: str = "render", dialect: str = "desktop", projection: str = "perspective",
             highlight: Node | None = None) -> ShaderSource:
    """Build the fragment shader for ``scene``.

    ``origin`` (float64) is the world point that the shader's coordinates are relative
    to; ``target`` is ``"render"`` (the image), ``"evaluate"`` (map() at given points),
    ``"evaluate_color"`` / ``"evaluate_surface"`` / ``"evaluate_emission"`` (a material
    channel and map() at given points: see EVALUATE_CHANNELS; mesh colours and path-traced
    materials use them), or one of the mesh exporter's samplers (sdfgl.mesh: same map(), other main()s):
    ``"mesh_grid"`` (a lattice of blocks), ``"mesh_gradient"`` (value and gradient at points),
    ``"mesh_project"`` (points moved onto the surface by Newton steps);
    ``dialect`` is ``"desktop"`` (GLSL 3.30) or ``"webgl2"`` (GLSL ES 3.00): the same
    code under another header (see :mod:`sdfgl.gl.dialect`); ``projection`` is the
    camera's ("perspective" or "orthographic": it shapes the rays). ``highlight`` is the
    subtree the "select" debug view tints.
    """
    lang = _dialect(dialect)
    if not isinstance(scene, Node):
        raise ParameterError(f"scene must be an sdfgl node, got {type(scene).__name__} {scene!r}")
    moving = moving_origin(scene, target, dialect)
    return run_deep(scene, lambda: _generate(scene, settings, origin, target, lang, projection, highlight, moving))


def _generate(scene: Node, settings: Settings, origin: Sequence[float], target: str, lang: Dialect,
              projection: str, highlight: Node | None = None, moving: bool = False) -> ShaderSource:
    """generate(), within the code-size budget."""
    settings = settings.resolved(scene.exactness)
    if scene.exactness == IMPLICIT and target == "render" and settings.method in DISTANCE_METHODS:
        raise ParameterError(
            f"{scene.label()} is an implicit field, not a distance bound: method {settings.method!r} would step "
            f"through surfaces. Use method='auto' (the default), 'newton', 'forward_newton' or 'reference'.")
    if (settings.debug == "select") != (highlight is not None and target == "render"):
        raise ParameterError("debug view 'select' needs a highlighted subtree (generate(..., highlight=node)), "
                             "and a highlight needs debug='select'")
    org = np.zeros(3) if moving else np.asarray(origin, dtype=np.float64)
    from .nodes.grid import GRID_MIN
    if settings.grid_min is not None:
        with grid_min_as(settings.grid_min):
            src = _generate_once(scene, settings, org, target, lang, projection, highlight=highlight,
                                 moving=moving)
        scene.__dict__["_data_min"] = settings.grid_min  # the twin of this scene follows its last compile
        return _checked(dataclasses.replace(src, grid_min=settings.grid_min))
    src = dataclasses.replace(_generate_once(scene, settings, org, target, lang, projection,
                                             highlight=highlight, moving=moving), grid_min=GRID_MIN)
    scene.__dict__.pop("_data_min", None)
    if src.code_size <= settings.code_budget or not settings.grid:
        return _checked(src)
    # over the budget: every hard union of BUDGET_GRID_MIN or more instances becomes data,
    # and every node with more than a few constant rows keeps them in a texture
    with grid_min_as(BUDGET_GRID_MIN):
        small = _generate_once(scene, settings, org, target, lang, projection, data_min=BUDGET_DATA_MIN,
                               highlight=highlight, moving=moving)
    if small.code_size >= src.code_size:  # nothing to gain: the scene stays code
        return _checked(src)
    scene.__dict__["_data_min"] = BUDGET_GRID_MIN
    return _checked(dataclasses.replace(
        small, grid_min=BUDGET_GRID_MIN,
        choice=f"data (scene code of {src.code_size} characters was over the code budget of "
               f"{settings.code_budget}; as data {small.code_size})"))


def _checked(src: ShaderSource) -> ShaderSource:
    if src.code_size > MAX_CODE_SIZE:
        raise ParameterError(f"scene: its generated code has {src.code_size} characters, over the limit of "
                             f"{MAX_CODE_SIZE} that a GL driver compiles in reasonable time (e.g. a chain of "
                             f"operations nested 10^5 deep with nothing to fold or keep as data); build big scenes "
                             f"as unions of instances, or flatten the chain")
    return src


def _generate_once(scene: Node, settings: Settings, org: np.ndarray, target: str, lang: Dialect,
                   projection: str, data_min: int = DATA_MIN, highlight: Node | None = None,
                   moving: bool = False) -> ShaderSource:
    params: list[Param] = []
    origins = OriginOffsets() if moving else None
    shared = shared_subtrees(scene, settings.grid)
    grids: dict = {}
    helpers: dict = {}
    tex = DataPool()
    ems = (org, params, shared, grids, settings.grid, helpers, tex, data_min, origins)
    free_way = ray_free_grid(scene, settings) if target == "render" else None
    dist, dist_result = _emit_map(scene, "dist", *ems, highlight=highlight if target == "render" else None,
                                  ray_free_id=None if free_way is None else id(free_way[0]))
    # a scene without any material node has one colour: mapColor() is that constant, not
    # another copy of the scene's code (which the driver would compile and llvmpipe JIT)
    one_color = not fact(scene, "_fields") and highlight is None
    color, color_result = (_emit_map(scene, "color", *ems)
                           if (target == "render" or target in EVALUATE_CHANNELS) and not one_color else (None, ""))
    detail, detail_result = (_emit_map(scene, "dist", *ems, True)
                             if target == "render" and scene.has_detail else (None, ""))
    channels = (material_channels(scene) if target == "render" else
                [ch for ch in material_channels(scene) if EVALUATE_CHANNELS.get(target) == f"map{ch.capitalize()}"])
    passes = {ch: _emit_map(scene, "color", *ems, channel=ch) for ch in channels}
    libs = list(dict.fromkeys(dist.libs + (color.libs if color else []) + (detail.libs if detail else [])
                              + [lib for em, _ in passes.values() for lib in em.libs]))
    live = bool(params) or moving  # the box (and the ground) move with the parameters or the origin
    rig = settings.lights if settings.lights is not None else DEFAULT_LIGHTS
    lights_at = _light_positions(rig, org, origins) if target == "render" else {}

    b = _Builder()
    b.add(lang.header(), "(codegen)")
    b.add(f"// sdfgl scene: {scene.label()}  [{scene.exactness}, L={scene.lipschitz:g}]", "(codegen)")
    b.add("\n".join(_defines(scene, settings, org, live, projection, moving)
                     + _free_way_defines(free_way)), "(settings)")
    for i, prm in enumerate(params):
        b.add(f"uniform {'vec3' if prm.dims == 3 else 'float'} uP{i};  // param {prm.label}", "(live parameters)")
    if live:
        b.add("uniform vec3 uBoundsLo;\nuniform vec3 uBoundsHi;\nuniform float uGroundY;\nuniform float uSceneScale;",
              "(live parameters)")
    if origins is not None:
        b.add("\n".join(f"uniform vec3 uOrg{i};" for i in range(len(origins.entries))) +
              ("\nuniform vec4 uAnalytic;" if settings.analytic and analytic_shape(scene) is not None else ""),
              "(moving origin)")
    b.add_file("stages/common")
    for name in libs:
        b.add_file(f"lib/{lang.lib(name)}")
    start = len(b.lines)
    for name, code in helpers.items():
        if isinstance(code, str):
            b.add(code, f"(generated helper {name})")
        else:  # (line, owner) pairs: user code whose lines keep their own numbers
            for line, owner in code:
                b.add(line, owner)
    data = tex.texture()
    if highlight is not None and target == "render":
        b.add("float gSel = 1e30;  // distance of the highlighted subtree at the last map() call", "(debug select)")
    done: set[str] = set()
    _helpers(b, dist, done)
    _function(b, "float map(vec3 p)", dist, dist_result, "{}")
    if target == "evaluate":
        size = b.size_since(start)
        b.add_file("mains/evaluate_main")
        return _sized(b.build(params, live, data), size, grids, origins)
    if target in ("mesh_grid", "mesh_gradient", "mesh_project"):
        size = b.size_since(start)
        b.add_file("stages/mesh_clip")
        b.add_file(f"mains/{target}_main")
        return _sized(b.build(params, live, data), size, grids, origins)
    if color is None:
        b.add(f"vec3 mapColor(vec3 p) {{\n    return {_vec3_literal(DEFAULT_COLOR)};  // no material node: one colour\n}}",
              "(codegen: one colour)")
    else:
        _helpers(b, color, done)
        _function(b, "vec3 mapColor(vec3 p)", color, color_result, "{}.rgb")
    for ch, (em, result) in passes.items():
        _helpers(b, em, done)
        _function(b, f"vec3 map{ch.capitalize()}(vec3 p)", em, result, "{}.rgb")
    if target in EVALUATE_CHANNELS:
        b.add(f"#define EVAL_CHANNEL {EVALUATE_CHANNELS[target]}", "(codegen)")
        size = b.size_since(start)
        b.add_file("mains/evaluate_channel_main")
        return _sized(b.build(params, live, data), size, grids, origins)
    if detail is not None:
        _helpers(b, detail, done)
        _function(b, "float mapDetail(vec3 p)", detail, detail_result, "{}")
        b.add("#define DETAIL_NORMALS", "(codegen)")
    size = b.size_since(start)
    b.add_file("stages/refine")
    marched = not (settings.analytic and analytic_shape(scene) is not None)
    if marched and settings.method in ("newton", "forward_newton"):
        b.add_file("stages/ray_derivative")
    if settings.analytic and analytic_shape(scene) is not None:
        b.add_file("stages/march_analytic")
    else:
        b.add_file(f"stages/march_{MARCH_FILES.get(settings.method, settings.method)}")
    b.add_file("stages/normal")
    implicit = scene.exactness == IMPLICIT
    for code, owner in shadow_code(shadow_kinds(rig, settings.shadows, implicit)):
        b.add(code, owner)
    if settings.ao:
        b.add_file("stages/ao")
    b.add_file("stages/shade")
    b.add(_surface_function(channels), "(codegen: material)")
    b.add(*background_code(settings.background, glsl_float))
    b.add(shade_function(settings.lights, settings.ambient, settings.shadows, implicit, glsl_float,
                         metals="surface" in channels, positions=lights_at), "(look: lights)")
    if settings.ground:
        b.add_file("stages/ground")
    b.add_file("mains/render_main_head")
    if settings.debug:
        b.add_file("stages/debug")
    b.add_file("mains/render_main")
    return _sized(b.build(params, live, data), size, grids, origins)


def _light_positions(rig: Sequence[Any], org: np.ndarray, origins: OriginOffsets | None) -> dict[int, str]:
    """GLSL of each point light's position relative to the shader origin: a constant, or
    minus the uOrgN uniform of offset -position when the origin moves."""
    out = {}
    for i, lt in enumerate(rig):
        if lt.kind != "directional":
            pos = np.asarray(lt.vector, dtype=np.float64)
            out[i] = (f"(-{origins.uniform(-pos, ())})" if origins is not None
                      else f"vec3({', '.join(glsl_float(x) for x in pos - org)})")
    return out


def _sized(src: ShaderSource, size: int, grids: dict, origins: OriginOffsets | None = None) -> ShaderSource:
    """``src`` with its scene-code size, its count of unions kept as data and its origin offsets."""
    return dataclasses.replace(src, code_size=size, data_unions=len(grids),
                               origin_offsets=None if origins is None else tuple(origins.entries))


def compile(scene: Node, **settings: object) -> str:  # noqa: A001 - public API name
    """The complete GLSL fragment shader that ``render(scene, **settings)`` runs.

    Args:
        scene: the scene node.
        settings: the render settings that shape the code (see :class:`sdfgl.settings.Settings`:
            ``aa``, ``shadows``, ``ao``, ``ground``, ``method``, ``max_steps``, ``hit``,
            ``debug``, ...). A feature that is off is absent from the source.

    Returns the source text (GLSL 330 core); the same scene and settings give the same text
    byte for byte (programs are cached by it).

    Example:
        >>> src = sg.compile(sg.sphere(1) & sg.box(1.5), aa=2)
        >>> src.startswith("#version 330 core") and "float map(vec3 p)" in src
        True
    """
    return generate(scene, Settings.build(**settings)).text
