"""How far beyond its children's boxes a smooth n-ary fold can be solid.

A smooth minimum lowers min(a, b) by at most ``lower`` (k/4 for the quadratic blend, k/2 for
the chamfer, k for the circular one) and only where |a - b| < ``window`` (k, k, and
k / (1 - sqrt(1/2)) for the circular blend). Folding n children left to right, the running
value r never rises. At a point p let D be the least child value. Until r drops below D
every fold leaves r >= D; the fold that takes it below lowers it by at most ``lower``; after
that, a fold lowers r only if its child is below r + window < D + window. So the result is at
least D - (1 + N) lower, with N the children below D + window there, and never more than
n - 1 folds lower it. A point where the result is below t therefore has D < t + (1 + N) lower.

With every child's field at least its box distance / g (see ``level_factor``), the nearest
child's box is within g D of p and those N children's boxes within g (2 D + window) of the
nearest one's. And a fold never goes below D - window: every smooth minimum here is
non-decreasing in both arguments and equals min(a, b) once |a - b| >= window, so
smin(r, c) >= smin(D - window, D) = D - window whenever r >= D - window and c >= D. Growing
each child's box by g F, where F is the least fixed point of
F = t + min(min(1 + N(g (2 F + window)), n - 1) lower, window), covers every such point: a
metaball blend of many close spheres grows by up to the window, a blend of scattered parts by
little more than one fold's reach.
"""
from __future__ import annotations

import numpy as np

PAIRWISE_MAX = 1500  # up to this many children the box distances are counted exactly


def _neighbour_counts(lo: np.ndarray, hi: np.ndarray, reach: np.ndarray) -> np.ndarray:
    """For every box i, how many boxes (itself included) lie within reach[i] of it, or a
    superset of them (above PAIRWISE_MAX boxes, by their centres and half-diagonals)."""
    n = len(lo)
    if n <= PAIRWISE_MAX:
        gap = np.maximum(0.0, np.maximum(lo[None, :, :] - hi[:, None, :], lo[:, None, :] - hi[None, :, :]))
        dist = np.sqrt((gap * gap).sum(axis=-1))
        return (dist < reach[:, None]).sum(axis=1)
    from scipy.spatial import cKDTree
    centre, half = (lo + hi) / 2, np.linalg.norm(hi - lo, axis=1) / 2
    tree = cKDTree(centre)
    return np.asarray(tree.query_ball_point(centre, r=reach + half + half.max(), return_length=True))


def blend_growth(lo: np.ndarray, hi: np.ndarray, t: float, lower: float, window: float, g: float) -> np.ndarray:
    """How far to grow each child's box (rows of ``lo``, ``hi``) so that the grown boxes hold
    every point where the smooth fold of the children is below ``t`` (see the module's text)."""
    n = len(lo)
    folds = max(n - 1, 1)
    most = t + min(folds * lower, window)
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        return np.full(n, g * most)
    f = np.full(n, t + min(min(2, folds) * lower, window))
    for _ in range(64):
        count = _neighbour_counts(lo, hi, g * (2.0 * f + window))
        nxt = np.maximum(f, t + np.minimum(np.minimum(1 + count, folds) * lower, window))
        if np.array_equal(nxt, f):
            return g * f
        f = nxt
    return np.full(n, g * most)
