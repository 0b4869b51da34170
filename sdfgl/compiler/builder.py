"""Assembling a shader's text line by line, each line with its owner (a node path or a file)."""
from __future__ import annotations

from typing import Sequence

import numpy as np

from .. import shaderlib
from ..params import Param
from .emitter import Emitter
from .source import ShaderSource, glsl_float


class SourceBuilder:
    """The lines of one shader and who wrote each (see :meth:`ShaderSource.owner_of`)."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.owners: list[str] = []

    def add(self, text: str, owner: str) -> None:
        """Append ``text`` (one or more lines), every line owned by ``owner``."""
        for line in text.rstrip("\n").split("\n"):
            self.lines.append(line)
            self.owners.append(owner)

    def add_file(self, name: str) -> None:
        """Append ``shaders/<name>.glsl``."""
        self.add(shaderlib.read(name), f"shaders/{name}.glsl")

    def build(self, params: Sequence[Param] = (), live_bounds: bool = False,
              data: Sequence[tuple[str, np.ndarray]] = ()) -> ShaderSource:
        """The source so far."""
        return ShaderSource("\n".join(self.lines) + "\n", tuple(self.owners), tuple(params), live_bounds,
                            tuple(data))

    def size_since(self, start: int) -> int:
        """Characters added since line ``start``."""
        return sum(len(x) + 1 for x in self.lines[start:])

    def add_helpers(self, em: Emitter, done: set[str]) -> None:
        """Append the GLSL functions ``em`` collected (subtrees, unions kept as data) not yet in ``done``."""
        for name, lines in em.functions.values():
            if name not in done:
                done.add(name)
                for code, owner in lines:
                    self.add(code, owner)

    def add_function(self, signature: str, em: Emitter, result: str, ret: str) -> None:
        """Append the function ``signature`` with ``em``'s lines, returning ``ret`` formatted with ``result``."""
        self.add(signature + " {", "(codegen)")
        for code, owner in em.lines:
            self.add(code, owner)
        self.add(f"    return {ret.format(result)};\n}}", "(codegen)")


def surface_function(channels: Sequence[str]) -> str:
    """GLSL of ``Surface sceneSurface(vec3 p)``: the material at a hit."""
    spec = "sf.x, sf.y, sf.z" if "surface" in channels else "DEFAULT_SPECULAR, DEFAULT_SHININESS, 0.0"
    emis = "mapEmission(p)" if "emission" in channels else "vec3(0.0)"
    head = "    vec3 sf = mapSurface(p);\n" if "surface" in channels else ""
    return f"Surface sceneSurface(vec3 p) {{\n{head}    return Surface(mapColor(p), {spec}, {emis});\n}}"


def vec3_literal(v: Sequence[float]) -> str:
    """A GLSL vec3 of float32 constants."""
    return f"vec3({', '.join(glsl_float(float(x)) for x in v)})"
