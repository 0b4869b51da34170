"""A triply periodic sheet: the gyroid, thickened into a solid (a bound)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..values import validate as v
from .base import INF, Primitive

if TYPE_CHECKING:  # pragma: no cover
    from ..compiler.emitter import Emitter


class Gyroid(Primitive):
    """The gyroid sheet sin x cos y + sin y cos z + sin z cos x = 0 at ``frequency`` (radians
    per unit), ``thickness`` thick: |g| / (f sqrt 6) - t / 2, a 1-Lipschitz bound. Unbounded:
    intersect it with a solid."""

    kind = "gyroid"
    exact = False
    lib = ("sd_gyroid",)

    def __init__(self, frequency: float = 2 * math.pi, thickness: float = 0.1) -> None:
        f = v.scalar(self.kind, "frequency", frequency, positive=True)
        t = v.scalar(self.kind, "thickness", thickness, positive=True)
        super().__init__(frequency=f, thickness=t)
        self.f, self.t = f, t

    def _expr(self, em: "Emitter", p: str) -> str:
        return f"sdGyroid({p}, {em.num(self.f)}, {em.num(self.t * 0.5)})"

    def _distance(self, p: np.ndarray) -> np.ndarray:
        q = p * float(self.f)
        g = np.sum(np.sin(q) * np.cos(q[..., [1, 2, 0]]), axis=-1)
        return np.abs(g) / (float(self.f) * 2.44948974) - float(self.t) * 0.5

    @property
    def _bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.full(3, -INF), np.full(3, INF)


def gyroid(frequency: float = 2 * math.pi, thickness: float = 0.1) -> Gyroid:
    """An infinite gyroid sheet (a bound); intersect it with a solid.

    Args:
        frequency: radians per unit length (2 pi: one period per unit), > 0.
        thickness: the sheet's thickness, > 0.

    Example:
        >>> part = sg.gyroid(6.283, 0.1) & sg.sphere(1)
        >>> part.exactness, float(part.distance((3, 0, 0)))
        ('bound', 2.0)
    """
    return Gyroid(frequency, thickness)
