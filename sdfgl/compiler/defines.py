"""The #define block of a shader: settings, scene frame, free way; and the lights' positions."""
from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

from ..nodes.base import IMPLICIT, Node
from ..nodes.mesh_field import MeshField
from ..settings import DEFAULT_OMEGA, Settings
from .analysis import (BOUNDS_PAD, GLSL_FAR, analytic_relative, analytic_shape, max_steps_of, ref_step, scene_frame,
                       unbounded)
from .emitter import DEFAULT_SURFACE
from .source import glsl_float
from .tables import OriginOffsets


def settings_defines(scene: Node, settings: Settings, origin: np.ndarray, live: bool, projection: str,
                     moving: bool = False) -> list[str]:
    """The #defines of the settings and the scene frame: bounds, steps, method, features."""
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
        if scene.exactness != IMPLICIT and math.isfinite(scene.lipschitz):  # calcAO's open test (stages/ao.glsl)
            d.append(f"#define AO_LIPSCHITZ {lipschitz_value(scene)}")
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


def glsl_mat3(m: np.ndarray) -> str:
    """The GLSL mat3 of the 3x3 matrix ``m`` (GLSL's constructor takes the columns)."""
    return f"mat3({', '.join(glsl_float(float(x)) for x in np.asarray(m).T.ravel())})"


def _flag_and_turn(flag: str, turn_flag: str, turn: np.ndarray, matrix: np.ndarray) -> list[str]:
    """``#define flag``, and ``#define turn_flag`` as the mat3 ``matrix`` where ``turn`` is no identity."""
    if np.array_equal(turn, np.eye(3)):
        return [f"#define {flag}"]
    return [f"#define {flag}", f"#define {turn_flag} {glsl_mat3(matrix)}"]


def free_way_defines(free_way: tuple[Any, np.ndarray] | None) -> list[str]:
    """The defines of the free way along the ray: RAY_FREE, and RAY_FREE_TURN (R^T, which
    turns the ray's direction into the grid's or mesh's frame) where it is rotated;
    RAY_FREE_HIT where the way ends where the ray meets the surface (a mesh's cast), so hard
    shadows step it too (a grid's way, a bound, did not pay there)."""
    if free_way is None:
        return []
    hit = ["#define RAY_FREE_HIT"] if isinstance(free_way[0], MeshField) else []
    return _flag_and_turn("RAY_FREE", "RAY_FREE_TURN", free_way[1], free_way[1].T) + hit


def mesh_normal_defines(mesh: tuple[Any, np.ndarray] | None) -> list[str]:
    """The defines of normals from the closest triangle (shaders/stages/normal.glsl) where the
    scene is one mesh (analysis.own_mesh): MESH_NORMAL, and MESH_NORMAL_TURN (R, which turns
    the mesh's gradient into the world) where it is rotated."""
    return [] if mesh is None else _flag_and_turn("MESH_NORMAL", "MESH_NORMAL_TURN", mesh[1], mesh[1])


def coarse_defines(scene: Node, tile: int) -> list[str]:
    """The defines of the coarse pass: its tile side in pixels and the field's Lipschitz factor
    (a cone advances by the field's value over it); none where there is no coarse pass."""
    if not tile:
        return []
    return [f"#define COARSE_TILE {tile}", f"#define LIPSCHITZ {lipschitz_value(scene)}"]


def lipschitz_value(scene: Node) -> str:
    """The scene's Lipschitz factor as the shaders' tests use it (never below 1), in GLSL."""
    return glsl_float(max(scene.lipschitz, 1.0))


def light_positions(rig: Sequence[Any], org: np.ndarray, origins: OriginOffsets | None) -> dict[int, str]:
    """GLSL of each point light's position relative to the shader origin: a constant, or
    minus the uOrgN uniform of offset -position when the origin moves."""
    out = {}
    for i, lt in enumerate(rig):
        if lt.kind != "directional":
            pos = np.asarray(lt.vector, dtype=np.float64)
            out[i] = (f"(-{origins.uniform(-pos, ())})" if origins is not None
                      else f"vec3({', '.join(glsl_float(x) for x in pos - org)})")
    return out
