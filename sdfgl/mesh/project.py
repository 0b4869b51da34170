"""Vertices moved onto the surface with the field and its gradient (Newton steps along it)."""
from __future__ import annotations

import numpy as np

from .sample import GPUField

TOLERANCE = 1e-3  # stop when every |f| at a vertex is below this share of a cell


def project(field: GPUField, verts: np.ndarray, step: float,
            iterations: int = 4) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(vertices on the surface, unit outward normals there, |field| there).

    Each step moves a vertex by -f grad / |grad|^2, at most half a cell, so a vertex near a
    thin wall or a crease stays on its own side of it. All steps run in one GPU draw
    (GPUField.project).
    """
    move, normals, values = field.project(verts, 0.05 * step, TOLERANCE * step, 0.5 * step, iterations)
    return np.asarray(verts, np.float64) + move, normals, np.abs(values)
