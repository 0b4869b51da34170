"""Scene graph -> GLSL fragment shader: the passes over the scene and the shader's head.

map() is straight-line code (loops only inside the library functions of nodes that need
them) with every parameter baked in as a float32 constant (or a uniform, for sg.param); only
the library functions the scene uses are included; settings become #defines, and the
code of a feature that is off (shadows, AO, ground, extra outputs) is not in the source.
What follows map() is the target's row of :data:`sdfgl.compiler.targets.TARGETS`.
"""
from __future__ import annotations

import dataclasses
import re
from typing import Sequence

import numpy as np

from ..errors import ParameterError
from ..gl.dialect import Dialect, dialect as dialect_named
from ..look.lights import DEFAULT_LIGHTS
from ..nodes.base import IMPLICIT, Node
from ..nodes.grid_scope import grid_min_as
from ..nodes.traverse import run_deep
from ..params import Param
from ..settings import DISTANCE_METHODS, Settings
from .analysis import analytic_shape, coarse_tile, material_channels, moving_origin, one_color, own_mesh, ray_free, shared_subtrees
from .builder import SourceBuilder
from .data.grid import GRID_MIN
from .defines import coarse_defines, free_way_defines, light_positions, mesh_normal_defines, settings_defines
from .emitter import DATA_MIN, Emitter
from .source import ShaderSource, comment_text
from .tables import DataPool, OriginOffsets
from .targets import TARGETS, Job, Target

BUDGET_DATA_MIN = 8  # a node with this many constant rows keeps them as data when map() is over the code budget
BUDGET_GRID_MIN = 8  # over the budget, unions of this many instances become data
MAX_CODE_SIZE = 3_000_000  # characters of scene code refused even as data (the driver would take many minutes)
# characters of scene code once every call of a reused subtree's function is written out, as
# the GL driver inlines them: past this its compile takes many seconds (a graph whose levels
# each reuse the one below twice doubles at every level)
MAX_EXPANDED_SIZE = 150_000


@dataclasses.dataclass
class Passes:
    """What every pass over one scene shares: live parameters, subtrees written as
    functions, unions kept as data, generated helpers, data tables and origin offsets."""

    origin: np.ndarray
    params: list[Param]
    shared: set
    grids: dict
    use_grids: bool | str
    helpers: dict
    data: DataPool
    data_min: int
    origins: OriginOffsets | None

    def emit(self, scene: Node, mode: str, detail: bool = False, channel: str = "albedo",
             highlight: Node | None = None, ray_free_id: int | None = None) -> tuple[Emitter, str]:
        """One pass over ``scene``: its Emitter and the result variable of map() (or its like)."""
        em = Emitter(mode, params=self.params, channel=channel)
        em.ray_free = ray_free_id
        em.origins = self.origins
        em.data = self.data
        em.data_min = self.data_min
        em.highlight = highlight
        em.helpers = self.helpers
        em.detail = detail
        em.shared_keys = self.shared
        em.grids = self.grids
        em.use_grids = self.use_grids
        if self.origins is not None:  # the origin is a uniform: every point from the root gets one
            em.origin_base = "p"
            p = em.shift("p", np.zeros(3))
        else:
            p = em.shift("p", self.origin) if self.origin.any() else "p"
        return em, scene.emit(em, p)


def generate(scene: Node, settings: Settings, origin: Sequence[float] = (0.0, 0.0, 0.0),
             target: str = "render", dialect: str = "desktop", projection: str = "perspective",
             highlight: Node | None = None) -> ShaderSource:
    """Build the fragment shader for ``scene``.

    ``origin`` (float64) is the world point that the shader's coordinates are relative
    to; ``target`` is one of :data:`sdfgl.compiler.targets.TARGETS`: ``"render"`` (the
    image), ``"evaluate"`` (map() at given points), ``"evaluate_color"`` /
    ``"evaluate_surface"`` / ``"evaluate_emission"`` (a material channel and map() at given
    points: mesh colours and path-traced materials use them), or one of the mesh exporter's
    samplers (sdfgl.mesh: same map(), other main()s): ``"mesh_grid"`` (a lattice of
    blocks), ``"mesh_gradient"`` (value and gradient at points), ``"mesh_project"`` (points
    moved onto the surface by Newton steps), or a render with raster meshes
    (:mod:`sdfgl.raster`): ``"render_over_mesh"`` (the image, marched only up to the meshes'
    depth) and ``"raster_mesh"`` (the meshes' fragment shader: the scene's lights, shadows and
    AO at a triangle point); ``dialect`` is ``"desktop"`` (GLSL 3.30) or
    ``"webgl2"`` (GLSL ES 3.00): the same code under another header (see
    :mod:`sdfgl.gl.dialect`); ``projection`` is the camera's ("perspective" or
    "orthographic": it shapes the rays). ``highlight`` is the subtree the "select" debug
    view tints.
    """
    lang = dialect_named(dialect)
    if not isinstance(scene, Node):
        raise ParameterError(f"scene must be an sdfgl node, got {type(scene).__name__} {scene!r}")
    if target not in TARGETS:
        raise ParameterError(f"target must be one of {', '.join(TARGETS)}, got {target!r}")
    moving = moving_origin(scene, target, dialect)
    return run_deep(scene, lambda: _generate(scene, settings, origin, target, lang, projection, highlight, moving))


def _generate(scene: Node, settings: Settings, origin: Sequence[float], target: str, lang: Dialect,
              projection: str, highlight: Node | None = None, moving: bool = False) -> ShaderSource:
    """generate(), within the code-size budget."""
    settings = settings.resolved(scene.exactness)
    if scene.exactness == IMPLICIT and TARGETS[target].image and settings.method in DISTANCE_METHODS:
        raise ParameterError(
            f"{scene.label()} is an implicit field, not a distance bound: method {settings.method!r} would step "
            f"through surfaces. Use method='auto' (the default), 'newton', 'forward_newton' or 'reference'.")
    if (settings.debug == "select") != (highlight is not None and TARGETS[target].image):
        raise ParameterError("debug view 'select' needs a highlighted subtree (generate(..., highlight=node)), "
                             "and a highlight needs debug='select'")
    org = np.zeros(3) if moving else np.asarray(origin, dtype=np.float64)
    row = TARGETS[target]
    tile = coarse_tile(scene, settings, target, lang.name)
    if settings.grid_min is not None:
        with grid_min_as(settings.grid_min):
            src = _write(scene, settings, org, row, lang, projection, highlight=highlight, moving=moving, coarse=tile)
        return _checked(dataclasses.replace(src, grid_min=settings.grid_min))
    src = dataclasses.replace(_write(scene, settings, org, row, lang, projection, highlight=highlight,
                                     moving=moving, coarse=tile), grid_min=GRID_MIN)
    if src.code_size <= settings.code_budget or not settings.grid:
        return _checked(src)
    # over the budget: every hard union of BUDGET_GRID_MIN or more instances becomes data,
    # and every node with more than a few constant rows keeps them in a texture
    with grid_min_as(BUDGET_GRID_MIN):
        small = _write(scene, settings, org, row, lang, projection, data_min=BUDGET_DATA_MIN,
                       highlight=highlight, moving=moving, coarse=tile)
    if small.code_size >= src.code_size:  # nothing to gain: the scene stays code
        return _checked(src)
    return _checked(dataclasses.replace(
        small, grid_min=BUDGET_GRID_MIN,
        choice=f"data (scene code of {src.code_size} characters was over the code budget of "
               f"{settings.code_budget}; as data {small.code_size})"))


def plain_size(emitters: Sequence[Emitter]) -> int:
    """Characters of the emitters' code with each subtree function counted once."""
    functions = {name: lines for em in emitters for name, lines in em.functions.values()}
    return sum(len(line) + 1 for lines in [*(em.lines for em in emitters), *functions.values()] for line, _ in lines)


def expanded_size(emitters: Sequence[Emitter]) -> int:
    """Characters of the emitters' code (map() and its like) with every call of a subtree
    function counted as the function's own expanded text, the way a driver inlines it."""
    functions = {name: lines for em in emitters for name, lines in em.functions.values()}
    calls = {name: re.compile(rf"\b{name}\(") for name in functions}
    memo: dict[str, int] = {}

    def text_size(lines: Sequence[tuple[str, str]], own: str = "") -> int:
        text = "\n".join(line for line, _ in lines)
        size = len(text)
        for name, pattern in calls.items():
            count = 0 if name == own else len(pattern.findall(text))
            if count:  # calls go only down the scene graph, so this recursion ends
                size += count * function_size(name)
        return size

    def function_size(name: str) -> int:
        if name not in memo:
            memo[name] = text_size(functions[name], own=name)
        return memo[name]

    return sum(text_size(em.lines) for em in emitters)


def _checked(src: ShaderSource) -> ShaderSource:
    if src.code_size > MAX_CODE_SIZE:
        raise ParameterError(f"scene: its generated code has {src.code_size} characters, over the limit of "
                             f"{MAX_CODE_SIZE} that a GL driver compiles in reasonable time (e.g. a chain of "
                             f"operations nested 10^5 deep with nothing to fold or keep as data); build big scenes "
                             f"as unions of instances, or flatten the chain")
    return src


def _write(scene: Node, settings: Settings, org: np.ndarray, row: Target, lang: Dialect, projection: str,
           data_min: int = DATA_MIN, highlight: Node | None = None, moving: bool = False,
           coarse: int = 0) -> ShaderSource:
    """One shader: the passes over the scene, the shared head and map(), then the target's stages
    (``coarse``: the tile side of the coarse pass the march starts from, 0 for none)."""
    origins = OriginOffsets() if moving else None
    passes = Passes(org, [], shared_subtrees(scene, settings.grid), {}, settings.grid, {}, DataPool(), data_min,
                    origins)
    free_way = ray_free(scene, settings) if row.image else None
    mesh_normal = own_mesh(scene) if row.image and not scene.has_detail else None
    dist, dist_result = passes.emit(scene, "dist", highlight=highlight if row.image else None,
                                    ray_free_id=None if free_way is None else id(free_way[0]))
    job = Job(scene, settings, row, SourceBuilder(), coarse=coarse, free_way=free_way)
    if row.color and not one_color(scene, highlight):
        job.color = passes.emit(scene, "color")
    if row.image and scene.has_detail:
        job.detail = passes.emit(scene, "dist", True)
    job.channels = [ch for ch in material_channels(scene) if row.reads(ch)]
    job.passes = {ch: passes.emit(scene, "color", channel=ch) for ch in job.channels}
    ems = [dist] + [found[0] for found in (job.color, job.detail) if found is not None]
    libs = list(dict.fromkeys([lib for em in ems for lib in em.libs]
                              + [lib for em, _ in job.passes.values() for lib in em.libs]))
    params = passes.params
    live = bool(params) or moving  # the box (and the ground) move with the parameters or the origin
    job.rig = settings.lights if settings.lights is not None else DEFAULT_LIGHTS
    job.lights_at = light_positions(job.rig, org, origins) if row.image else {}

    b = job.b
    b.add(lang.header(), "(codegen)")
    b.add(f"// sdfgl scene: {comment_text(scene.label())}  [{scene.exactness}, L={scene.lipschitz:g}]", "(codegen)")
    b.add("\n".join(settings_defines(scene, settings, org, live, projection, moving)
                     + free_way_defines(free_way) + mesh_normal_defines(mesh_normal) + coarse_defines(scene, coarse)),
          "(settings)")
    for i, prm in enumerate(params):
        b.add(f"uniform {'vec3' if prm.dims == 3 else 'float'} uP{i};  // param {comment_text(prm.label)}", "(live parameters)")
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
    for name, code in passes.helpers.items():
        if isinstance(code, str):
            b.add(code, f"(generated helper {name})")
        else:  # (line, owner) pairs: user code whose lines keep their own numbers
            for line, owner in code:
                b.add(line, owner)
    data = passes.data.texture()
    if highlight is not None and row.image:
        b.add("float gSel = 1e30;  // distance of the highlighted subtree at the last map() call", "(debug select)")
    b.add_helpers(dist, job.done)
    b.add_function("float map(vec3 p)", dist, dist_result, "{}")
    for stage in row.scene:
        stage(job)
    size = b.size_since(start)
    passes_ems = ems + [em for em, _ in job.passes.values()]
    expanded = expanded_size(passes_ems)
    if expanded > MAX_EXPANDED_SIZE and expanded > 2 * plain_size(passes_ems):
        raise ParameterError(
            f"scene: its code would be {expanded:,} characters once its reused subtrees are written out "
            f"(the GL driver inlines every call of the {len(dist.functions)} subtree functions), over the limit "
            f"of {MAX_EXPANDED_SIZE:,} that compiles in reasonable time; a graph whose every level uses the one "
            f"below more than once grows exponentially: build the copies as one union of instances instead")
    for stage in row.main:
        stage(job)
    return dataclasses.replace(b.build(params, live, data), code_size=size, data_unions=len(passes.grids),
                               origin_offsets=None if origins is None else tuple(origins.entries), coarse_tile=coarse,
                               ground=bool(settings.ground))


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
