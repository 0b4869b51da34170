"""The scene as triangle meshes for Mitsuba: sdfgl's own mesh export.

The mesh comes from :func:`sdfgl.mesh` (the generated map() on the GPU, dual contouring so
that CSG edges stay sharp, every vertex moved onto the surface by Newton steps to 0.001 of a
cell), at MESH_CELLS_PER_FOOTPRINT lattice cells per pixel footprint. The scene's colours,
node materials and Blend weights become per-vertex attributes (read by Mitsuba's
``mesh_attribute`` texture), evaluated at the vertices by the same generated code. Faces
whose vertices emit are split off into one mesh per emitted colour, each an ``area``
emitter (Mitsuba 3.9 crashes sampling an area emitter whose radiance is a mesh attribute).
Faces are flat-shaded: they are a third of a pixel across, and creases keep no averaged normal.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..camera import Camera
from ..compiler.analysis import material_channels
from ..errors import ParameterError
from ..evaluate import evaluate, evaluate_channel
from ..mesh.build import mesh as export_mesh
from ..mesh.result import Mesh
from ..nodes.base import Node
from .field_grid import MAX_CELLS, cell_size
from .materials import blend_weight, surface_terms

GEOMETRIES = ("auto", "mesh", "grid")
# A feature one grid cell thick (half a pixel footprint) spans 1.5 mesh cells, so the lattice
# always holds a sample inside it. Measured on a plate one grid cell thick at 160x120: 2 cells
# per footprint matched the EGL silhouette on 98.9 % of its edge pixels, 3 on 99.8 %.
MESH_CELLS_PER_FOOTPRINT = 3
AUTO_MAX_CELLS = 512       # "auto" meshes up to this many lattice cells along the box's longest side (meshing grows with its square: ~10 s at 400 on 2 cores)
MAX_EMITTED_COLOURS = 16   # distinct emitted colours on the mesh path (one area emitter each)


def check_geometry(geometry: object) -> str:
    """``geometry`` if it is one of GEOMETRIES, else a ParameterError naming the option."""
    if not isinstance(geometry, str) or geometry not in GEOMETRIES:
        raise ParameterError(f"pbr: 'geometry' must be one of {', '.join(repr(g) for g in GEOMETRIES)}, "
                             f"got {geometry!r}")
    return geometry


def mesh_step(lo: np.ndarray, hi: np.ndarray, camera: Camera, height: int, quality: float,
              resolution: int | None) -> float:
    """The mesh lattice's cell: ``resolution`` cells along the longest side of [lo, hi] when
    given, else MESH_CELLS_PER_FOOTPRINT * ``quality`` cells per pixel footprint at the box
    centre (at most MAX_CELLS cells along the longest side)."""
    if resolution is not None:
        return cell_size(lo, hi, resolution)
    dist = max(float(np.linalg.norm((lo + hi) / 2 - camera.eye)), 1e-9)
    footprint = float(camera.footprint(dist, height))
    return max(footprint / (MESH_CELLS_PER_FOOTPRINT * quality), float((hi - lo).max()) / MAX_CELLS)


def choose_geometry(geometry: str, scene: Node, lo: np.ndarray, hi: np.ndarray, step: float) -> tuple[str, str]:
    """(the geometry to use, why): "auto" meshes a bounded scene whose lattice has at most
    AUTO_MAX_CELLS cells along its longest side, and samples the grid otherwise (an
    unbounded field, whose mesh would close where the box cuts it, or a mesh too fine)."""
    if geometry != "auto":
        return geometry, "asked for"
    slo, shi = scene.bounds
    if not (np.all(np.isfinite(slo)) and np.all(np.isfinite(shi))):
        return "grid", "unbounded scene: a mesh would close where the box cuts it"
    cells = math.ceil(float((hi - lo).max()) / step)
    if cells > AUTO_MAX_CELLS:
        return "grid", f"a mesh lattice of {cells} cells along the longest side is over {AUTO_MAX_CELLS}"
    return "mesh", "bounded scene: the mesh is exact at its vertices and keeps features down to a lattice cell"


class VertexAttributes:
    """The texture factories :func:`sdfgl.pbr.materials.bsdf` takes, as per-vertex attributes of
    ``mesh``: the scene's colour, its node materials' roughness and metallic, Blend weights."""

    def __init__(self, scene: Node, mesh: Mesh, origin: np.ndarray) -> None:
        self.scene, self.mesh, self.origin = scene, mesh, origin
        self.values: dict[str, np.ndarray] = {}

    def _texture(self, name: str, values: np.ndarray) -> dict:
        self.values[name] = np.ascontiguousarray(values, np.float32)
        return {"type": "mesh_attribute", "name": name}

    def albedo(self) -> dict:
        """The scene's colour at the vertices (the mesh export's colours)."""
        if "vertex_color" in self.values:
            return {"type": "mesh_attribute", "name": "vertex_color"}
        return self._texture("vertex_color", np.clip(np.nan_to_num(self.mesh.colors), 0.0, 1.0))

    def weight(self, boundary: Node, width: float) -> dict:
        """A Blend's weight at the vertices, one attribute per Blend."""
        f = evaluate(boundary, self.mesh.vertices, origin=self.origin)
        return self._texture(f"vertex_blend{sum(k.startswith('vertex_blend') for k in self.values)}",
                             blend_weight(f, width))

    def surface(self) -> tuple[dict, dict, float]:
        """Roughness and metallic attributes and the specular weight from mapSurface() at the vertices."""
        sf = evaluate_channel(self.scene, self.mesh.vertices, "surface", origin=self.origin)[:, :3]
        rough, metal, spec = surface_terms(sf)
        return self._texture("vertex_roughness", rough), self._texture("vertex_metallic", metal), spec


def export(scene: Node, bounds: object, step: float) -> Mesh:
    """The scene's mesh at lattice cell ``step``, cut by ``bounds`` when given."""
    box = None if bounds is None else tuple(np.asarray(b, np.float64).reshape(3) for b in bounds)  # type: ignore[union-attr]
    m = export_mesh(scene, step=step, bounds=box, mode="sharp", colors=True, progress=False)
    if len(m.faces) == 0:
        raise ParameterError(f"pbr: {scene.label()} has no surface to mesh at step {step:g}")
    return m


def emitted_groups(scene: Node, mesh: Mesh, origin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(group of each face: -1 where it does not emit, distinct colours (G, 3)): faces grouped by
    the mean emission of their vertices (mapEmission()), rounded to 1e-4."""
    if "emission" not in material_channels(scene):
        return np.full(len(mesh.faces), -1), np.zeros((0, 3))
    e = np.nan_to_num(evaluate_channel(scene, mesh.vertices, "emission", origin=origin)[:, :3].astype(np.float64))
    face = np.round(np.maximum(e[mesh.faces].mean(axis=1), 0.0), 4)
    lit = face.max(axis=1) > 0
    colours, inverse = np.unique(face[lit], axis=0, return_inverse=True)
    if len(colours) > MAX_EMITTED_COLOURS:
        raise ParameterError(f"pbr: the mesh path renders at most {MAX_EMITTED_COLOURS} distinct emitted colours "
                             f"(one area emitter each); {scene.label()} emits {len(colours)} over its surface")
    group = np.full(len(mesh.faces), -1)
    group[lit] = inverse.reshape(-1)
    return group, colours


def _mitsuba_mesh(mi: Any, name: str, verts: np.ndarray, faces: np.ndarray, attributes: dict[str, np.ndarray],
                  bsdf: Any, emitter: Any = None) -> Any:
    """An in-memory ``mi.Mesh`` of the faces' vertices, with those vertices' attributes."""
    used, local = np.unique(faces, return_inverse=True)
    props = mi.Properties()
    props["bsdf"] = bsdf
    if emitter is not None:
        props["emitter"] = emitter
    out = mi.Mesh(name, len(used), len(faces), props=props)
    params = mi.traverse(out)
    params["vertex_positions"] = np.ascontiguousarray(verts[used], np.float32).ravel()
    params["faces"] = local.reshape(-1).astype(np.uint32)
    params.update()
    for key, values in attributes.items():
        v = values[used]
        out.add_attribute(key, 1 if v.ndim == 1 else v.shape[1], v.ravel())
    return out


def mesh_shapes(mi: Any, mesh: Mesh, attributes: dict[str, np.ndarray], bsdf: dict, groups: np.ndarray,
                colours: np.ndarray, offset: np.ndarray) -> dict[str, Any]:
    """The Mitsuba shapes by name: ``sdf_mesh`` (the faces that do not emit) and
    ``sdf_emitter_0``, ... (one area emitter per emitted colour), all with ``bsdf``."""
    verts = mesh.vertices - offset
    loaded = mi.load_dict(bsdf)
    out: dict[str, Any] = {}
    dark = groups < 0
    if dark.any():
        out["sdf_mesh"] = _mitsuba_mesh(mi, "sdf_mesh", verts, mesh.faces[dark], attributes, loaded)
    for g, rgb in enumerate(colours):
        emitter = mi.load_dict({"type": "area", "radiance": {"type": "rgb", "value": [float(c) for c in rgb]}})
        out[f"sdf_emitter_{g}"] = _mitsuba_mesh(mi, f"sdf_emitter_{g}", verts, mesh.faces[groups == g], attributes,
                                                loaded, emitter)
    return out
