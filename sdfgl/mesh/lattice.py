"""The sampling lattice: box, step, blocks and chunks, from the user's step/resolution/bounds."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..errors import ParameterError
from ..nodes.base import Node

BLOCK = 8    # cells per block side: the unit the coarse pass keeps or skips
CHUNK = 16   # blocks per chunk side: the unit sampled and extracted at once (128^3 cells)
MAX_CELLS = 4096  # cells per axis


@dataclass(frozen=True)
class Lattice:
    """Samples at ``start + step * (i, j, k)``, ``i`` in 0..cells[0] (and so on).

    ``box`` is the sampling box (lo, hi): the mesh is the solid cut by it. The lattice
    starts half a cell outside the box, so its outer samples are always outside the cut
    field and every surface closes. ``cells`` is a multiple of BLOCK on every axis.
    """

    start: np.ndarray
    step: float
    cells: tuple[int, int, int]
    box: tuple[np.ndarray, np.ndarray]

    @property
    def blocks(self) -> tuple[int, int, int]:
        return tuple(c // BLOCK for c in self.cells)  # type: ignore[return-value]

    @property
    def samples(self) -> int:
        """Samples of the dense lattice (the 'effective' sample count)."""
        return int(np.prod(np.asarray(self.cells) + 1))

    def chunks(self) -> list[tuple[int, int, int]]:
        """Chunk origins in block coordinates."""
        nb = self.blocks
        return [(x, y, z) for x in range(0, nb[0], CHUNK) for y in range(0, nb[1], CHUNK)
                for z in range(0, nb[2], CHUNK)]


def _vec3(name: str, v: object) -> np.ndarray:
    try:
        a = np.asarray(v, dtype=np.float64).reshape(3)
    except (TypeError, ValueError):
        raise ParameterError(f"mesh: '{name}' must be 3 numbers, got {v!r}") from None
    if not np.all(np.isfinite(a)):
        raise ParameterError(f"mesh: '{name}' must be finite, got {v!r}")
    return a


def _positive(name: str, v: object) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not (
            0 < v <= sys.float_info.max):  # NaN and an int too big for a float compare without raising
        raise ParameterError(f"mesh: '{name}' must be a positive number, got {v!r}")
    return float(v)


def make_lattice(scene: Node, step: float | None = None, resolution: int | None = None,
                 samples: int | None = None,
                 bounds: tuple[Sequence[float], Sequence[float]] | None = None) -> Lattice:
    """The lattice for one of ``step`` (cell size), ``resolution`` (cells along the longest side)
    or ``samples`` (total dense samples, as fogleman/sdf counts them) and ``bounds``.

    Without ``bounds`` the box is the scene's bounds padded by one cell; an unbounded scene
    needs ``bounds``.
    """
    given = [n for n, v in (("step", step), ("resolution", resolution), ("samples", samples)) if v is not None]
    if len(given) > 1:
        raise ParameterError(f"mesh: give one of step, resolution or samples, not {' and '.join(given)}")
    if bounds is not None:
        try:
            lo, hi = bounds
        except (TypeError, ValueError):
            raise ParameterError(f"mesh: 'bounds' must be (lo, hi), two 3-vectors, got {bounds!r}") from None
        lo, hi = _vec3("bounds lo", lo), _vec3("bounds hi", hi)
        if not np.all(hi > lo):
            raise ParameterError(f"mesh: 'bounds' hi must exceed lo on every axis, got lo={lo}, hi={hi}")
        pad_cells = 0.0
    else:
        lo, hi = scene.bounds
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            raise ParameterError(
                f"mesh: {scene.label()} is unbounded (bounds {lo} .. {hi}); pass bounds=(lo, hi) "
                f"(CLI: --bounds x0 y0 z0 x1 y1 z1) to say which part to mesh")
        pad_cells = 1.0
    ext = float(np.max(hi - lo))
    if ext <= 0:  # a degenerate (flat) solid still gets a box
        ext = 1.0
    if step is not None:
        h = _positive("step", step)
    elif resolution is not None:
        if (isinstance(resolution, bool) or not isinstance(resolution, (int, float, np.integer, np.floating))
                or not 8 <= resolution <= MAX_CELLS or int(resolution) != resolution):  # NaN fails the range
            raise ParameterError(f"mesh: 'resolution' must be an integer in 8..{MAX_CELLS}, got {resolution!r}")
        h = ext / (int(resolution) - 2 * pad_cells)
    else:
        n = _positive("samples", samples if samples is not None else 2 ** 22)
        h = float(np.prod(hi - lo + 2 * pad_cells * ext / 128)) ** (1 / 3) / n ** (1 / 3)
    lo, hi = lo - pad_cells * h, hi + pad_cells * h
    raw = np.ceil((hi - lo) / h).astype(int) + 1
    if np.any(raw > MAX_CELLS):
        raise ParameterError(f"mesh: step {h:g} gives {raw.max()} cells along an axis of the box "
                             f"{lo} .. {hi}; at most {MAX_CELLS}: use a larger step")
    cells = tuple(int(-(-c // BLOCK) * BLOCK) for c in raw)
    return Lattice(lo - h / 2, h, cells, (lo, hi))  # type: ignore[arg-type]
