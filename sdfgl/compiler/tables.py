"""What a shader reads besides its code: the one data texture and the moving origin's offsets."""
from __future__ import annotations

import hashlib
import threading
import weakref
from collections import OrderedDict
from typing import Sequence

import numpy as np

from ..errors import ParameterError
from ..params import Live
from .source import OriginEntry

DATA_WIDTH = 1024  # texels per row of a data table (a power of two)
RECENT_TEXTURES = 2  # data textures found by content: an image's and its coarse pass's sources share one
_recent: OrderedDict[tuple[bytes, ...], weakref.ref[np.ndarray]] = OrderedDict()  # held by their sources only
_recent_lock = threading.Lock()


class DataPool:
    """The float32 texels of every table a shader reads (grid lists, polygon vertices), in
    one texture: one sampler however many tables (drivers allow only a few samplers)."""

    def __init__(self) -> None:
        self.chunks: list[np.ndarray] = []
        self.size = 0
        self._index: dict[bytes, int] = {}  # content key -> first texel (insertion order: the chunks')

    def add(self, texels: np.ndarray) -> int:
        """Append (n, 4) float32 texels (once per content); return the first one's index."""
        arr = np.ascontiguousarray(texels, dtype=np.float32).reshape(-1, 4)
        key = hashlib.sha1(arr.tobytes()).digest() + len(arr).to_bytes(8, "little")
        if key not in self._index:
            self._index[key] = self.size
            self.chunks.append(arr)
            self.size += len(arr)
        return self._index[key]

    def texture(self) -> tuple[tuple[str, np.ndarray], ...]:
        """("uData", (rows, DATA_WIDTH, 4)) or nothing. Pools of the same tables give the same
        array while a source made from the one before holds it (of the last few made), so their
        sources share one upload (sdfgl.gl.data)."""
        if not self.chunks:
            return ()
        if self.size >= 2 ** 24:
            raise ParameterError(f"scene: its data tables hold {self.size} texels, over the limit of 2^24 "
                                 f"(float32 indices); use fewer or smaller instances")
        key = tuple(self._index)
        with _recent_lock:
            ref = _recent.get(key)
            hit = None if ref is None else ref()
            if hit is not None:
                _recent.move_to_end(key)
                return (("uData", hit),)
        flat = np.zeros((-(-self.size // DATA_WIDTH) * DATA_WIDTH, 4), dtype=np.float32)
        at = 0
        for chunk in self.chunks:
            flat[at:at + len(chunk)] = chunk
            at += len(chunk)
        table = flat.reshape(-1, DATA_WIDTH, 4)
        table.flags.writeable = False
        with _recent_lock:
            _recent[key] = weakref.ref(table)
            while len(_recent) > RECENT_TEXTURES:
                _recent.popitem(last=False)
        return (("uData", table),)


class OriginOffsets:
    """The uniforms uOrg0, uOrg1, ... of a shader whose origin moves (unbounded scenes and
    scenes with live parameters, see :func:`sdfgl.compiler.analysis.moving_origin`): each is
    ``origin + offset - sum(live offsets)`` for a point met in map() (the root itself, a
    translation, a grid's centre), summed in float64 on the CPU at every draw. The float32
    point a node sees is then one rounding away from exact wherever the origin is, and
    moving the camera or a parameter (which moves the origin) changes uniforms, never the
    source."""

    def __init__(self) -> None:
        self.entries: list[OriginEntry] = []
        self._index: dict[tuple, int] = {}

    def uniform(self, offset: np.ndarray, lives: tuple[Live, ...], along: np.ndarray | None = None,
                period: np.ndarray | None = None, frame: np.ndarray | None = None) -> str:
        """The uniform's name for this offset (one per distinct offset); ``frame``: the sum is
        turned by this rotation; ``along``: only its component along this unit axis is kept;
        ``period``: reduced modulo these periods on the axes where they are > 0 (see
        Emitter.point and Emitter.rotate)."""
        key = (np.asarray(offset, dtype=np.float64).tobytes(), tuple(id(x) for x in lives),
               *(None if a is None else a.tobytes() for a in (along, period, frame)))
        if key not in self._index:
            self._index[key] = len(self.entries)
            self.entries.append((np.array(offset, dtype=np.float64), lives, along, period, frame))
        return f"uOrg{self._index[key]}"


def origin_values(entries: Sequence[OriginEntry], origin: np.ndarray) -> dict[str, tuple]:
    """The uOrgN uniform values for the shader origin ``origin`` (float64), at the current
    parameter values."""
    out = {}
    for i, (off, lives, along, period, frame) in enumerate(entries):
        v = np.asarray(origin, dtype=np.float64) + off
        for live in lives:
            v = v - np.broadcast_to(np.asarray(live.value, dtype=np.float64), (3,))
        if frame is not None:
            v = frame @ v
        if along is not None:
            v = (v @ along) * along
        if period is not None:
            v = reduce_modulo(v, period)
        out[f"uOrg{i}"] = tuple(float(x) for x in v)
    return out


def reduce_modulo(v: np.ndarray, period: np.ndarray) -> np.ndarray:
    """``v`` (float64) less the nearest whole number of periods on each axis whose period is
    > 0 (the others unchanged): in -period/2..period/2 there, so float32 holds it as finely
    as the cell it falls in, wherever the point lies."""
    v, s = np.asarray(v, dtype=np.float64), np.asarray(period, dtype=np.float64)
    safe = np.where(s > 0, s, 1.0)
    return np.where(s > 0, v - safe * np.round(v / safe), v)
