"""The batched symmetric 3x3 eigensolver that dual contouring's vertex placement uses."""
import numpy as np

from sdfgl.mesh.eigen3 import symmetric_eigen


def quadrics(rng: np.random.Generator, n: int) -> np.ndarray:
    """Sums of n n^T over a few unit normals: full rank, edges (two directions, some equal
    weights), flat cells (one direction, nearly repeated), zeros, and wide scales."""
    normals = rng.normal(size=(n, 6, 3))
    normals /= np.linalg.norm(normals, axis=2, keepdims=True)
    k = n // 6
    normals[:k] = normals[:k, :1] + 1e-4 * rng.normal(size=(k, 6, 3))   # flat, nearly rank 1
    normals[k:2 * k, 3:] = normals[k:2 * k, :1]                         # rank 2
    normals[2 * k:3 * k, :, 2] = 0.0                                    # rank 2, equal axes possible
    normals[2 * k:3 * k, :3] = (1, 0, 0)
    normals[2 * k:3 * k, 3:] = (0, 1, 0)                                # two equal eigenvalues
    a = np.einsum("mki,mkj->mij", normals, normals)
    a[3 * k:3 * k + 10] = 0.0                                           # no crossings' planes
    a[4 * k:5 * k] *= 1e-12                                             # tiny and huge scales
    a[5 * k:] *= 1e9
    return a


def test_eigen_decomposition_rebuilds_the_matrices_and_matches_lapack():
    a = quadrics(np.random.default_rng(3), 6000)
    w, v = symmetric_eigen(a)
    scale = np.abs(a).reshape(len(a), -1).max(axis=1) + 1e-300
    rebuilt = np.einsum("mik,mk,mjk->mij", v, w, v)
    assert np.all(np.abs(rebuilt - a).reshape(len(a), -1).max(axis=1) <= 1e-13 * scale + 1e-300)
    assert np.abs(np.einsum("mki,mkj->mij", v, v) - np.eye(3)).max() < 1e-13
    ref = np.linalg.eigvalsh(a)
    assert np.all(np.abs(np.sort(w, axis=1) - ref).max(axis=1) <= 1e-13 * scale + 1e-300)


def test_pseudo_inverse_with_small_values_cut_equals_lapacks():
    """What dual contouring takes from the decomposition: the pseudo-inverse with eigenvalues
    below 3 % of the largest cut, which is well defined even where the vectors are not."""
    a = quadrics(np.random.default_rng(4), 3000)

    def pinv(w: np.ndarray, v: np.ndarray) -> np.ndarray:
        w = np.abs(w)
        keep = w > 0.03 * w.max(axis=1, keepdims=True)
        inv = np.where(keep, 1.0 / np.where(w > 0, w, 1.0), 0.0)
        return np.einsum("mik,mk,mjk->mij", v, inv, v)

    mine, ref = pinv(*symmetric_eigen(a)), pinv(*np.linalg.eigh(a))
    size = np.abs(ref).reshape(len(a), -1).max(axis=1) + 1e-300
    assert np.all(np.abs(mine - ref).reshape(len(a), -1).max(axis=1) <= 1e-10 * size)
