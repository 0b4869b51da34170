"""How a grid union's record stores an instance's move (sdfgl.compiler.data.grid).

Reading data is what a packed primitive costs on llvmpipe (each texel is a texelFetch;
on the 5000-primitive benchmark scene the fetches were most of the frame), so a record
holds as few floats as the move needs:

- ``"translate"``: the translation (3 floats). Also used for centred spheres under
  rotations, whose field a rotation does not change.
- ``"quat"``: a unit quaternion of the inverse rotation and the translation (7 floats,
  two texels): p_local = rotate(q, p - t) / s, two cross products in the shader.
- ``"matrix"``: the 3x4 inverse transform (12 floats, three texels), kept for types with
  a reflected member (an orthonormal matrix of determinant -1 has no quaternion).

The uniform scale s, when a type has one, sits after the move (``InstanceType.layout``).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...nodes.primitives import Sphere

if TYPE_CHECKING:  # pragma: no cover
    from .instances import InstanceType


def kind(t: "InstanceType", rotations: np.ndarray | None) -> str:
    """The move layout of type ``t`` given its members' rotations ((n, 3, 3); None where
    the type has neither turned nor scaled members)."""
    if not t.affine or (isinstance(t.inner, Sphere) and not t.scaled and not np.any(t.inner.c)):
        return "translate"
    return "matrix" if float(np.linalg.det(rotations).min()) < 0 else "quat"


def floats(move: str) -> int:
    """Floats a record spends on a move of this layout."""
    return {"translate": 3, "quat": 7, "matrix": 12}[move]


def quaternions(m: np.ndarray) -> np.ndarray:
    """(n, 4) unit quaternions (x, y, z, w) of (n, 3, 3) proper rotations (Shepperd's method:
    the largest of the four squared components is computed directly, so none is lost)."""
    tr = np.trace(m, axis1=1, axis2=2)
    diag = np.stack([m[:, 0, 0], m[:, 1, 1], m[:, 2, 2], tr], axis=1)
    big = diag.argmax(axis=1)
    q = np.zeros((len(m), 4))
    for i in range(3):  # the x, y or z component is the largest
        sel = big == i
        j, k = (i + 1) % 3, (i + 2) % 3
        r = np.sqrt(np.maximum(1.0 + 2.0 * m[sel, i, i] - tr[sel], 1e-300))
        q[sel, i] = 0.5 * r
        q[sel, j] = 0.5 * (m[sel, j, i] + m[sel, i, j]) / r
        q[sel, k] = 0.5 * (m[sel, k, i] + m[sel, i, k]) / r
        q[sel, 3] = 0.5 * (m[sel, k, j] - m[sel, j, k]) / r
    sel = big == 3
    r = np.sqrt(1.0 + tr[sel])
    q[sel, 3] = 0.5 * r
    q[sel, 0] = 0.5 * (m[sel, 2, 1] - m[sel, 1, 2]) / r
    q[sel, 1] = 0.5 * (m[sel, 0, 2] - m[sel, 2, 0]) / r
    q[sel, 2] = 0.5 * (m[sel, 1, 0] - m[sel, 0, 1]) / r
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def encode(move: str, tr: np.ndarray, rot: np.ndarray | None, scale: np.ndarray) -> np.ndarray:
    """(n, floats(move)): the records' move floats for world = tr + scale * rot @ local."""
    if move == "translate":
        return tr
    if move == "quat":
        return np.concatenate([quaternions(rot.transpose(0, 2, 1)), tr], axis=1)
    a = rot.transpose(0, 2, 1) / scale[:, None, None]
    b = -np.einsum("nij,nj->ni", a, tr)
    return np.concatenate([a, b[:, :, None]], axis=2).reshape(-1, 12)


def glsl(move: str, scale: str | None) -> str:
    """The shader line that sets ``q``, the point in the instance's frame, from the record's
    texels d0, d1, d2 (``scale``: the GLSL of the member's scale, None if unscaled)."""
    if move == "translate":
        return "        vec3 q = p - d0.xyz;"
    if move == "quat":
        div = f" / {scale}" if scale is not None else ""
        return ("        vec3 q = p - d1.xyz;\n"
                f"        q = (q + 2.0 * cross(d0.xyz, cross(d0.xyz, q) + d0.w * q)){div};")
    return "        vec3 q = vec3(dot(d0.xyz, p) + d0.w, dot(d1.xyz, p) + d1.w, dot(d2.xyz, p) + d2.w);"
