"""Reading a mesh file (through trimesh) into a :class:`~sdfgl.nodes.mesh_field.MeshField`."""
from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import MeshError
from ..extras import require_extra
from ..nodes.mesh_field import MAX_TRIANGLES, MeshField
from ..values import validate as v
from ..values.units import MILLIMETRES, unit_name
from .source import MeshFile, file_sha256, mesh_file


def _factor(scale: float, units: str | None, scene_units: str, where: str) -> float:
    """The factor from the file's numbers to scene units."""
    s = float(v.scalar(where, "scale", scale, positive=True))
    if units is None:
        return s
    file_unit = MILLIMETRES[unit_name(units, f"{where}: units")]
    return s * file_unit / MILLIMETRES[unit_name(scene_units, f"{where}: scene_units")]


def load_mesh(path: str | os.PathLike, scale: float = 1.0, units: str | None = None,
              scene_units: str = "mm", name: str | None = None) -> MeshField:
    """The exact signed distance to the closed mesh in the file at ``path``.

    Args:
        path: an STL, OBJ, PLY, GLB/glTF, 3MF or OFF file (all its meshes together).
        scale: a factor applied to the vertices (after the unit conversion).
        units: the file's length unit ("mm", "cm", "inch", "m", ...); None: its numbers are
            taken as scene units.
        scene_units: what one scene unit is, when ``units`` is given (default "mm", the
            unit :meth:`Node.save` writes 3MF in).
        name: what errors and the shader's comments call the mesh (default: ``path``).

    The node remembers the file (its absolute path and SHA-256), so a scene document saves
    it as a reference to the file (docs/scene-format.md). Duplicate vertices are merged, faces wound inward are turned and small holes (a
    missing triangle or quad) are filled. A mesh that stays open, is not a manifold, has
    non-finite vertices, no triangles or more than
    :data:`~sdfgl.nodes.mesh_field.MAX_TRIANGLES` raises :class:`~sdfgl.errors.MeshError`
    naming the file.

    Example:
        >>> import os, tempfile, trimesh
        >>> path = os.path.join(tempfile.mkdtemp(), "ball.stl")
        >>> _ = trimesh.creation.icosphere().export(path)
        >>> sg.load_mesh(path, units="cm").bounds[1].round(1)  # a unit sphere in cm, in mm
        array([10., 10., 10.])
    """
    given = os.fspath(v.file_path("load_mesh", "path", path))
    require_extra("meshin", "trimesh", purpose="sg.load_mesh")
    import trimesh
    if not Path(given).is_file():
        raise MeshError(f"mesh file '{given}': no such file")
    file = mesh_file(given)
    digest = file_sha256(file)
    try:
        loaded = trimesh.load(str(file), file_type=file.suffix.lower()[1:], force="mesh", process=False)
    except Exception as exc:  # trimesh's loaders raise many kinds of error for a bad file
        raise MeshError(f"mesh file '{given}': cannot be read ({type(exc).__name__}: {exc})") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise MeshError(f"mesh file '{given}': holds no triangles")
    source = MeshFile(str(file), digest, float(v.scalar(f"mesh '{given}'", "scale", scale, positive=True)), units,
                      scene_units)
    return _field(loaded, scale, units, scene_units, given if name is None else name, source)


def from_mesh(mesh: Any, scale: float = 1.0, units: str | None = None, scene_units: str = "mm",
              name: str = "mesh") -> MeshField:
    """The exact signed distance to a closed ``trimesh.Trimesh``, repaired as in
    :func:`load_mesh` (``mesh`` itself is not changed).

    Args:
        mesh: the triangle mesh (``trimesh.Trimesh``).
        scale: a factor applied to the vertices (after the unit conversion).
        units: the mesh's length unit ("mm", "cm", "inch", ...); None: its numbers are
            taken as scene units.
        scene_units: what one scene unit is, when ``units`` is given (default "mm").
        name: what errors call the mesh.

    Example:
        >>> import trimesh
        >>> sg.from_mesh(trimesh.creation.icosphere()).exactness
        'exact'
    """
    require_extra("meshin", "trimesh", purpose="sg.from_mesh")
    return _field(mesh, scale, units, scene_units, name, None)


def _field(mesh: Any, scale: float, units: str | None, scene_units: str, name: str,
           source: MeshFile | None) -> MeshField:
    """The repaired mesh's node (see :func:`from_mesh`), remembering its file ``source``."""
    import trimesh
    if not isinstance(mesh, trimesh.Trimesh):
        raise MeshError(f"mesh '{name}': from_mesh needs a trimesh.Trimesh, got {type(mesh).__name__}")
    factor = _factor(scale, units, scene_units, f"mesh '{name}'")
    verts = np.asarray(mesh.vertices, dtype=np.float64)
    faces = np.asarray(mesh.faces)
    if len(faces) == 0:
        raise MeshError(f"mesh '{name}': has no triangles")
    if len(faces) > MAX_TRIANGLES:
        raise MeshError(f"mesh '{name}': has {len(faces)} triangles, over the limit of {MAX_TRIANGLES}; "
                        f"simplify it first (e.g. trimesh's simplify_quadric_decimation)")
    bad = ~np.isfinite(verts).all(axis=1)
    if bad.any():
        raise MeshError(f"mesh '{name}': {int(bad.sum())} vertices are not finite (NaN or inf), e.g. vertex "
                        f"{int(np.flatnonzero(bad)[0])}")
    tm = trimesh.Trimesh(verts * factor, faces, process=True, validate=False)
    if not tm.is_watertight:
        tm.fill_holes()
    trimesh.repair.fix_winding(tm)
    return MeshField(tm.vertices, tm.faces, name=name, source=source)
