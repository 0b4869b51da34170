"""Where a mesh node's triangles came from: the file, its SHA-256 and how it was scaled.

Scene documents (:mod:`sdfgl.scene_io.mesh_nodes`) save a file-backed mesh node as this
record and load it by reading the file again, after checking it has not changed.
"""
from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from pathlib import Path

from ..errors import MeshError

FORMATS = (".stl", ".obj", ".ply", ".glb", ".gltf", ".3mf", ".off")
"""File suffixes a mesh is read from (trimesh's loaders; none of them runs code)."""


@dataclass(frozen=True)
class MeshFile:
    """A mesh node's file: its absolute ``path``, the ``sha256`` of its bytes when it was
    read, and the ``scale``, ``units`` and ``scene_units`` it was loaded with."""

    path: str
    sha256: str
    scale: float
    units: str | None
    scene_units: str


def mesh_file(path: str | os.PathLike) -> Path:
    """``path`` as an absolute path, if it names an existing, non-empty file of a mesh format;
    else a MeshError naming the file."""
    file = Path(os.path.abspath(os.fspath(path)))
    if file.suffix.lower() not in FORMATS:
        raise MeshError(f"mesh file '{path}': unknown format {file.suffix!r}; use one of {', '.join(FORMATS)}")
    if not file.is_file():
        raise MeshError(f"mesh file '{path}': no such file")
    try:
        if file.stat().st_size == 0:
            raise MeshError(f"mesh file '{path}': is empty")
    except OSError as exc:
        raise MeshError(f"mesh file '{path}': cannot be read ({exc.strerror})") from None
    return file


def file_sha256(path: Path) -> str:
    """The SHA-256 of the file's bytes (hex), or a MeshError naming the file."""
    digest = hashlib.sha256()
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                digest.update(block)
    except OSError as exc:
        raise MeshError(f"mesh file '{path}': cannot be read ({exc.strerror})") from None
    return digest.hexdigest()
