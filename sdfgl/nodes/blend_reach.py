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

from ..extras import installed

PAIRWISE_MAX = 1500     # up to this many children the box distances are counted exactly
KDTREE_FROM = 30000     # from this many children, scipy's k-d tree counts where scipy is installed
PAIRS_PER_PASS = 1 << 21  # candidate pairs measured in one numpy pass
PAIRS_MOST = 1 << 23      # beyond this many candidate pairs the candidates are counted instead


def _neighbour_counts(lo: np.ndarray, hi: np.ndarray, reach: np.ndarray, rows: np.ndarray | None = None) -> np.ndarray:
    """For every box i (of ``rows``, default all; ``reach`` is theirs), how many boxes (itself
    included) lie within reach[i] of it, or a
    superset of them: above PAIRWISE_MAX boxes, those whose centres lie within reach[i] plus
    both half-diagonals of box i's centre, found through a uniform grid of that radius (the
    boxes in the 27 cells around box i's; from KDTREE_FROM boxes by scipy's k-d tree where
    it is installed), or where that would measure more than PAIRS_MOST pairs, every box in
    those 27 cells."""
    n = len(lo)
    rows = np.arange(n) if rows is None else rows
    if n <= PAIRWISE_MAX:
        gap = np.maximum(0.0, np.maximum(lo[None, :, :] - hi[rows, None, :], lo[rows, None, :] - hi[None, :, :]))
        dist = np.sqrt((gap * gap).sum(axis=-1))
        return (dist < reach[:, None]).sum(axis=1)
    centre, half = (lo + hi) / 2, np.linalg.norm(hi - lo, axis=1) / 2
    radius = reach + half[rows] + half.max()
    if n >= KDTREE_FROM and installed("scipy"):
        # the same count, about 5x faster at 10^5 boxes; below this its 0.6 s import costs more
        from scipy.spatial import cKDTree
        return np.asarray(cKDTree(centre).query_ball_point(centre[rows], r=radius, return_length=True))
    cell = max(float(radius.max()), 1e-300)
    ijk = np.floor((centre - centre.min(axis=0)) / cell).astype(np.int64)
    dims = ijk.max(axis=0) + 1
    code = (ijk[:, 2] * dims[1] + ijk[:, 1]) * dims[0] + ijk[:, 0]
    order = np.argsort(code, kind="stable")
    ranked = code[order]
    offsets = np.array([(i, j, k) for k in (-1, 0, 1) for j in (-1, 0, 1) for i in (-1, 0, 1)])
    near = ijk[rows, None, :] + offsets[None, :, :]  # (rows, 27, 3)
    inside = np.all((near >= 0) & (near < dims), axis=-1)
    near_code = (near[..., 2] * dims[1] + near[..., 1]) * dims[0] + near[..., 0]
    start = np.where(inside, np.searchsorted(ranked, near_code, side="left"), 0)
    stop = np.where(inside, np.searchsorted(ranked, near_code, side="right"), 0)
    candidates = (stop - start).sum(axis=1)
    if candidates.sum() > PAIRS_MOST:
        return candidates
    m = len(rows)
    counts = np.zeros(m, dtype=np.int64)
    before = np.r_[0, np.cumsum(candidates)]  # candidate pairs of the boxes before each
    first = 0
    while first < m:  # queries first .. last - 1: at most PAIRS_PER_PASS pairs (or one box)
        last = max(first + 1, int(np.searchsorted(before, before[first] + PAIRS_PER_PASS, side="right")) - 1)
        part = np.arange(first, min(last, m))
        first = int(part[-1]) + 1
        s, size = start[part].ravel(), (stop[part] - start[part]).ravel()
        who = np.repeat(np.repeat(part, 27), size)
        other = order[np.repeat(s - np.r_[0, np.cumsum(size)[:-1]], size) + np.arange(int(size.sum()))]
        d2 = ((centre[rows[who]] - centre[other]) ** 2).sum(axis=1)
        counts += np.bincount(who[d2 <= radius[who] ** 2], minlength=m)
    return counts


def blend_growth(lo: np.ndarray, hi: np.ndarray, t: float, lower: float, window: float, g: float) -> np.ndarray:
    """How far to grow each child's box (rows of ``lo``, ``hi``) so that the grown boxes hold
    every point where the smooth fold of the children is below ``t`` (see the module's text)."""
    n = len(lo)
    folds = max(n - 1, 1)
    most = t + min(folds * lower, window)
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        return np.full(n, g * most)
    f = np.full(n, t + min(min(2, folds) * lower, window))
    # box i's next value depends on its own f alone: only those that moved, short of the most, are counted again
    active = np.arange(n)
    for _ in range(64):
        count = _neighbour_counts(lo, hi, g * (2.0 * f[active] + window), active)
        nxt = np.maximum(f[active], t + np.minimum(np.minimum(1 + count, folds) * lower, window))
        moved = nxt != f[active]
        f[active] = nxt
        active = active[moved & (nxt < most)]
        if not len(active):
            return g * f
    return np.full(n, g * most)
