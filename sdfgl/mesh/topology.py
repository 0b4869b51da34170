"""Mesh hygiene: degenerate and duplicate faces out, unused vertices dropped."""
from __future__ import annotations

import numpy as np


def clean(verts: np.ndarray, faces: np.ndarray, normals: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Drop faces that repeat a vertex or repeat another face, then vertices no face uses."""
    f = np.asarray(faces, np.int64).reshape(-1, 3)
    f = f[(f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])]
    if len(f):
        a, b, c = f[:, 0], f[:, 1], f[:, 2]
        lo, hi = np.minimum(a, np.minimum(b, c)), np.maximum(a, np.maximum(b, c))
        n = max(len(verts), 1)
        if n < 2 ** 21:  # one int64 key per face
            _, first = np.unique((lo * n + (a + b + c - lo - hi)) * n + hi, return_index=True)
        else:
            _, first = np.unique(np.sort(f, axis=1), axis=0, return_index=True)
        if len(first) < len(f):
            f = f[np.sort(first)]
    used = np.zeros(len(verts), bool)
    used[f.ravel()] = True
    remap = np.cumsum(used) - 1
    return verts[used], remap[f], normals[used]


def edge_use(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(number of faces on each undirected edge, number of directed edges used twice)."""
    e = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    _, counts = np.unique(np.sort(e, axis=1), axis=0, return_counts=True)
    _, dcounts = np.unique(e, axis=0, return_counts=True)
    return counts, int(np.sum(dcounts > 1))
