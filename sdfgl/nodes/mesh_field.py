"""A closed triangle mesh as a field: the exact signed distance to its surface.

On the GPU the triangles are data in a bounding volume hierarchy
(:mod:`sdfgl.compiler.data.triangles`, registered as the layout "mesh"); the sign is the
side of the angle-weighted pseudonormal at the closest feature (face, edge or vertex), which
is right everywhere for a closed, consistently oriented mesh and needs no more than the
closest point. The float64 twin is libigl's ``signed_distance`` with the same sign rule
(the ``meshin`` extra). Meshes that cannot be signed that way (holes, edges shared by more
than two faces, faces that disagree on orientation) are refused with a :class:`MeshError`
naming the mesh; :func:`sdfgl.load_mesh` repairs what it safely can first.
"""
from __future__ import annotations

import hashlib
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import MeshError
from .base import EXACT, Node
from .layouts import layout

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter
    from ..meshin.source import MeshFile

RAY_BOX_PAD = 1e-5
"""How much the free way's ray-box tests widen the hierarchy's boxes, of the largest vertex
coordinate (float32 rounds relative to it: the box entry must not skip the box of the
triangle the ray meets)."""
MAX_TRIANGLES = 1_500_000
"""The most triangles a mesh node holds (its GPU tables fill the data texture's 2^24 texels)."""


def _edge_faults(faces: np.ndarray, nvert: int) -> tuple[int, int]:
    """(boundary edges, edges used twice the same way): both 0 for a closed, consistently
    oriented 2-manifold."""
    directed = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2).astype(np.int64)
    code = np.sort(directed[:, 0] * nvert + directed[:, 1])
    repeated = int(np.count_nonzero(code[1:] == code[:-1]))
    rev = np.sort(directed[:, 1] * nvert + directed[:, 0])
    at = np.clip(np.searchsorted(code, rev), 0, len(code) - 1)
    boundary = int(np.count_nonzero(code[at] != rev))
    return boundary, repeated


def checked_mesh(vertices: Any, faces: Any, name: str) -> tuple[np.ndarray, np.ndarray]:
    """(float64 vertices (v, 3), int64 faces (n, 3) wound outward) of a closed mesh, else a
    MeshError naming ``name`` and what is wrong."""
    try:
        verts = np.array(vertices, dtype=np.float64)
        tris = np.array(faces)
    except (TypeError, ValueError):
        raise MeshError(f"mesh '{name}': vertices and faces must be numeric arrays") from None
    if verts.ndim != 2 or verts.shape[1] != 3 or tris.ndim != 2 or tris.shape[1] != 3:
        raise MeshError(f"mesh '{name}': needs vertices of shape (v, 3) and triangles of shape (n, 3), "
                        f"got {verts.shape} and {tris.shape}")
    if len(tris) == 0:
        raise MeshError(f"mesh '{name}': has no triangles")
    if len(tris) > MAX_TRIANGLES:
        raise MeshError(f"mesh '{name}': has {len(tris)} triangles, over the limit of {MAX_TRIANGLES}; "
                        f"simplify it first (e.g. trimesh's simplify_quadric_decimation)")
    if not np.issubdtype(tris.dtype, np.integer):
        raise MeshError(f"mesh '{name}': triangle indices must be integers, got {tris.dtype}")
    tris = tris.astype(np.int64)
    if tris.min() < 0 or tris.max() >= len(verts):
        raise MeshError(f"mesh '{name}': a triangle index is outside 0..{len(verts) - 1}")
    bad = ~np.isfinite(verts).all(axis=1)
    if bad.any():
        raise MeshError(f"mesh '{name}': {int(bad.sum())} vertices are not finite (NaN or inf), e.g. vertex "
                        f"{int(np.flatnonzero(bad)[0])}")
    boundary, repeated = _edge_faults(tris, len(verts))
    if boundary or repeated:
        what = []
        if boundary:
            what.append(f"{boundary} edges border a hole or a face of the other orientation")
        if repeated:
            what.append(f"{repeated} edges are used twice the same way (non-manifold or inconsistent winding)")
        raise MeshError(f"mesh '{name}': is not a closed, consistently oriented surface ({'; '.join(what)}), "
                        f"so inside and outside are not defined; close its holes and fix its winding first")
    t = verts[tris]
    volume = float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum()) / 6.0
    if not volume:
        raise MeshError(f"mesh '{name}': encloses no volume")
    if volume < 0:  # wound inward: turn every face so the normals point out
        tris = tris[:, ::-1].copy()
    return verts, tris


class MeshField(Node):
    """The exact signed distance to a closed triangle mesh (negative inside).

    Build it with :func:`sdfgl.load_mesh` (a file) or :func:`sdfgl.from_mesh` (a trimesh);
    ``MeshField(vertices, faces, name)`` takes the arrays themselves. ``source`` is the file
    the triangles were read from (:class:`~sdfgl.meshin.source.MeshFile`, set by
    ``load_mesh``), which a scene document saves instead of the triangles
    (:mod:`sdfgl.scene_io.mesh_nodes`)."""

    kind = "mesh"
    costly = True

    def __init__(self, vertices: Any, faces: Any, name: str = "mesh", source: "MeshFile | None" = None) -> None:
        verts, tris = checked_mesh(vertices, faces, name)
        digest = hashlib.sha1(verts.tobytes() + tris.tobytes()).hexdigest()[:16]
        super().__init__((), mesh=digest, triangles=len(tris))
        self.vertices, self.faces, self.name, self.source = verts, tris, name, source

    def label(self) -> str:
        return f"mesh({self.name}, {len(self.faces)} triangles)"

    @property
    def exactness(self) -> str:
        return EXACT

    @property
    def bvh(self) -> Any:
        """The GPU tables of this mesh (sdfgl.compiler.data.triangles), built once."""
        if "_bvh" not in self.__dict__:
            build = layout("mesh")
            if build is None:
                raise MeshError(f"{self.label()}: no mesh layout is registered (import sdfgl first)")
            self.__dict__["_bvh"] = build(self.vertices, self.faces)
        return self.__dict__["_bvh"]

    def _emit(self, em: "Emitter", p: str) -> str:
        bvh = self.bvh
        em.require("sd_mesh_bvh")
        nodes, tris = em.table(bvh.nodes), em.table(bvh.triangles)
        end = tris + len(bvh.triangles)
        q = em.point(p)
        pad = em.num(RAY_BOX_PAD * float(np.abs(self.vertices).max()))
        em.ask_free_way(self, f"meshRayFree({q}, gRayDir, gRayInv, {nodes}, {tris}, {pad})")  # the scene's own mesh
        walk = f"sdMeshBVH({q}, {nodes}, {tris}, {end})"
        if em.leaves_free_way(self):  # the march wants the cast alone (stages/march_cast.glsl)
            walk = f"(gCastOnly ? 0.0 : {walk})"
        return em.with_color(em.assign("float", walk))

    def _distance(self, p: np.ndarray) -> np.ndarray:
        from ..extras import require_extra
        require_extra("meshin", "igl", purpose=f"the float64 twin of {self.label()}")
        import igl
        flat = np.ascontiguousarray(p.reshape(-1, 3))
        if not len(flat):
            return np.zeros(p.shape[:-1])
        d = igl.signed_distance(flat, self.vertices, self.faces, sign_type=igl.SIGNED_DISTANCE_TYPE_PSEUDONORMAL)[0]
        return np.asarray(d, dtype=np.float64).reshape(p.shape[:-1])

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return self.vertices.min(axis=0), self.vertices.max(axis=0)
