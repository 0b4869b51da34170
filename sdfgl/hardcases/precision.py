"""Hard cases of float32 precision: thin walls' normals, endless repetition far from the origin,
tiny near objects before a far backdrop."""
from __future__ import annotations

from .spec import HardCase

PRECISION_CASES: tuple[HardCase, ...] = ()
