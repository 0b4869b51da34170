"""The generated shader's text and float formatting: the leaf of the compiler.

This is the one module of :mod:`sdfgl.compiler` that :mod:`sdfgl.gl` imports (a program is
built from a :class:`ShaderSource`); it imports nothing else of the compiler.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..params import Param

# one offset behind a uOrgN uniform of a moving origin (see sdfgl.compiler.tables.OriginOffsets):
# (float64 offset, live offsets to subtract, unit axis to project on, periods to reduce by,
# rotation to turn by; each None where unused): see OriginOffsets.uniform
OriginEntry = tuple[np.ndarray, tuple[Any, ...], "np.ndarray | None", "np.ndarray | None", "np.ndarray | None"]


def glsl_float(x: float) -> str:
    """A GLSL float literal that round-trips the float32 value of ``x``."""
    f = float(np.float32(x))
    s = f"{f:.9g}"
    if not any(ch in s for ch in ".e"):
        s += ".0"
    return s


def comment_text(text: object) -> str:
    """``text`` made safe for a ``//`` comment of generated GLSL: printable ASCII stays, and
    every other character (a newline or backslash that would end or continue the comment
    line, a control or non-ASCII character a driver may refuse) becomes ``?``. Every comment
    that carries a name or value from a scene goes through here."""
    return "".join(ch if " " <= ch <= "~" and ch != "\\" else "?" for ch in str(text))


@dataclass(frozen=True)
class ShaderSource:
    """A generated fragment shader plus the owner (node path or file) of every line.

    ``params`` are the live parameters behind uniforms uP0, uP1, ...; ``live_bounds`` says
    the scene box is a uniform (it moves with the parameters)."""

    text: str
    owners: tuple[str, ...]
    params: tuple[Param, ...] = ()
    live_bounds: bool = False
    data: tuple[tuple[str, np.ndarray], ...] = ()  # sampler name -> float32 RGBA texels (rows, width, 4)
    code_size: int = 0  # characters of scene code (map(), mapColor(), their functions and helpers)
    grid_min: int = 0   # the fewest instances a union kept as data had to have
    choice: str = "code"  # how the scene was written: "code", or "data (...)" when over the budget
    data_unions: int = 0  # unions kept as data (grids) in this shader
    # a moving origin (see sdfgl.compiler.analysis.moving_origin): the offsets behind uOrg0,
    # uOrg1, ... (sdfgl.compiler.tables.origin_values turns them into uniform values); the
    # source then does not depend on the origin
    origin_offsets: tuple[OriginEntry, ...] | None = None
    coarse_tile: int = 0  # the tile side of the coarse pass the march starts from (0: none)
    ground: bool = False  # the image has the analytic ground plane

    def owner_of(self, line: int) -> str:
        """Who wrote 1-based source line ``line``."""
        return self.owners[line - 1] if 1 <= line <= len(self.owners) else "(unknown line)"
