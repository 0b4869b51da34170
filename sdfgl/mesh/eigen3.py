"""Eigen-decomposition of many symmetric 3x3 matrices at once, by cyclic Jacobi rotations.

numpy's batched ``eigh`` calls LAPACK once per matrix, and for 3x3 matrices that call's cost
is the whole cost: dual contouring solves one quadric per surface cell, tens of thousands a
mesh. Here every rotation is a few array operations over all matrices together, on the six
distinct entries kept as separate arrays. Jacobi's rotations are orthogonal, so the vectors
stay orthonormal and the values accurate to rounding (relative to the matrix's size) even
where eigenvalues coincide, which is the usual case for the quadric of a flat or edge cell;
cyclic sweeps converge quadratically, four or five for double precision.
"""
from __future__ import annotations

import numpy as np

MAX_SWEEPS = 10
PLANES = ((0, 1, 2), (0, 2, 1), (1, 2, 0))  # (p, q, the third index) of each rotation


def symmetric_eigen(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (n, 3), unsorted, and eigenvectors (n, 3, 3, in columns, matching them) of
    the symmetric matrices ``a`` (n, 3, 3): ``a[i] == v[i] @ diag(w[i]) @ v[i].T`` to rounding."""
    n = len(a)
    diag = [a[:, i, i].astype(np.float64) for i in range(3)]
    off = {(0, 1): a[:, 0, 1].astype(np.float64), (0, 2): a[:, 0, 2].astype(np.float64),
           (1, 2): a[:, 1, 2].astype(np.float64)}
    vec = [[np.full(n, float(i == j)) for j in range(3)] for i in range(3)]  # vec[row][column]
    small = (1e-15 * (np.abs(diag[0]) + np.abs(diag[1]) + np.abs(diag[2]))) ** 2
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        for _ in range(MAX_SWEEPS):
            if not np.any(off[0, 1] ** 2 + off[0, 2] ** 2 + off[1, 2] ** 2 > small):
                break
            for p, q, r in PLANES:
                apq = off[p, q]
                live = apq != 0
                theta = (diag[q] - diag[p]) / np.where(live, 2 * apq, 1.0)
                # the smaller rotation angle's tangent; 0 where apq is negligible (theta overflows)
                t = np.where(live, np.copysign(1.0, theta) / (np.abs(theta) + np.sqrt(theta * theta + 1)), 0.0)
                t = np.where(np.isfinite(t), t, 0.0)
                c = 1 / np.sqrt(t * t + 1)
                s = t * c
                diag[p] = diag[p] - t * apq
                diag[q] = diag[q] + t * apq
                off[p, q] = np.zeros(n)
                rp, rq = (min(r, p), max(r, p)), (min(r, q), max(r, q))
                arp, arq = off[rp], off[rq]
                off[rp], off[rq] = c * arp - s * arq, s * arp + c * arq
                for row in vec:
                    vp, vq = row[p], row[q]
                    row[p], row[q] = c * vp - s * vq, s * vp + c * vq
    return np.stack(diag, 1), np.stack([np.stack(row, 1) for row in vec], 1)
