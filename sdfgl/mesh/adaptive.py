"""Adaptive meshes with a bounded error: a uniform mesh simplified by quadric error, then held to
the tolerance with the GPU field.

``tolerance`` bounds the field at every vertex and the distance from every face centre to the
surface (|f| / |grad f|, in scene units). The steps:

1. a uniform mesh at a cell of ``STEP_PER_TOLERANCE`` tolerances (dual contouring by default,
   so edges and corners are sharp): its own face centres lie inside the bound wherever the
   surface bends less than the cell (a sagitta of a few hundredths of a cell). On the CSG part
   and the demo scene at 0.05 of the 2^22-sample cell, 40 tolerances took 1.3 and 1.2 s, 60
   took 0.7 and 0.8 s with about as many triangles, and 80 left the demo scene's small parts
   off by 1.6 tolerances after the splits (sdfgl.mesh.build then meshes again finer);
2. edge collapses by quadric error (Garland and Heckbert), through pyfqmr (the
   Fast-Quadric-Mesh-Simplification library): its threshold, the sum of squared distances of
   a merged vertex to the planes of all the faces merged into it, is capped at
   ``QUADRIC_SHARE`` tolerances squared, so flat parts lose almost every vertex and curved
   parts and features keep theirs. A result that is not closed and manifold is undone and
   collapsed again with a lower cap (down to the uniform mesh itself);
3. meshoptimizer's simplifier (Kapoulkine) at a quarter tolerance, which only drops vertices:
   it clears flat faces oblique to the axes, where pyfqmr's collapses stall (a rotated box
   keeps 7 440 triangles of 51 116 after pyfqmr, 40 after this); a result that is not closed
   and manifold is not kept;
4. every vertex projected onto the surface (sdfgl.mesh.project);
5. the field measured at vertices and face centres on the GPU; the longest edge of each face
   whose centre is off by more than ``MARGIN`` tolerances is split at its midpoint (a conforming
   split: both faces on the edge are split, so the mesh stays closed), the new vertices are
   projected, until every face holds. Once fewer than ``TAIL_SHARE`` of the faces are off (at
   creases, where a split of the longest edge halves the error only every other round), all
   three edges of each are split: on the CSG part 10 rounds became 4 for 6 % more triangles,
   on the demo scene 9 became 6 for 0.6 % more.

pyfqmr was chosen over fast-simplification (the same library behind pyvista's wrapper)
because its collapse threshold can be capped in scene units (``alpha``, ``K``,
``aggressiveness``, ``max_iterations``): fast-simplification's threshold grows without bound
until a triangle count is reached, so only a count, not an error, could be asked of it. A cap
of 4 tolerances squared keeps the face centres of fogleman's CSG part within about two
tolerances before the splits, and 16 tolerances squared went past that. meshoptimizer alone (no
quadric placement, vertices only dropped) kept 2.7 times the triangles on the CSG part at half a
tolerance, and on the demo scene it joined two sheets at an edge; after pyfqmr it only has flat
parts left to clear.

Time, against the uniform marching-cubes export at 2^22 samples (tolerance 0.05 of its cell;
``python -c "from sdfgl.mesh.bench import run_adaptive; print(run_adaptive(rounds=5)[0])"``,
medians of interleaved runs on 2 shared CPU cores with llvmpipe, so within about 20 %): the CSG
part 0.117 s against 0.073 s (1.6x, 8 380 triangles, 2.3 % of the uniform mesh), the demo scene
0.105 s against 0.057 s (1.9x, 27 618 triangles, 16.0 %), both within 0.95 tolerances at face
centres. The uniform export uses both cores (the GPU's sampling beside numpy); most of this
pipeline is one: on the demo scene dual contouring of the coarse lattice about 35 ms, pyfqmr
about 20 ms, meshoptimizer 10 ms, the split rounds about 40 ms (profiled with cProfile). The
demo scene's coarse lattice leaves a third of its faces more than a tolerance off (curved
parts), so its collapses leave about 10 800 triangles and six split rounds bring them to 27 618;
splitting all three edges of every face off by more than two tolerances saved one round and
no time measurably. At this tolerance the cell is capped by ``COARSEST`` at 63.5 tolerances, so
``STEP_PER_TOLERANCE`` above that changes nothing. pyfqmr with 15 passes instead of 40 took
31 ms instead of 40 on the CSG part's coarse mesh (39 840 triangles; 12 against 15 ms on the
demo scene's 19 364), for 0.7 % and 0.5 % more triangles after it and the same count within
1 % after the splits (medians of 5 calls); 10 passes saved 3 ms more on the CSG part for
another 1 %.
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from ..errors import ParameterError
from ..nodes.base import Node
from .deps import require
from .lattice import MAX_CELLS, make_lattice
from .project import project
from .sample import GPUField
from .topology import clean

STEP_PER_TOLERANCE = 60.0  # the uniform mesh's cell, in tolerances
QUADRIC_SHARE = 4.0        # collapse threshold: this many tolerances squared of quadric error
ITERATIONS = 15            # pyfqmr passes; the threshold rises to the cap at the last one
AGGRESSIVENESS = 7.0
FLAT_SHARE = 0.25          # meshoptimizer's error limit after pyfqmr, in tolerances
RETRIES = 3                # lower caps tried when a simplified mesh is not closed and manifold
SPLIT_ROUNDS = 12          # rounds of edge splits that bring faces within the tolerance
TAIL_SHARE = 0.02          # below this share of faces off, a round splits every edge of each
MAX_TRIANGLES = 1 << 26    # estimated triangles of the uniform mesh (about 10 GB of arrays)
MARGIN = 0.95              # the GPU (float32) holds face centres to this share of the tolerance
COARSEST = 1 << 17         # samples of the coarsest uniform lattice a tolerance may ask for


def check_tolerance(tolerance: object) -> float:
    """``tolerance`` as a float, or a clear error when it is not a positive number."""
    if isinstance(tolerance, bool) or not isinstance(tolerance, (int, float, np.floating, np.integer)) or not (
            math.isfinite(float(tolerance)) and float(tolerance) > 0):
        raise ParameterError(f"mesh: 'tolerance' must be a positive number (scene units), got {tolerance!r}")
    return float(tolerance)


def step_for(scene: Node, tolerance: float, bounds: tuple[Sequence[float], Sequence[float]] | None) -> float:
    """The uniform mesh's cell for ``tolerance``: ``STEP_PER_TOLERANCE`` tolerances, but no
    coarser than the lattice of ``COARSEST`` samples (so a loose tolerance still sees the
    scene's features). Refuses, before any sampling, a tolerance whose lattice would pass
    MAX_CELLS cells along an axis or whose mesh would pass MAX_TRIANGLES (estimated from the
    area of the box's faces)."""
    tolerance = check_tolerance(tolerance)
    coarsest = make_lattice(scene, samples=COARSEST, bounds=bounds)
    step = min(STEP_PER_TOLERANCE * tolerance, coarsest.step)
    lo, hi = coarsest.box
    ext = hi - lo
    smallest = max(float(ext.max()) / (MAX_CELLS - 4),
                   math.sqrt(2 * 2 * (ext[0] * ext[1] + ext[1] * ext[2] + ext[0] * ext[2]) / MAX_TRIANGLES))
    if step < smallest:
        raise ParameterError(
            f"mesh: tolerance {tolerance:g} needs a uniform mesh of cell {step:g} over the box "
            f"{np.round(lo, 4).tolist()} .. {np.round(hi, 4).tolist()}, past the memory limit "
            f"({MAX_CELLS} cells an axis, about {MAX_TRIANGLES} triangles); the smallest tolerance for "
            f"this box is {smallest / STEP_PER_TOLERANCE:.3g}")
    return step


def _collapse(verts: np.ndarray, faces: np.ndarray, cap: float) -> tuple[np.ndarray, np.ndarray]:
    """Edge collapses (pyfqmr) whose quadric error stays below ``cap`` (squared units), in
    ``ITERATIONS`` passes whose threshold rises to the cap (cheap collapses first, so the
    vertices left are well placed; a pass collapses each triangle at most once, so large flat
    parts need many passes)."""
    pyfqmr = require("pyfqmr")
    s = pyfqmr.Simplify()
    s.setMesh(np.ascontiguousarray(verts, np.float64), np.ascontiguousarray(faces, np.int32))
    k = 3
    s.simplify_mesh(target_count=4, update_rate=5, aggressiveness=AGGRESSIVENESS, max_iterations=ITERATIONS,
                    alpha=cap / (ITERATIONS - 1 + k) ** AGGRESSIVENESS, K=k, verbose=False, preserve_border=True)
    v, f, _ = s.getMesh()
    return np.asarray(v, np.float64), np.asarray(f, np.int64)


def _flatten(verts: np.ndarray, faces: np.ndarray, limit: float) -> np.ndarray:
    """Faces left by meshoptimizer's simplifier (its vertices are a subset of ``verts``, moved
    nowhere) within an absolute error of ``limit``: it clears the flat parts that pyfqmr's
    collapses stall on (a plane's quadric is singular, and rounding makes its determinant
    nonzero where the plane is oblique to the axes, so pyfqmr puts the merged vertex far off
    and refuses the collapse as a flip)."""
    meshopt = require("meshoptimizer")
    index = np.ascontiguousarray(faces, np.uint32).ravel()
    out = np.zeros_like(index)
    n = meshopt.simplify(out, index, np.ascontiguousarray(verts, np.float32), target_index_count=0,
                         target_error=float(limit), options=meshopt.SIMPLIFY_ERROR_ABSOLUTE)
    return without_fins(out[:n].reshape(-1, 3).astype(np.int64))


def without_fins(faces: np.ndarray) -> np.ndarray:
    """``faces`` less each pair of one triangle and its reverse (the same three vertices wound
    the other way): a fin of no volume, which a simplifier can leave where it folded a sliver
    onto itself and which would make the mesh non-manifold."""
    if len(faces) == 0:
        return faces
    rolled = np.take_along_axis(faces, (np.argmin(faces, axis=1)[:, None] + np.arange(3)[None]) % 3, 1)
    # lowest vertex first, winding kept: a face and its reverse share the first vertex and
    # swap the other two
    a = rolled[:, 1:].min(axis=1)
    b = rolled[:, 1:].max(axis=1)
    forward = rolled[:, 1] < rolled[:, 2]
    n = int(faces.max()) + 1
    if n < 1 << 21:  # the triple as one int64 key: a 1-D unique sorts numbers, not rows
        _, inverse, counts = np.unique((rolled[:, 0] * n + a) * n + b, return_inverse=True, return_counts=True)
    else:
        _, inverse, counts = np.unique(np.stack([rolled[:, 0], a, b], 1), axis=0, return_inverse=True,
                                       return_counts=True)
    inverse = inverse.ravel()
    pairs = counts[inverse] == 2
    if not pairs.any():
        return faces
    fwd = np.bincount(inverse, weights=forward, minlength=len(counts))
    fin = pairs & (fwd[inverse] == 1)  # two faces of one triple, wound opposite ways
    return faces[~fin]


def closed(faces: np.ndarray) -> bool:
    """Every edge on exactly two faces and no directed edge twice (closed, manifold, wound alike):
    each directed edge then meets its reverse exactly once."""
    if len(faces) == 0:
        return False
    a = faces.ravel()
    b = np.roll(faces, -1, axis=1).ravel()
    n = int(faces.max()) + 1
    directed = np.sort(a * n + b)
    if np.any(directed[1:] == directed[:-1]):
        return False
    reverse = b * n + a
    at = np.minimum(np.searchsorted(directed, reverse), len(directed) - 1)
    return bool(np.all(directed[at] == reverse))


def face_errors(field: GPUField, verts: np.ndarray, faces: np.ndarray, step: float) -> np.ndarray:
    """Distance estimate |f| / |grad f| at the centres of ``faces``, from the GPU field
    (gradients 0.02 cell wide; a gradient longer than 1 counts as 1, so the estimate never falls
    below |f|)."""
    f, g, _ = field.gradient_bend(verts[faces].mean(axis=1), 0.02 * step)
    return np.abs(f) / np.clip(np.linalg.norm(g, axis=1), 1e-6, 1.0)


def split_edges(verts: np.ndarray, faces: np.ndarray, faces_to_split: np.ndarray,
                every_edge: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Split the longest edge of each face in ``faces_to_split`` (a mask) at its midpoint, every
    edge of each face in ``every_edge`` (a mask, or None), and every face on a split edge with
    it (one, two or three split edges give two, three or four triangles), so the mesh stays
    closed. Returns (vertices, faces, indices of the new vertices,
    mask of the faces left as they were: they come first, in their order, the new ones after).
    Only the split edges are sorted; the edges of the faces with two ends of split edges are
    looked up among them by binary search, so a round costs little more than a pass over the
    faces."""
    n = len(verts)
    bad = faces[faces_to_split]
    nxt = bad[:, [1, 2, 0]]
    longest = np.argmax(np.linalg.norm(verts[bad] - verts[nxt], axis=2), axis=1)
    a = np.take_along_axis(bad, longest[:, None], 1)[:, 0]
    b = np.take_along_axis(nxt, longest[:, None], 1)[:, 0]
    if every_edge is not None and every_edge.any():
        all3 = faces[every_edge]
        a = np.concatenate([a, all3.ravel()])
        b = np.concatenate([b, all3[:, [1, 2, 0]].ravel()])
    marked = np.unique(np.minimum(a, b) * n + np.maximum(a, b))   # sorted keys of the split edges
    end = np.zeros(n, bool)                                        # ends of split edges
    end[marked // n] = end[marked % n] = True
    near = np.nonzero(end[faces].sum(axis=1) >= 2)[0]              # faces that may hold one
    near_faces = faces[near]
    f1 = near_faces[:, [1, 2, 0]]
    key = np.minimum(near_faces, f1) * n + np.maximum(near_faces, f1)  # edge (v_i, v_i+1)
    at = np.searchsorted(marked, key)
    np.minimum(at, len(marked) - 1, out=at)
    m = np.where(marked[at] == key, n + at, -1)                    # midpoint of each edge or -1
    count = (m >= 0).sum(axis=1)
    verts = np.concatenate([verts, (verts[marked // n] + verts[marked % n]) / 2])
    hit = count > 0
    unchanged = np.ones(len(faces), bool)
    unchanged[near[hit]] = False
    out = [faces[unchanged]]
    faces, m, count = near_faces[hit], m[hit], count[hit]
    for r in range(3):  # rotate each face so its split edges start at edge 0
        f, mm = np.roll(faces, -r, axis=1), np.roll(m, -r, axis=1)
        v0, v1, v2, m0, m1 = f[:, 0], f[:, 1], f[:, 2], mm[:, 0], mm[:, 1]
        one = (count == 1) & (m0 >= 0)
        out += [np.stack([v0, m0, v2], 1)[one], np.stack([m0, v1, v2], 1)[one]]
        two = (count == 2) & (m0 >= 0) & (m1 >= 0)
        out += [np.stack([m0, v1, m1], 1)[two], np.stack([v0, m0, m1], 1)[two], np.stack([v0, m1, v2], 1)[two]]
    three = count == 3
    v0, v1, v2, m0, m1, m2 = faces[:, 0], faces[:, 1], faces[:, 2], m[:, 0], m[:, 1], m[:, 2]
    out += [np.stack(t, 1)[three] for t in ((v0, m0, m2), (m0, v1, m1), (m2, m1, v2), (m0, m1, m2))]
    return verts, np.concatenate(out), n + np.arange(len(marked)), unchanged


def simplify(field: GPUField, verts: np.ndarray, faces: np.ndarray, normals: np.ndarray, tolerance: float,
             step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """The uniform mesh (vertices, faces, normals, at cell ``step``) made adaptive within
    ``tolerance`` (see the module docstring): (vertices, faces, normals, the largest error
    measured on the GPU at its vertices and face centres)."""
    cap = QUADRIC_SHARE * tolerance ** 2
    for _ in range(RETRIES + 1):
        v, f = _collapse(verts, faces, cap)
        if closed(f):
            break
        cap /= 4
    else:  # no cap left the mesh closed: keep the uniform mesh
        v, f = verts, faces
    flat = _flatten(v, f, FLAT_SHARE * tolerance)
    if closed(flat):
        used = np.unique(flat)
        remap = np.zeros(len(v), np.int64)
        remap[used] = np.arange(len(used))
        v, f = v[used], remap[flat]
    v, n, ev = project(field, v, step)  # ev: |f| at the vertices, measured where they end
    ec = face_errors(field, v, f, step)
    for _ in range(SPLIT_ROUNDS):  # only new vertices and faces are measured again
        over = ec > MARGIN * tolerance
        if not over.any():
            break
        # the last few faces off (at creases, where a split of the longest edge halves the error
        # only every other round) have all three edges split
        v, f, new, unchanged = split_edges(v, f, over, over if over.sum() < TAIL_SHARE * len(over) else None)
        v[new], n_new, ev_new = project(field, v[new], step)
        n = np.concatenate([n, n_new])
        ec_new = face_errors(field, v, f[unchanged.sum():], step)
        ev, ec = np.concatenate([ev, ev_new]), np.concatenate([ec[unchanged], ec_new])
    v, f, n = clean(v, f, n)
    return v, f, n, float(max(ev.max(initial=0.0), ec.max(initial=0.0)))
