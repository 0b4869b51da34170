"""Sparse sampling: a coarse pass at block centres skips blocks the distance bound proves empty.

A block of BLOCK^3 cells lies inside a ball of radius r = BLOCK * step * sqrt(3) / 2 about
its centre c. With a Lipschitz factor L, |f(c)| > L * r means no point of the block is on
the surface, and every sample of the block has the sign of f(c). Only the other blocks are
sampled finely. Fields without a bound (L = inf: implicit fields) keep every block.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable, Iterator

import numpy as np

from .lattice import BLOCK, CHUNK, Lattice
from .sample import GPUField

MARGIN = 1.05  # head-room on the bound for float32 evaluation


@dataclass
class Chunk:
    """One chunk's samples: ``coarse`` (CHUNK^3 block-centre values, block [x, y, z]),
    the chunk's ``active`` blocks (K, 3 chunk-local block coordinates) and their ``fine``
    samples (K, BLOCK+1, BLOCK+1, BLOCK+1)."""

    origin: tuple[int, int, int]  # in blocks
    coarse: np.ndarray
    active: np.ndarray
    fine: np.ndarray


def skip_radius(lipschitz: float, step: float) -> float:
    """|f(centre)| above which a block cannot hold surface (inf: no block is skipped)."""
    L = max(float(lipschitz), 1.0)  # the clip box is 1-Lipschitz
    return MARGIN * L * BLOCK * step * math.sqrt(3) / 2 if math.isfinite(L) else math.inf


def chunks(field: GPUField, lat: Lattice, lipschitz: float,
           progress: Callable[[int, int], None] | None = None) -> Iterator[Chunk]:
    """Sample the lattice chunk by chunk, yielding chunks that hold surface."""
    origins = lat.chunks()
    nb = np.asarray(lat.blocks)
    h = lat.step
    r = skip_radius(lipschitz, h)
    coarse = None
    if math.isfinite(r):
        coarse = field.blocks(lat.start + BLOCK * h / 2, np.asarray(origins), CHUNK, BLOCK * h)
    for n, org in enumerate(origins):
        o = np.asarray(org)
        size = np.minimum(CHUNK, nb - o)
        if coarse is not None:
            c = coarse[n]
            inside = np.zeros((CHUNK,) * 3, bool)
            inside[:size[0], :size[1], :size[2]] = True
            act = np.argwhere(inside & (np.abs(c) <= r))
        else:
            c = np.zeros((CHUNK,) * 3, np.float32)
            act = np.argwhere(np.ones(tuple(size), bool))
        if progress is not None:
            progress(n + 1, len(origins))
        if len(act) == 0:
            continue
        fine = field.blocks(lat.start, (o + act) * BLOCK, BLOCK + 1, h)
        yield Chunk(tuple(int(x) for x in o), c, act, fine)  # type: ignore[arg-type]


class Progress:
    """Prints 'meshing: 37% (12 of 32 chunks)' to a stream on runs longer than ``after`` s."""

    def __init__(self, stream, after: float = 2.0) -> None:  # noqa: ANN001
        self.stream, self.after, self.t0, self.last = stream, after, time.perf_counter(), -1.0

    def __call__(self, done: int, total: int) -> None:
        t = time.perf_counter() - self.t0
        if self.stream is None or t < self.after or (t - self.last < 1.0 and done < total):
            return
        self.last = t
        self.stream.write(f"\rmeshing: {100 * done // total:3d}% ({done} of {total} chunks, {t:.0f} s)")
        if done == total:
            self.stream.write("\n")
        self.stream.flush()
