"""mesh(): scene -> sparse GPU samples -> extraction -> projection -> Mesh."""
from __future__ import annotations

import sys
import time
from typing import Sequence

import numpy as np

from ..compiler.emitter import DEFAULT_COLOR
from ..errors import ParameterError
from ..nodes.base import Node
from ..nodes.traverse import fact
from .deficit import volume_error
from .deps import require
from .lattice import Lattice, make_lattice
from .project import project
from .sample import GPUField
from .sparse import Progress, chunks
from .topology import clean

MODES = ("mc", "sharp")
# With no step, resolution or samples given, a mesh whose volume is estimated off by more than
# VOLUME_TARGET (thin parts, small curved features) is made again at a finer step, at most
# REFINE_PASSES times and never finer than 1 / FINEST of the default step.
VOLUME_TARGET = 0.0025
REFINE_PASSES = 2
FINEST = 4
# An adaptive mesh whose faces the edge splits could not bring within the tolerance (features
# smaller than the lattice resolves) is made again from a lattice of half the step, at most
# TOLERANCE_PASSES times.
TOLERANCE_PASSES = 2


def _colors(scene: Node, field: GPUField, verts: np.ndarray) -> np.ndarray:
    """The scene's colour at each vertex: from the GPU colour field, or, for a scene with no
    material node, its one colour (no draw)."""
    if fact(scene, "_fields"):
        return field.colors(verts)
    return np.tile(np.asarray(DEFAULT_COLOR, np.float32), (len(verts), 1))


def mesh(scene: Node, step: float | None = None, resolution: int | None = None, samples: int | None = None,
         bounds: tuple[Sequence[float], Sequence[float]] | None = None, mode: str | None = None,
         colors: bool = True, progress: bool | None = None, tolerance: float | None = None):  # -> Mesh
    """Triangle mesh of ``scene``'s solid from its generated map() sampled on the GPU.

    Give one of ``step`` (cell size), ``resolution`` (cells along the longest side of the
    box) or ``samples`` (dense sample count, as fogleman/sdf counts). With none of them the
    mesh starts at 2^22 samples and, where its volume is then estimated off by more than
    0.25 % (thin or small curved parts; sdfgl.mesh.deficit), is made again at a finer step,
    up to 4x finer (the result's ``default_step`` is then the step it started from).
    ``bounds=(lo, hi)`` is the box to mesh (default: the scene's bounds padded by one cell;
    required for unbounded scenes); the solid is closed where the box cuts it.
    ``mode="mc"`` is marching cubes (smooth shapes, always manifold); ``"sharp"`` is dual
    contouring with field gradients (box edges, corners and CSG cuts stay sharp).
    ``progress`` prints a progress line on long runs (default: when stderr is a terminal).

    ``tolerance`` (scene units) makes the mesh adaptive (sdfgl.mesh.adaptive): few triangles
    where the surface is flat, many where it bends, with |f| at every vertex and the distance
    from every face centre to the surface within ``tolerance``, still closed and manifold. It
    picks the cell of the uniform mesh it starts from (60 tolerances, unless ``step``,
    ``resolution`` or ``samples`` is given) and makes ``mode`` default to ``"sharp"``; a
    tolerance too small for the memory limit is refused before any sampling. The result's
    ``tolerance`` and ``error`` (the largest measured on the GPU) say how it went: where the
    splits could not bring every face within it, the uniform mesh is made again at half the
    step, at most twice.
    """
    from .result import Mesh
    if not isinstance(scene, Node):
        raise ParameterError(f"mesh: 'scene' must be an sdfgl node, got {type(scene).__name__} {scene!r}")
    if mode is None:
        mode = "mc" if tolerance is None else "sharp"
    if mode not in MODES:
        raise ParameterError(f"mesh: 'mode' must be one of {', '.join(MODES)}, got {mode!r}")
    t0 = time.perf_counter()
    sized = step is not None or resolution is not None or samples is not None
    if tolerance is not None:
        from .adaptive import check_tolerance, step_for
        tolerance = check_tolerance(tolerance)
        require("pyfqmr"), require("meshoptimizer")  # before any sampling
        if not sized:
            step = step_for(scene, tolerance, bounds)
    lat = make_lattice(scene, step, resolution, samples, bounds)
    show = sys.stderr.isatty() if progress is None else progress
    verts, faces, normals, field, took = _extract(scene, lat, mode, show)
    taken, default_step = field.samples, None
    if not sized and tolerance is None:
        for _ in range(REFINE_PASSES):
            finer = _finer_step(field, verts, faces, lat.step, default_step or lat.step)
            if finer is None:
                break
            try:
                lat_finer = make_lattice(scene, step=finer, bounds=bounds)
            except ParameterError:  # past MAX_CELLS: keep the mesh we have
                break
            default_step = default_step or lat.step
            lat = lat_finer
            verts, faces, normals, field, more = _extract(scene, lat, mode, show)
            took = [a + b for a, b in zip(took, more)]
            taken += field.samples
    error = None
    if tolerance is not None and len(faces):
        from .adaptive import simplify
        took.append(0.0)
        for attempt in range(TOLERANCE_PASSES + 1):
            t1 = time.perf_counter()
            got = simplify(field, verts, faces, normals, tolerance, lat.step)
            took[2] += time.perf_counter() - t1
            if got[3] <= tolerance or attempt == TOLERANCE_PASSES:
                break
            try:  # features the lattice is too coarse for: mesh again at half the step
                lat = make_lattice(scene, step=lat.step / 2, bounds=bounds)
            except ParameterError:  # past MAX_CELLS: keep the mesh we have (its error says so)
                break
            verts, faces, normals, field, more = _extract(scene, lat, mode, show)
            took = [a + b for a, b in zip(took, more + [0.0])]
            taken += field.samples
        verts, faces, normals, error = got
    rgb = _colors(scene, field, verts) if colors and len(verts) else None
    t2 = time.perf_counter()
    timings = {"extract_s": took[0], "project_s": took[1], "total_s": t2 - t0}
    if error is not None:
        timings["simplify_s"] = took[2]
    return Mesh(verts, faces, normals, rgb, scene=scene, lattice=lat, mode=mode, timings=timings,
                samples=taken, default_step=default_step,
                tolerance=tolerance, error=error)


def _extract(scene: Node, lat: Lattice, mode: str, show: bool):
    """(vertices, faces, normals, the GPUField, [extraction seconds, projection seconds]) of
    one lattice."""
    t0 = time.perf_counter()
    field = GPUField(scene, *lat.box)
    parts = chunks(field, lat, scene.lipschitz, Progress(sys.stderr if show else None))
    if mode == "mc":
        from .extract_mc import march
        verts, faces = march(parts, lat)
    else:
        from .extract_dc import dual_contour
        verts, faces = dual_contour(parts, lat, field)
    t1 = time.perf_counter()
    verts, normals, _ = project(field, verts, lat.step)
    if mode != "mc":  # march() leaves no degenerate or repeated triangles and no unused vertex
        verts, faces, normals = clean(verts, faces, normals)
    return verts, faces, normals, field, [t1 - t0, time.perf_counter() - t1]


def _finer_step(field: GPUField, verts: np.ndarray, faces: np.ndarray, step: float, first: float) -> float | None:
    """The step to mesh again at when the default step leaves the volume off by more than
    VOLUME_TARGET (estimated, sdfgl.mesh.deficit; the error falls with the step squared), or
    None. Never finer than FINEST times the default step."""
    if step <= first / FINEST * (1 + 1e-9):
        return None
    err = abs(volume_error(field, verts, faces, step))
    if err <= VOLUME_TARGET:
        return None
    return max(step * 0.9 * (VOLUME_TARGET / err) ** 0.5, first / FINEST)
