"""Big unions of simple primitives as data: a primitive texture and a uniform grid.

A hard union of at least GRID_MIN (128) children that are spheres, (rounded) boxes, tori or
cylinders under translations, rotations, uniform scales and colours is not written out
as code: its primitives are packed into a texture, and a uniform grid lists per cell the
primitives within one cell size of it (shaders/grid_union.glsl). The shader then costs
what is near a point, and compiling costs the same for 64 primitives as for 10 000.

The field is min(listed primitives, cap), where every unlisted primitive is at least
``cap`` away; the float64 twin computes min(all primitives, cap) with the same cap,
which is the same number (see Grid.cap).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..params import Live
from .base import Node, Primitive
from .primitives import Box, Cylinder, RoundedBox, Sphere, Torus

GRID_MIN = 128      # fewer children than this are written out as code (measured crossover: 64..256)
LIST_WIDTH = 1024   # texels per row of the cell and list textures
MAX_DIMS = 64       # cells per axis at most

SPHERE, BOX, TORUS, CYLINDER = 0, 1, 2, 3


@dataclass
class Packed:
    """One primitive: world = t + s * R @ local; ``size`` and ``rounding`` per type."""

    type: int
    scale: float
    t: np.ndarray
    r: np.ndarray
    size: np.ndarray
    rounding: float
    color: tuple[float, float, float] | None


def _shape(prim: Primitive) -> tuple[int, np.ndarray, float, np.ndarray] | None:
    """(type, size, rounding, centre offset) of a packable primitive, else None."""
    if any(isinstance(v, Live) for v in prim.params.values()):
        return None
    if isinstance(prim, Sphere):
        return SPHERE, np.array([prim.r, 0.0, 0.0]), 0.0, np.asarray(prim.c, dtype=float)
    if isinstance(prim, RoundedBox):
        return BOX, np.asarray(prim.half, dtype=float), float(prim.r), np.zeros(3)
    if isinstance(prim, Box):
        return BOX, np.asarray(prim.half, dtype=float), 0.0, np.zeros(3)
    if isinstance(prim, Torus):
        return TORUS, np.array([prim.r1, prim.r2, 0.0]), 0.0, np.zeros(3)
    if isinstance(prim, Cylinder):
        return CYLINDER, np.array([prim.r, prim.h, 0.0]), 0.0, np.zeros(3)
    return None


def unwrap(node: Node) -> tuple[Node, np.ndarray, np.ndarray, float, tuple[float, float, float] | None] | None:
    """Peel rigid transforms, uniform scales and colours off ``node``: (inner node, t, R, s,
    colour) with world = t + s * R @ local; None if a live parameter is in the way."""
    from .transforms import Material, Rotate, Scale, Translate
    t, r, s, color = np.zeros(3), np.eye(3), 1.0, None
    while isinstance(node, (Material, Translate, Rotate, Scale)):
        if any(isinstance(v, Live) for v in node.params.values()):
            return None
        if isinstance(node, Translate):
            t = t + s * (r @ node.offset)
        elif isinstance(node, Rotate):
            r = r @ node.m
        elif isinstance(node, Scale):
            s = s * float(node.s)
        elif node.surface:  # packed primitives carry a colour only, not a full material
            return None
        else:
            color = node.rgb  # the innermost colour wins, as in code
        node = node.child
    return node, t, r, s, color


def pack(node: Node) -> Packed | None:
    """The primitive behind a chain of rigid transforms, uniform scales and colours, or None."""
    peeled = unwrap(node)
    if peeled is None or not isinstance(peeled[0], Primitive):
        return None
    prim, t, r, s, color = peeled
    shape = _shape(prim)
    if shape is None:
        return None
    kind, size, rounding, centre = shape
    return Packed(kind, s, t + s * (r @ centre), r, size, rounding, color)


class Grid:
    """The packed primitives of one union and the cell lists over their bounds."""

    def __init__(self, children: list[Node], packed: list[Packed], single_cell: bool = False) -> None:
        """``single_cell`` makes one cell list every primitive: a plain data-driven loop
        (the uber-shader the benchmark compares against)."""
        self.children, self.packed = children, packed
        los, his = zip(*(c.bounds for c in children))
        lo, hi = np.min(los, axis=0), np.max(his, axis=0)
        extent = np.maximum(hi - lo, 1e-9)
        cell = 0.5 * float(np.prod(extent) / len(children)) ** (1 / 3)  # ~8 cells a primitive
        cell = float(extent.max()) * 1.001 if single_cell else max(cell, float(extent.max()) / MAX_DIMS)
        self.dims = np.minimum(np.ceil(extent / cell).astype(int), MAX_DIMS)
        self.cell = cell
        self.lo = lo
        margin = cell
        lists: list[list[int]] = [[] for _ in range(int(np.prod(self.dims)))]
        for i, (clo, chi) in enumerate(zip(los, his)):
            a = np.clip(np.floor((clo - margin - lo) / cell).astype(int), 0, self.dims - 1)
            b = np.clip(np.floor((chi + margin - lo) / cell).astype(int), 0, self.dims - 1)
            for z in range(a[2], b[2] + 1):
                for y in range(a[1], b[1] + 1):
                    for x in range(a[0], b[0] + 1):
                        lists[(z * self.dims[1] + y) * self.dims[0] + x].append(i)
        self.lists = lists

    def cap(self, p: np.ndarray) -> np.ndarray:
        """The distance below which every unlisted primitive lies, at (..., 3) points."""
        rel = (p - self.lo) / self.cell
        cell = np.clip(np.floor(rel), 0, self.dims - 1)
        cell_lo = self.lo + cell * self.cell
        outside = np.maximum(np.maximum(cell_lo - p, p - (cell_lo + self.cell)), 0.0)
        half = 0.5 * self.dims * self.cell
        k = np.abs(p - (self.lo + half)) - half
        box = np.sqrt(np.sum(np.maximum(k, 0.0) ** 2, axis=-1)) + np.minimum(k.max(axis=-1), 0.0)
        return np.maximum(self.cell - np.sqrt(np.sum(outside ** 2, axis=-1)), box)

    def textures(self, origin: np.ndarray, default_color: tuple[float, float, float]) -> dict[str, np.ndarray]:
        """float32 RGBA arrays (rows, width, 4) for the Prims, Cells and List samplers."""
        prims = np.zeros((len(self.packed), 5, 4), dtype=np.float32)
        for i, q in enumerate(self.packed):
            t = q.t - origin
            prims[i, 0] = (q.type, q.scale, t[0], t[1])
            prims[i, 1] = (t[2], *q.size)
            prims[i, 2] = (*q.r[:, 0], q.rounding)
            prims[i, 3] = (*q.r[:, 1], 0.0)
            prims[i, 4] = (*(q.color or default_color), 0.0)
        counts = np.array([len(x) for x in self.lists])
        firsts = np.concatenate([[0], np.cumsum(counts)[:-1]])
        cells = np.zeros((-(-len(self.lists) // LIST_WIDTH) * LIST_WIDTH, 4), dtype=np.float32)
        cells[:len(self.lists), 0] = firsts
        cells[:len(self.lists), 1] = counts
        flat = np.concatenate([np.array(x, dtype=np.float32) for x in self.lists if x] or [np.zeros(0, np.float32)])
        lst = np.zeros((max(1, -(-len(flat) // LIST_WIDTH)) * LIST_WIDTH, 4), dtype=np.float32)
        lst[:len(flat), 0] = flat
        return {"Prims": prims, "Cells": cells.reshape(-1, LIST_WIDTH, 4), "List": lst.reshape(-1, LIST_WIDTH, 4)}


def build(children: list[Node]) -> Grid | None:
    """A grid for a union's children if enough of them pack (those that do not stay code)."""
    finite = [c for c in children if np.all(np.isfinite(c.bounds[0])) and np.all(np.isfinite(c.bounds[1]))]
    packed = [(c, pack(c)) for c in finite]
    packed = [(c, q) for c, q in packed if q is not None]
    if len(packed) < GRID_MIN:
        return None
    return Grid([c for c, _ in packed], [q for _, q in packed])
