"""mesh(): scene -> sparse GPU samples -> extraction -> projection -> Mesh."""
from __future__ import annotations

import sys
import time
from typing import Sequence

import numpy as np

from ..codegen import DEFAULT_COLOR
from ..errors import ParameterError
from ..nodes.base import Node
from ..nodes.traverse import fact
from .lattice import make_lattice
from .project import project
from .sample import GPUField
from .sparse import Progress, chunks
from .topology import clean

MODES = ("mc", "sharp")


def _colors(scene: Node, field: GPUField, verts: np.ndarray) -> np.ndarray:
    """The scene's colour at each vertex: from the GPU colour field, or, for a scene with no
    material node, its one colour (no draw)."""
    if fact(scene, "_fields"):
        return field.colors(verts)
    return np.tile(np.asarray(DEFAULT_COLOR, np.float32), (len(verts), 1))


def mesh(scene: Node, step: float | None = None, resolution: int | None = None, samples: int | None = None,
         bounds: tuple[Sequence[float], Sequence[float]] | None = None, mode: str = "mc",
         colors: bool = True, progress: bool | None = None):  # -> Mesh
    """Triangle mesh of ``scene``'s solid from its generated map() sampled on the GPU.

    Give one of ``step`` (cell size), ``resolution`` (cells along the longest side of the
    box) or ``samples`` (dense sample count, as fogleman/sdf counts; default 2^22).
    ``bounds=(lo, hi)`` is the box to mesh (default: the scene's bounds padded by one cell;
    required for unbounded scenes); the solid is closed where the box cuts it.
    ``mode="mc"`` is marching cubes (smooth shapes, always manifold); ``"sharp"`` is dual
    contouring with field gradients (box edges, corners and CSG cuts stay sharp).
    ``progress`` prints a progress line on long runs (default: when stderr is a terminal).
    """
    from .result import Mesh
    if not isinstance(scene, Node):
        raise ParameterError(f"mesh: 'scene' must be an sdfgl node, got {type(scene).__name__} {scene!r}")
    if mode not in MODES:
        raise ParameterError(f"mesh: 'mode' must be one of {', '.join(MODES)}, got {mode!r}")
    t0 = time.perf_counter()
    lat = make_lattice(scene, step, resolution, samples, bounds)
    field = GPUField(scene, *lat.box)
    show = sys.stderr.isatty() if progress is None else progress
    parts = chunks(field, lat, scene.lipschitz, Progress(sys.stderr if show else None))
    if mode == "mc":
        from .extract_mc import march
        verts, faces = march(parts, lat)
    else:
        from .extract_dc import dual_contour
        verts, faces = dual_contour(parts, lat, field)
    t1 = time.perf_counter()
    verts, normals = project(field, verts, lat.step)
    if mode != "mc":  # march() leaves no degenerate or repeated triangles and no unused vertex
        verts, faces, normals = clean(verts, faces, normals)
    rgb = _colors(scene, field, verts) if colors and len(verts) else None
    t2 = time.perf_counter()
    timings = {"extract_s": t1 - t0, "project_s": t2 - t1, "total_s": t2 - t0}
    return Mesh(verts, faces, normals, rgb, scene=scene, lattice=lat, mode=mode, timings=timings,
                samples=field.samples)
