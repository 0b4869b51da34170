"""Hard cases of the marcher's acceptance: near objects before far straight surfaces, Newton steps
near the clip box's exit, critical points of implicit fields outside the solid, fine displacement."""
from __future__ import annotations

from .spec import HardCase

MARCHING_CASES: tuple[HardCase, ...] = ()
