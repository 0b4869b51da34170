"""Named parts of a print, each with its materials: what the multi-part writers consume.

A :class:`Part` is a name, a triangle mesh and a palette with one material index per
triangle (the scene's colours, quantised by :func:`materials`).
:func:`parts_of` turns ``{"body": node_or_mesh, ...}`` into parts, meshing nodes with the
options given.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from ..errors import ParameterError, SdfglError
from ..nodes.base import Node

MAX_MATERIALS = 256
"""The most materials one part gets (colours are quantised more coarsely past it)."""


@dataclass
class Part:
    """One named part: ``vertices`` (N, 3), ``faces`` (M, 3), ``palette`` (K, 3) linear RGB and
    ``material`` (M,) the palette index of each face."""

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    palette: np.ndarray
    material: np.ndarray

    def split(self) -> list[tuple[str, np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
        """(name, vertices, faces, normals, colour) per material of the part, vertices
        renumbered; the name is the part's when it has one material, else ``name.k``."""
        out = []
        for k, rgb in enumerate(self.palette):
            faces = self.faces[self.material == k]
            if len(faces) == 0:
                continue
            used, inverse = np.unique(faces, return_inverse=True)
            name = self.name if len(self.palette) == 1 else f"{self.name}.{k}"
            out.append((name, self.vertices[used], inverse.reshape(-1, 3), self.normals[used], rgb))
        return out


def materials(colors: np.ndarray | None, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(palette (K, 3), material index per face): face colours (the mean of their vertices')
    rounded to 8 bits per channel, coarser if needed to keep at most MAX_MATERIALS."""
    if colors is None:
        return np.array([[0.7, 0.68, 0.64]]), np.zeros(len(faces), np.int64)
    fc = colors[faces].mean(axis=1)
    levels = 255
    while True:
        q = np.round(fc * levels).astype(np.int64)
        palette, index = np.unique(q, axis=0, return_inverse=True)
        if len(palette) <= MAX_MATERIALS or levels <= 3:
            return palette / levels, index.ravel()
        levels //= 2


def part_of(name: str, mesh: Any) -> Part:
    """The part ``name`` of a :class:`~sdfgl.mesh.result.Mesh`."""
    palette, index = materials(mesh.colors, mesh.faces)
    return Part(name, mesh.vertices, mesh.faces, mesh.normals, palette, index)


def parts_of(parts: Mapping[str, Any], **mesh_options: Any) -> list[Part]:
    """Parts from ``{name: node or Mesh}``; nodes are meshed with ``sg.mesh(node, **mesh_options)``."""
    from .build import mesh
    from .result import Mesh
    if not isinstance(parts, Mapping) or not parts:
        raise ParameterError(f"parts must be a non-empty dict of name -> node or mesh, got {parts!r:.80}")
    out = []
    for name, value in parts.items():
        if not isinstance(name, str) or not name.strip():
            raise ParameterError(f"parts: a part's name must be a non-empty string, got {name!r}")
        if isinstance(value, Node):
            value = mesh(value, **mesh_options)
        elif not isinstance(value, Mesh):
            raise ParameterError(f"parts: part {name!r} must be an sdfgl node or mesh, got {type(value).__name__}")
        if len(value.faces) == 0:
            raise SdfglError(f"parts: part {name!r} is empty (no surface in its box)")
        out.append(part_of(name, value))
    return out
