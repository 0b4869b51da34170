"""How far a mesh's volume is off the solid's, estimated from the field on its triangles.

A triangle with its corners on the surface cuts a chord under a curved surface (or skips a
feature the lattice resolved only partly). The gap between the triangle and the surface is,
to second order, a quadratic over the triangle that is zero at its corners; its mean is the
mean of its values at the three edge midpoints. The field divided by its gradient's length
gives that gap at a midpoint (a distance even where the field is only a bound or warped), so
the mesh's volume error is sum(area x mean midpoint gap), relative to the mesh's volume. It
tracks the error against the twin's integral to 10-30 % on the zoo (docs/notes/session5).
"""
from __future__ import annotations

import numpy as np

from .sample import GPUField


SAMPLED_FACES = 12000  # faces the estimate looks at (a fixed random subset of larger meshes)


def volume_error(field: GPUField, verts: np.ndarray, faces: np.ndarray, step: float) -> float:
    """Estimated (mesh volume - solid volume) / mesh volume; 0 for an empty mesh.

    Larger meshes are estimated from SAMPLED_FACES faces drawn at random (seeded: the same mesh
    gives the same figure), scaled by the share of faces they are. A gap is clipped to one cell
    (a field whose gradient vanishes there says nothing about distance)."""
    if len(faces) == 0:
        return 0.0
    x, y, z = (np.ascontiguousarray(verts[:, i])[faces] for i in range(3))  # divergence theorem along z
    volume = np.sum(((x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (y[:, 1] - y[:, 0]) * (x[:, 2] - x[:, 0]))
                    * z.sum(axis=1)) / 6.0
    if volume <= 0:
        return 0.0
    pick = np.arange(len(faces))
    if len(faces) > SAMPLED_FACES:
        pick = np.random.default_rng(0).integers(0, len(faces), SAMPLED_FACES)
    v = verts[faces[pick]]
    area = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    mids = (v + np.roll(v, -1, axis=1)) / 2  # (F, 3 edges, 3)
    # one Newton step from a midpoint moves it by -f grad / |grad|^2: its length is the gap
    # (the projection's program, which the mesh has compiled already)
    move, normal = field.project(mids.reshape(-1, 3), 0.05 * step, 0.0, step, 1)
    gap = -np.einsum("ij,ij->i", move, normal).reshape(-1, 3).mean(axis=1)
    # a point outside the solid (gap > 0) under a triangle is mesh volume the solid lacks
    return float(np.sum(area * gap) * (len(faces) / len(pick)) / volume)
