"""Several named parts in one print file: ``sg.save_3mf`` and ``sg.save_parts``.

    sg.save_3mf({"body": body.material("white"), "inlay": inlay.material("red")}, "two.3mf")

Each part is meshed on its own (a node; or pass a ready :class:`~sdfgl.mesh.result.Mesh`)
and written as its own object with its colours as materials: in 3MF one object and one
base-material group per part, part k printed by extruder k + 1 in PrusaSlicer; in OBJ an
``o`` group per part with its materials in the .mtl; in glTF a node per part and colour.
The parts keep their places: model the inlay where it sits in the body (body minus inlay
for the body, so the two do not overlap).

From a Python scene file, define ``parts = {"body": ..., "inlay": ...}`` beside ``scene``:
``sdfgl mesh scene.py -o two.3mf --units mm`` then writes the parts instead of the scene.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

from ..errors import SdfglError
from ..values.validate import file_path
from .parts import parts_of
from .writers import write_parts


def save_parts(parts: Mapping[str, Any], path: str | Path, units: str | None = None, **mesh_options: Any) -> Path:
    """Write ``{name: node or Mesh}`` to one ``.3mf``, ``.obj``, ``.glb`` or ``.gltf`` file, one
    object per part with its colours as materials (see the module docstring).

    Args:
        parts: part names to nodes (meshed with ``sg.mesh(node, **mesh_options)``) or meshes.
        path: the file; its suffix picks the format.
        units: what one scene unit is in the 3MF model ("mm", "millimeter", "cm", "inch", ...;
            coordinates are not scaled; default millimetres). Only 3MF stores it.
        mesh_options: ``step``, ``resolution``, ``samples``, ``bounds``, ``mode`` as ``sg.mesh`` takes.

    Example:
        >>> import tempfile
        >>> out = tempfile.mkdtemp() + "/two.3mf"
        >>> sg.save_3mf({"cube": sg.box(1).material("white"),
        ...              "ball": sg.sphere(0.4).translate((1, 0, 0)).material("red")}, out, resolution=16).name
        'two.3mf'
    """
    return write_parts(parts_of(parts, **mesh_options), file_path("save_parts", "path", path), units)


def save_3mf(parts: Mapping[str, Any], path: str | Path, units: str | None = None, **mesh_options: Any) -> Path:
    """:func:`save_parts` to a ``.3mf`` file: one object per part with its colours as base
    materials, the model's unit, part k on extruder k + 1 for PrusaSlicer.

    Args:
        parts: part names to nodes or meshes.
        path: the ``.3mf`` file.
        units: what one scene unit is ("mm" by default, "cm", "inch", ...; not scaled).
        mesh_options: as ``sg.mesh`` takes them (``step``, ``resolution``, ``mode``, ...).

    Example:
        >>> import tempfile
        >>> out = sg.save_3mf({"plate": sg.box((20, 20, 2)).material("#2a6")},
        ...                   tempfile.mkdtemp() + "/plate.3mf", units="mm", resolution=16)
        >>> out.suffix
        '.3mf'
    """
    if file_path("save_3mf", "path", path).suffix.lower() != ".3mf":
        raise SdfglError(f"save_3mf: '{path}' does not end in .3mf (save_parts writes .obj, .glb and .gltf)")
    return save_parts(parts, path, units, **mesh_options)
