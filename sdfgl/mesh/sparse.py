"""Sparse sampling: coarse passes at block centres skip blocks the distance bound proves empty.

A cube of n^3 cells lies inside a ball of radius r = n * step * sqrt(3) / 2 about its
centre c. With a Lipschitz factor L, |f(c)| > L * r means no point of the cube is on the
surface, and every sample of it has the sign of f(c). One draw tests the centres of the
BLOCK^3-cell blocks of a chunk; a second tests the 8 FINE^3-cell sub-blocks of each block
kept; only the sub-blocks kept then are sampled finely. The band of kept sub-blocks is about
half as thick as the band of blocks; with their shared faces sampled twice this takes a
quarter fewer samples on fogleman's CSG example at 2^22 (1.89 M, was 2.54 M) and 30 % fewer
at 1024^3 (8.1e7, was 1.15e8).
Fields without a bound (L = inf: implicit fields) keep every block, sampled as whole blocks.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from concurrent.futures import ThreadPoolExecutor
from typing import Callable, Iterable, Iterator, TypeVar

import numpy as np

from .lattice import BLOCK, CHUNK, Lattice
from .sample import GPUField

T = TypeVar("T")
MARGIN = 1.05  # head-room on the bound for float32 evaluation
FINE = 4       # cells per side of the sub-blocks sampled finely (BLOCK is a multiple of it)


@dataclass
class Chunk:
    """One chunk's samples: its ``origin`` (in blocks), the side ``block`` (cells) of its
    finely sampled cubes, their lower cells ``active`` (K, 3, chunk-local, in cells) and
    their ``fine`` samples (K, block+1, block+1, block+1), indexed [cube, i, j, k]."""

    origin: tuple[int, int, int]  # in blocks
    block: int
    active: np.ndarray
    fine: np.ndarray

    @property
    def base(self) -> np.ndarray:
        """(K, 3) int64: the global lattice index of each cube's lower sample."""
        return np.asarray(self.origin, np.int64) * BLOCK + self.active


def skip_radius(lipschitz: float, step: float, cells: int = BLOCK) -> float:
    """|f(centre)| above which a cube of ``cells``^3 cells cannot hold surface (inf: none is skipped)."""
    L = max(float(lipschitz), 1.0)  # the clip box is 1-Lipschitz
    return MARGIN * L * cells * step * math.sqrt(3) / 2 if math.isfinite(L) else math.inf


_SUB = np.argwhere(np.ones((BLOCK // FINE,) * 3, bool))  # sub-block offsets, in the order blocks() returns them


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
        if progress is not None:
            progress(n + 1, len(origins))
        if coarse is not None:
            inside = np.zeros((CHUNK,) * 3, bool)
            inside[:size[0], :size[1], :size[2]] = True
            act = np.argwhere(inside & (np.abs(coarse[n]) <= r))
            if len(act) == 0:
                continue
            k = BLOCK // FINE
            sub = field.blocks(lat.start + FINE * h / 2, (o + act) * k, k, FINE * h).reshape(len(act), -1)
            keep = np.abs(sub) <= skip_radius(lipschitz, h, FINE)
            blk, s = np.nonzero(keep)
            act, side = (act[blk] * k + _SUB[s]) * FINE, FINE
        else:
            act, side = np.argwhere(np.ones(tuple(size), bool)) * BLOCK, BLOCK
        if len(act) == 0:
            continue
        fine = field.blocks(lat.start, o * BLOCK + act, side + 1, h)
        yield Chunk(tuple(int(x) for x in o), side, act, fine)  # type: ignore[arg-type]


def analysed(parts: Iterable[Chunk], work: Callable[..., T], *args: object, workers: int = 1) -> list[T]:
    """[work(chunk, *args) for each chunk], run on worker threads while the GPU samples the
    next chunks (numpy releases the GIL in these loops); at most a few chunks wait in memory."""
    out: list[T] = []
    pending: list = []
    with ThreadPoolExecutor(max_workers=workers) as pool:
        for ch in parts:
            pending.append(pool.submit(work, ch, *args))
            while len(pending) > workers + 1:
                out.append(pending.pop(0).result())
        out += [p.result() for p in pending]
    return out


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
