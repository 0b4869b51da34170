"""Mesh nodes (``sg.load_mesh`` / ``sg.from_mesh``) in scene documents.

A node read from a file is saved as a reference to the file: its path (relative to the
document's folder when the file lies in it or below, else absolute), the SHA-256 of its
bytes and the scale and units it was loaded with. Loading reads the file again (only files
with a mesh format's suffix, through trimesh's loaders, which run no code) and refuses a
file whose SHA-256 differs. A node built from an in-memory mesh has no file, so its
triangles are saved in the document: base64 of little-endian float64 vertices and int32
faces, up to :data:`~sdfgl.scene_io.limits.MAX_INLINE_TRIANGLES` triangles. float64 keeps
the round trip exact (the same vertices give the same GPU tables, twin and shader source).
"""
from __future__ import annotations

import base64
import binascii
import os
from pathlib import Path
from typing import Any, Callable

import numpy as np

from ..errors import ParameterError, SceneDocumentError, SdfglError
from .limits import MAX_INLINE_TRIANGLES

KIND = "mesh"
FILE_KEYS = ("name", "file", "sha256", "scale", "units", "scene_units")
INLINE_KEYS = ("name", "vertices", "faces")
PARAMETERS = ("`name` (default: the file, or `'mesh'`); `file`, `sha256`, `scale` = `1.0`, `units` = `None`, `scene_units` = `'mm'` "
              "(a file) or `vertices`, `faces` (base64, inline)")
"""The document keys of a mesh node, for the node-kind table of docs/scene-format.md."""

_VERTEX, _FACE = np.dtype("<f8"), np.dtype("<i4")


def encode_mesh(node: Any, base: Path | None) -> dict[str, Any]:
    """The document object of mesh node ``node``; file paths inside folder ``base`` (the
    document's) are written relative to it."""
    src = node.source
    if src is not None:
        return {"kind": KIND, "name": node.name, "file": _relative(Path(src.path), base), "sha256": src.sha256,
                "scale": src.scale, "units": src.units, "scene_units": src.scene_units}
    if len(node.faces) > MAX_INLINE_TRIANGLES:
        raise ParameterError(f"{node.label()}: a mesh without a file is saved with its triangles in the document, "
                             f"up to {MAX_INLINE_TRIANGLES} triangles; write it to a file (mesh.export('part.stl')) "
                             f"and build the node with sg.load_mesh, which saves a reference to the file")
    return {"kind": KIND, "name": node.name,
            "vertices": _b64(node.vertices.astype(_VERTEX)), "faces": _b64(node.faces.astype(_FACE))}


def decode_mesh(obj: dict[str, Any], path: str, base: Path | None,
                fail: Callable[[str, str], SceneDocumentError]) -> Any:
    """The mesh node of document object ``obj`` (found at JSON ``path``); a relative file is
    looked for in ``base`` (the document's folder; None: the working directory)."""
    from ..nodes.mesh_field import MeshField
    inline = "vertices" in obj or "faces" in obj
    keys, required = (INLINE_KEYS, ("vertices", "faces")) if inline else (FILE_KEYS, ("file",))
    for k in obj:
        if k != "kind" and k not in keys:
            raise fail(f"{path}.{k}", f"unknown key of a mesh node with {'inline triangles' if inline else 'a file'}; "
                                      f"known: {', '.join(keys)}")
    for k in required:
        if k not in obj:
            raise fail(f"{path}.{k}", "missing")
    name = _string(obj.get("name", "mesh" if inline else obj["file"]), f"{path}.name", fail)
    try:
        if inline:
            verts = _array(obj["vertices"], _VERTEX, f"{path}.vertices", fail)
            faces = _array(obj["faces"], _FACE, f"{path}.faces", fail)
            if len(faces) > MAX_INLINE_TRIANGLES:
                raise fail(f"{path}.faces", f"{len(faces)} triangles (limit {MAX_INLINE_TRIANGLES} inline)")
            return MeshField(verts, faces, name=name)
        return _from_file(obj, name, path, base, fail)
    except SceneDocumentError:
        raise
    except SdfglError as exc:
        raise fail(path, str(exc)) from None


def _from_file(obj: dict[str, Any], name: str, path: str, base: Path | None,
               fail: Callable[[str, str], SceneDocumentError]) -> Any:
    from ..meshin.load import load_mesh
    from ..meshin.source import file_sha256, mesh_file
    where = f"{path}.file"
    given = _string(obj["file"], where, fail)
    file = Path(given) if os.path.isabs(given) else (base or Path.cwd()) / given
    try:
        file = mesh_file(file)
    except SdfglError as exc:
        raise fail(where, str(exc)) from None
    want = obj.get("sha256")
    if want is not None:
        want = _string(want, f"{path}.sha256", fail).lower()
        got = file_sha256(file)
        if got != want:
            raise fail(where, f"mesh file '{file}' has changed since the document was saved (SHA-256 {got[:12]}..., "
                              f"the document records {want[:12]}...); save the scene again to accept the new file")
    scale = obj.get("scale", 1.0)
    if isinstance(scale, bool) or not isinstance(scale, (int, float)):
        raise fail(f"{path}.scale", f"expected a number, got {type(scale).__name__}")
    units = obj.get("units")
    if units is not None:
        units = _string(units, f"{path}.units", fail)
    scene_units = _string(obj.get("scene_units", "mm"), f"{path}.scene_units", fail)
    try:
        return load_mesh(file, scale=scale, units=units, scene_units=scene_units, name=name)
    except SdfglError as exc:
        raise fail(where, str(exc)) from None


def _relative(file: Path, base: Path | None) -> str:
    """``file`` relative to ``base`` (POSIX separators) when it lies in it, else absolute."""
    if base is not None:
        try:
            return file.relative_to(Path(os.path.abspath(base))).as_posix()
        except ValueError:
            pass
    return str(file)


def _b64(a: np.ndarray) -> str:
    return base64.b64encode(np.ascontiguousarray(a).tobytes()).decode("ascii")


def _string(v: Any, path: str, fail: Callable[[str, str], SceneDocumentError]) -> str:
    if not isinstance(v, str):
        raise fail(path, f"expected a string, got {type(v).__name__}")
    return v


def _array(v: Any, dtype: np.dtype, path: str, fail: Callable[[str, str], SceneDocumentError]) -> np.ndarray:
    """An (n, 3) array from its base64 text."""
    text = _string(v, path, fail)
    try:
        raw = base64.b64decode(text, validate=True)
    except (binascii.Error, ValueError):
        raise fail(path, "expected base64 text") from None
    row = 3 * dtype.itemsize
    if len(raw) % row:
        raise fail(path, f"{len(raw)} bytes is not a whole number of {row}-byte rows ({dtype.name} x 3)")
    return np.frombuffer(raw, dtype=dtype).reshape(-1, 3)
