"""Triangle meshes drawn by rasterisation in a render, composited with the ray march by depth.

:func:`raster` turns a ``trimesh.Trimesh`` or a mesh file into a :class:`RasterMesh`;
``sg.render(scene, meshes=[...])`` draws them first, then marches the scene only up to
the meshes' depth per pixel (see :mod:`sdfgl.render`).
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from .compiler.emitter import DEFAULT_SURFACE
from .errors import MeshError, ParameterError
from .extras import require_extra
from .values import validate as v

MATERIAL_FIELDS = ("specular", "shininess", "metallic", "emission")
"""The material fields a raster mesh takes (the albedo is its ``color``)."""


@dataclass(frozen=True, eq=False)
class RasterMesh:
    """A triangle mesh to rasterise: float64 ``vertices`` (N, 3), int32 ``faces`` (M, 3),
    float32 unit vertex ``normals`` (N, 3) (vertices split at sharp edges, so flat faces shade flat), a linear RGB ``color`` and material fields
    (``specular``, ``shininess``, ``metallic``, ``emission``) shaded by the scene's lights.
    Made by :func:`raster`.

    Example:
        >>> import trimesh
        >>> m = sg.raster(trimesh.creation.icosphere(), color="red")
        >>> m.color, m.bounds[1].round(3).tolist()
        ((1.0, 0.0, 0.0), [1.0, 1.0, 1.0])
    """

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    color: tuple[float, float, float]
    material: Mapping[str, Any] = field(default_factory=dict)

    @property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi) corners of the vertices' box."""
        return self.vertices.min(axis=0), self.vertices.max(axis=0)

    def __repr__(self) -> str:
        return f"<RasterMesh {len(self.vertices)} vertices, {len(self.faces)} triangles>"


def _material(where: str, material: Mapping[str, Any] | None) -> dict[str, Any]:
    if material is None:
        material = {}
    if not isinstance(material, Mapping):
        raise ParameterError(f"{where}: 'material' must be a mapping of {', '.join(MATERIAL_FIELDS)}, "
                             f"got {type(material).__name__}")
    unknown = sorted(set(material) - set(MATERIAL_FIELDS))
    if unknown:
        raise ParameterError(f"{where}: 'material' has unknown fields {unknown}; choose from {', '.join(MATERIAL_FIELDS)}")
    out: dict[str, Any] = {}
    for name in ("specular", "shininess", "metallic"):
        val = material.get(name, DEFAULT_SURFACE[name])
        out[name] = float(v.scalar(where, name, val))
    if not 0.0 <= out["metallic"] <= 1.0:
        raise ParameterError(f"{where}: material 'metallic' must lie in [0, 1], got {out['metallic']:g}")
    out["emission"] = tuple(float(x) for x in v.vector(where, "emission", material.get("emission", DEFAULT_SURFACE["emission"])))
    return out


def raster(mesh: Any, color: object = "#cccccc", material: Mapping[str, Any] | None = None) -> RasterMesh:
    """A mesh that ``sg.render(..., meshes=[...])`` draws by rasterisation.

    Args:
        mesh: a ``trimesh.Trimesh`` or the path of a mesh file trimesh reads (STL, OBJ,
            PLY, GLB/glTF, 3MF, OFF).
        color: its albedo (a name, hex, 0..255 or 0..1 triple).
        material: optional ``specular``, ``shininess``, ``metallic`` (0..1) and ``emission``
            (a linear RGB triple); unset fields take the scene's defaults.

    Example:
        >>> import trimesh
        >>> sg.raster(trimesh.creation.box((1, 1, 1)), color="#ccc").faces.shape
        (12, 3)
    """
    require_extra("meshin", "trimesh", purpose="sg.raster")
    import trimesh
    name = "raster"
    if isinstance(mesh, (str, os.PathLike)):
        name = f"raster: mesh file '{os.fspath(mesh)}'"
        if not os.path.isfile(mesh):
            raise MeshError(f"{name}: no such file")
        try:
            mesh = trimesh.load(os.fspath(mesh), force="mesh", process=False)
        except Exception as exc:  # trimesh's loaders raise many kinds of error for a bad file
            raise MeshError(f"{name}: cannot be read ({type(exc).__name__}: {exc})") from None
    if not isinstance(mesh, trimesh.Trimesh):
        raise ParameterError(f"raster: 'mesh' must be a trimesh.Trimesh or a file path, got {type(mesh).__name__}")
    verts = np.asarray(mesh.vertices, dtype=np.float64)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if len(faces) == 0:
        raise MeshError(f"{name}: the mesh holds no triangles")
    if not np.isfinite(verts).all():
        raise MeshError(f"{name}: {int((~np.isfinite(verts).all(axis=1)).sum())} vertices are not finite (NaN or inf)")
    # vertices are split where faces meet at a sharp angle: a box keeps its flat faces, a sphere stays smooth
    shaded = trimesh.Trimesh(verts, faces, process=False).smooth_shaded
    verts, faces = np.asarray(shaded.vertices, dtype=np.float64), np.asarray(shaded.faces, dtype=np.int64)
    normals = np.asarray(shaded.vertex_normals, dtype=np.float32)
    rgb = v.color("raster", color)
    return RasterMesh(verts, faces.astype(np.int32), normals, tuple(float(c) for c in rgb), _material("raster", material))
