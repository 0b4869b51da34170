"""Scene analysis: what the compiler learns about a scene before writing code.

Its frame (finite bounds, length scale, step limit), a closed-form shape the marcher may
intersect directly, a moving shader origin, the union whose free way along the ray the
marcher may step, the subtrees that occur more than once and the material channels the
scene sets. What a node is, the compiler asks the node (``data_union``,
``distance_keeping``, ``analytic_plane``), never its class.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from ..nodes.base import Node
from ..nodes.mesh_field import MeshField
from ..nodes.traverse import fact
from ..settings import Settings
from .data.instances import pack, unwrap
from .emitter import CHANNELS

# Stand-in for an infinite bound inside GLSL: finite in float32, so no inf*0 arises.
GLSL_FAR = 1e30
BOUNDS_PAD = 1e-3  # the ray clip box grows by this share of the scene size
# methods that share a loop file, told apart by a #define
MARCH_FILES = {"sphere": "relaxed", "enhanced": "relaxed", "forward_newton": "newton"}


def scene_frame(scene: Node) -> tuple[np.ndarray, np.ndarray, float]:
    """Finite stand-ins for the scene bounds (inf -> GLSL_FAR) and a length scale."""
    lo, hi = scene.bounds
    finite = np.isfinite(lo) & np.isfinite(hi)
    ext = (hi - lo)[finite]
    scale = float(ext.max()) if ext.size and ext.max() > 0 else 1.0
    return np.where(np.isfinite(lo), lo, -GLSL_FAR), np.where(np.isfinite(hi), hi, GLSL_FAR), scale


# nodes whose children's boxes are in the node's own frame (their surfaces lie in those boxes)
SAME_FRAME_KINDS = frozenset({"union", "intersection", "difference"})
NEAR_WORK_NODES = 4096  # near_work looks at no more parts than this
SPAN_OF_SCALES = 1e3  # a scene box this many times as large as how far a part near the eye reaches


def near_work(scene: Node, eye: np.ndarray) -> float | None:
    """For a scene that spans scales around the eye (a part near the eye, and small, far
    smaller than the scene's finite box: SPAN_OF_SCALES), how far that part reaches from
    the eye (the distance to the far side of its box): the float32 origin belongs near the
    eye then, where the part's own coordinates stay as small as it is, not at the box's
    centre. None elsewhere.

    The booleans are entered (their children's boxes are in their frame, and their surfaces
    lie in those boxes); any other node is a part, reaching as far as its box."""
    eye = np.asarray(eye, dtype=np.float64)
    lo, hi = scene.bounds
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        return None
    size = float(np.linalg.norm(hi - lo)) / 2
    near, stack, seen = np.inf, [scene], {id(scene)}
    while stack:
        node = stack.pop()
        lo, hi = node.bounds
        gap = float(np.linalg.norm(np.maximum(np.maximum(lo - eye, eye - hi), 0.0)))
        if gap >= near:
            continue
        if node.kind in SAME_FRAME_KINDS:
            if len(seen) + len(node.children) > NEAR_WORK_NODES:
                return None  # a scene of many parts keeps its box centre (the walk stays cheap)
            fresh = [c for c in node.children if id(c) not in seen]  # a shared subtree once (DAGs)
            seen.update(id(c) for c in fresh)
            stack.extend(fresh)
        else:
            near = min(near, float(np.linalg.norm(np.maximum(np.abs(lo - eye), np.abs(hi - eye)))))
    return near if near * SPAN_OF_SCALES < size else None


def unbounded(scene: Node) -> bool:
    """True where the scene box is infinite on some side: only then does max_dist limit a ray."""
    lo, hi = scene.bounds
    return not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)))


def analytic_shape(scene: Node) -> tuple[str, np.ndarray] | None:
    """("sphere", (centre, radius)) or ("plane", (normal, offset)) in world space when the
    scene is one sphere or plane under rigid transforms, uniform scales and colours."""
    q = pack(scene)
    if q is not None and q.type == 0:
        return "sphere", np.array([*q.t, q.scale * q.size[0]])
    peeled = unwrap(scene)
    if peeled is None:
        return None
    inner, t, r, s, _ = peeled
    plane = inner.analytic_plane()
    if plane is None:
        return None
    normal, anchor = plane
    n = r @ normal
    point = t + s * (r @ anchor)
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


IMAGE_TARGETS = ("render", "render_over_mesh", "raster_mesh", "coarse")
"""The targets that draw one image together (the march and the raster meshes): they share a shader origin."""


def moving_origin(scene: Node, target: str = "render", dialect: str = "desktop") -> bool:
    """Whether the shader origin of ``scene`` is a uniform (uOrgN offsets, bounds as
    uniforms): rendering on the desktop an unbounded scene (the origin follows the eye) or
    one with live parameters (it follows the box's centre). Elsewhere the origin is folded
    into constants (a bounded scene is anchored at its fixed centre)."""
    if target not in IMAGE_TARGETS or dialect != "desktop":
        return False
    lo, hi = scene.bounds
    return not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))) or bool(scene.live_params())


COARSE_METHODS = ("sphere", "relaxed", "enhanced")  # marchers that step by a distance bound


def coarse_tile(scene: Node, settings: Settings, target: str = "render", dialect: str = "desktop") -> int:
    """The tile side (pixels) of the coarse pass before ``target``'s march, or 0 where there is
    none: the pass needs a distance bound with a finite Lipschitz factor and a marcher that steps
    by it (settings resolved), and runs before the desktop image only (``"coarse"`` is the
    pass itself); a closed-form shape is intersected, never marched."""
    if not settings.coarse or target not in ("render", "coarse") or dialect != "desktop":
        return 0
    if settings.method not in COARSE_METHODS or not np.isfinite(scene.lipschitz) or scene.lipschitz <= 0:
        return 0
    if settings.analytic and analytic_shape(scene) is not None:
        return 0
    cast = ray_free(scene, settings)
    if cast is not None and isinstance(cast[0], MeshField) and not (settings.ground and (settings.shadows or settings.ao)):
        # a lone mesh is cast, not marched (stages/march_cast.glsl): its cones would walk the mesh
        # for a start the cast does not need; only the ground's lit tiles pay for them
        return 0
    return int(settings.coarse)


def _under_moves(scene: Node) -> tuple[Node, np.ndarray]:
    """(the node under the scene's translations, rotations and materials, the rotation R
    with world = R @ that node's frame): the moves keep distances."""
    node, turn = scene, np.eye(3)
    while (step := node.distance_keeping()) is not None and not node.live_params():
        node, rotation = step
        if rotation is not None:
            turn = turn @ rotation
    return node, turn


def own_mesh(scene: Node) -> tuple[MeshField, np.ndarray] | None:
    """(the mesh, R with world = R @ the mesh's frame) where the scene is one mesh under
    translations, rotations and materials: the normal at a hit is the surface's at the triangle
    the ray met (sd_mesh_bvh.glsl's gMeshNormal), and the ray meets it where it meets a
    triangle."""
    node, turn = _under_moves(scene)
    return (node, turn) if isinstance(node, MeshField) else None


def ray_free(scene: Node, settings: Settings) -> tuple[Any, np.ndarray] | None:
    """What leaves the free way along the ray that the marcher may step (shaders/lib/ray_free.glsl),
    and the rotation R (world = R @ local) from its frame to the world's: the scene's own union
    kept as data (its grid: shaders/templates/grid_ray.glsl; any child beside the instances
    bounding the way by its distance) or the scene's own mesh (:func:`own_mesh`: where the ray
    meets its triangles), under translations, rotations and materials only (they keep
    distances; the marcher turns its direction by R^T); where the settings' method is sphere
    tracing or a relaxed variant. A grid's way is stepped by march_relaxed.glsl; a mesh's
    cast is the whole march (march_cast.glsl). None elsewhere."""
    if MARCH_FILES.get(settings.method, settings.method) != "relaxed" or not settings.free_way:
        return None
    mesh = own_mesh(scene)
    if mesh is not None:
        return mesh
    if settings.grid is not True:
        return None
    node, turn = _under_moves(scene)
    grid = node.data_union()
    if grid is not None and not grid.free_way:
        return None
    # the scene is a distance bound wherever a distance marcher runs (an implicit one is refused)
    return None if grid is None else (grid, turn)


def shared_subtrees(scene: Node, use_grids: bool | str = True) -> set:
    """Keys of composite subtrees that occur more than once (each becomes one GLSL function)."""
    counts: dict = {}
    stack = [scene]
    while stack:
        n = stack.pop()
        if n.children and n is not scene:  # the scene itself occurs once
            counts[n.key] = counts.get(n.key, 0) + 1
            if counts[n.key] > 1:
                continue  # its inside is counted once; the function holds it
        grid = n.data_union() if use_grids else None
        if grid is not None:  # instances are data: only their types' code and the other children
            stack.extend(grid.rest)
            stack.extend(t.inner for t in grid.types if t.slots is None)
            continue
        stack.extend(n.children)
    return {k for k, c in counts.items() if c > 1}


def material_channels(scene: Node) -> list[str]:
    """The colour passes the scene needs besides albedo: "surface" where some node sets
    specular, shininess or metallic, "emission" where some node sets an emission."""
    names = fact(scene, "_fields")
    return [ch for ch in ("surface", "emission") if any(f in names for f in CHANNELS[ch])]


def one_color(scene: Node, highlight: Node | None) -> bool:
    """True for a scene without any material node (and no highlight): mapColor() is then one
    constant, not another copy of the scene's code."""
    return not fact(scene, "_fields") and highlight is None

