"""Crossing planes for dual contouring where a crossing lies on a crease of the field.

A crossing closer to an edge of the solid (a box edge, a CSG cut) than the gradient stencil is
wide gets a gradient that mixes the two sides and is neither face's normal; its plane would
pull its cells' vertices off the edge or corner by a good part of a cell. The stencil's bend
(mean of its samples minus the value, shaders/stages/mesh_clip.glsl) tells such crossings. Each is
given instead the gradients sampled a little way off it on the four stencil directions, those
whose own stencil is clear of the crease: the faces' normals (or, outside a convex edge, a
blend of them, whose plane through the crossing still holds the edge line). Their planes pass
through the crossing, which lies on the crease to within the stencil's width.
"""
from __future__ import annotations

import numpy as np

from .sample import GPUField

KINK = 0.02   # |bend| above this share of eps |grad|: the stencil straddles a crease
OFF = 5.0     # side samples this many stencil widths off the crossing
DROPPED = 1e-3  # weight of a crease crossing's own plane when a side sample is clear (below the
#                 quadric solver's singular-value cut: it only counts where nothing else does)
TETRA = np.array([(1, -1, -1), (-1, -1, 1), (-1, 1, -1), (1, 1, 1)], np.float64)


def bent(grad: np.ndarray, bend: np.ndarray, eps: float) -> np.ndarray:
    """Mask of gradients whose stencil (``eps`` wide) straddles a crease."""
    return np.abs(bend) > KINK * eps * np.linalg.norm(grad, axis=1)


def planes(field: GPUField, points: np.ndarray, grad: np.ndarray, bend: np.ndarray,
           eps: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Planes for the quadrics: (crossing of each plane (P,), unit normal (P, 3), weight (P,)).

    One plane per crossing (its gradient, weight 1), and for each crease crossing up to four
    more from side samples clear of the crease (weights sharing 1; the crossing's own plane
    then keeps ``DROPPED``)."""
    n = len(points)
    normal = grad / np.maximum(np.linalg.norm(grad, axis=1, keepdims=True), 1e-30)
    weight = np.ones(n)
    crease = np.nonzero(bent(grad, bend, eps))[0]
    if len(crease) == 0:
        return np.arange(n), normal, weight
    side = (points[crease, None, :] + OFF * eps * TETRA).reshape(-1, 3)
    _, g, b = field.gradient_bend(side, eps)
    clear = ~bent(g, b, eps) & (np.linalg.norm(g, axis=1) > 0)
    owner = np.repeat(crease, 4)[clear]
    count = np.bincount(owner, minlength=n)
    weight[count > 0] = DROPPED
    g = g[clear]
    return (np.concatenate([np.arange(n), owner]),
            np.concatenate([normal, g / np.linalg.norm(g, axis=1, keepdims=True)]),
            np.concatenate([weight, 1.0 / count[owner]]))
