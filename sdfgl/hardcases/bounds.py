"""Hard cases of bounds and signs: polygons kept as an edge grid on round coordinates, n-ary
smooth unions with large blend radii."""
from __future__ import annotations

from .spec import HardCase

BOUNDS_CASES: tuple[HardCase, ...] = ()
