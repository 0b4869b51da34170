"""The table of targets: what each kind of shader writes after map().

Every target shares the head of the shader (version, #defines, uniforms, library
functions, map()); a :class:`Target` names the passes it needs and its stages: those
counted as scene code (``ShaderSource.code_size``) and those of its entry point. A target
is a row of :data:`TARGETS`, never a branch of the generator.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

from ..look.shading import background_code, shade_function, shadow_code, shadow_kinds, unshadowed_tile_function
from ..nodes.base import IMPLICIT, Node
from ..nodes.mesh_field import MeshField
from ..settings import Settings
from .analysis import MARCH_FILES, analytic_shape
from .builder import SourceBuilder, surface_function, vec3_literal
from .emitter import DEFAULT_COLOR, Emitter
from .source import glsl_float


@dataclass
class Job:
    """What the stages of one shader share: the scene, its settings, the builder and the
    emitted passes (an Emitter and its result variable each)."""

    scene: Node
    settings: Settings
    target: "Target"
    b: SourceBuilder
    color: tuple[Emitter, str] | None = None  # mapColor()'s pass; None: one colour
    detail: tuple[Emitter, str] | None = None  # mapDetail()'s pass (the normals-only field)
    passes: dict[str, tuple[Emitter, str]] = field(default_factory=dict)  # material channel -> pass
    channels: list[str] = field(default_factory=list)  # the material channels the shader has
    rig: Sequence[Any] = ()  # the lights
    lights_at: dict[int, str] = field(default_factory=dict)  # GLSL of each point light's position
    done: set[str] = field(default_factory=set)  # GLSL functions already written
    coarse: int = 0  # the tile side of the coarse pass (0: none)
    free_way: tuple[Any, Any] | None = None  # what leaves the march's free way (analysis.ray_free), and its turn


Stage = Callable[[Job], None]


def add_file(name: str) -> Stage:
    """The stage that appends ``shaders/<name>.glsl``."""
    def stage(job: Job) -> None:
        job.b.add_file(name)
    stage.__name__ = f"file {name}"
    return stage


def color_functions(job: Job) -> None:
    """mapColor() (one constant where no node sets a material) and map<Channel>() per pass."""
    b = job.b
    if job.color is None:
        b.add(f"vec3 mapColor(vec3 p) {{\n    return {vec3_literal(DEFAULT_COLOR)};  // no material node: one colour\n}}",
              "(codegen: one colour)")
    else:
        em, result = job.color
        b.add_helpers(em, job.done)
        b.add_function("vec3 mapColor(vec3 p)", em, result, "{}.rgb")
    for ch, (em, result) in job.passes.items():
        b.add_helpers(em, job.done)
        b.add_function(f"vec3 map{ch.capitalize()}(vec3 p)", em, result, "{}.rgb")


def channel_define(job: Job) -> None:
    """The material channel function an evaluate main() runs."""
    job.b.add(f"#define EVAL_CHANNEL {job.target.channel}", "(codegen)")


def detail_function(job: Job) -> None:
    """mapDetail(): the field with its fine detail, for normals only."""
    if job.detail is not None:
        em, result = job.detail
        job.b.add_helpers(em, job.done)
        job.b.add_function("float mapDetail(vec3 p)", em, result, "{}")
        job.b.add("#define DETAIL_NORMALS", "(codegen)")


def march(job: Job) -> None:
    """The hit refinement, the marcher the method names (or the closed form, or the cast of a
    lone mesh) and the normal."""
    b, settings = job.b, job.settings
    analytic = settings.analytic and analytic_shape(job.scene) is not None
    cast = job.free_way is not None and isinstance(job.free_way[0], MeshField)  # the ray meets its first triangle
    if not cast:
        b.add_file("stages/refine")
    if job.coarse:
        b.add_file("stages/coarse_start")
    if cast:
        b.add_file("stages/march_cast")
        b.add_file("stages/normal")
        return
    if not analytic and settings.method in ("newton", "forward_newton"):
        b.add_file("stages/ray_derivative")
    if analytic:
        b.add_file("stages/march_analytic")
    else:
        b.add_file(f"stages/march_{MARCH_FILES.get(settings.method, settings.method)}")
    b.add_file("stages/normal")


def shading(job: Job) -> None:
    """Shadows, AO, the material at a hit, the background, the lights, the ground and the
    pixel's gamma encoding."""
    b, settings = job.b, job.settings
    implicit = job.scene.exactness == IMPLICIT
    for code, owner in shadow_code(shadow_kinds(job.rig, settings.shadows, implicit)):
        b.add(code, owner)
    if settings.ao:
        b.add_file("stages/ao")
    b.add_file("stages/shade")
    b.add(surface_function(job.channels), "(codegen: material)")
    b.add(*background_code(settings.background, glsl_float))
    b.add(shade_function(settings.lights, settings.ambient, settings.shadows, implicit, glsl_float,
                         metals="surface" in job.channels, positions=job.lights_at), "(look: lights)")
    if settings.ground:
        b.add_file("stages/ground")
    b.add_file("stages/gamma")


def render_main(job: Job) -> None:
    """The image's main(): its head, the debug views when one is on, its body."""
    job.b.add_file("mains/render_main_head")
    if job.settings.debug:
        job.b.add_file("stages/debug")
    job.b.add_file("mains/render_main")


@dataclass(frozen=True)
class Target:
    """One kind of shader: the passes it needs besides map() and its stages."""

    image: bool = False  # the rendered image: every material channel, detail, highlight, free way, lights
    color: bool = False  # it reads mapColor()
    channel: str | None = None  # evaluate targets: the channel function its main() runs at given points
    scene: tuple[Stage, ...] = ()  # stages written as scene code (counted in code_size)
    main: tuple[Stage, ...] = ()  # the stages of its entry point

    def reads(self, channel: str) -> bool:
        """Whether this target's shader has the map<Channel>() pass of material ``channel``."""
        return self.image or self.channel == f"map{channel.capitalize()}"


def _evaluate_channel(fn: str) -> Target:
    return Target(color=True, channel=fn, scene=(color_functions, channel_define),
                  main=(add_file("mains/evaluate_channel_main"),))


def _mesh(name: str) -> Target:
    return Target(main=(add_file("stages/mesh_clip"), add_file(f"mains/{name}_main")))


def coarse_lights(job: Job) -> None:
    """The coarse pass's test of a tile's ground against the shadowed lights."""
    job.b.add(unshadowed_tile_function(job.settings.lights, job.settings.shadows, glsl_float), "(look: lights)")


def raster_mesh_main(job: Job) -> None:
    """The raster mesh's fragment main(): a triangle point shaded with the scene's lights."""
    job.b.add_file("mains/raster_mesh_main")


# target -> its row: "render" (the image), "evaluate" (map() at given points), "evaluate_color" /
# "evaluate_surface" / "evaluate_emission" (a material channel and map() at given points: mesh
# colours and path-traced materials), the mesh exporter's samplers "mesh_grid" (a lattice of
# blocks), "mesh_gradient" (value and gradient at points), "mesh_project" (points moved onto the
# surface by Newton steps), "render_over_mesh" (the image marched only up to the raster meshes'
# depth), "raster_mesh" (the fragments of raster meshes, shaded and shadowed by the scene) and
# "coarse" (the pass before "render": per tile of pixels, the depth its rays start marching from).
# The "webgl2" dialect writes the same targets under another header.
TARGETS: dict[str, Target] = {
    "render": Target(image=True, color=True, scene=(color_functions, detail_function),
                     main=(march, shading, render_main)),
    "evaluate": Target(main=(add_file("mains/evaluate_main"),)),
    "evaluate_color": _evaluate_channel("mapColor"),
    "evaluate_surface": _evaluate_channel("mapSurface"),
    "evaluate_emission": _evaluate_channel("mapEmission"),
    "mesh_grid": _mesh("mesh_grid"),
    "mesh_gradient": _mesh("mesh_gradient"),
    "mesh_project": _mesh("mesh_project"),
    "render_over_mesh": Target(image=True, color=True, scene=(color_functions, detail_function),
                               main=(add_file("stages/raster_composite"), march, shading, render_main)),
    "raster_mesh": Target(image=True, color=True, scene=(color_functions, detail_function),
                          main=(shading, raster_mesh_main)),
    "coarse": Target(main=(coarse_lights, add_file("stages/coarse_cone"), add_file("mains/coarse_main"))),
}
# evaluate targets: the material channel function each runs at given points (with map())
EVALUATE_CHANNELS = {name: t.channel for name, t in TARGETS.items() if t.channel is not None}
