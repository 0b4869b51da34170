"""The GLSL dialects sdfgl writes: desktop GLSL 3.30 core and WebGL2's GLSL ES 3.00.

Every .glsl file under ``shaders/`` is written in the common subset of the two (explicit
int/float conversions, no desktop-only built-ins), so both targets use the same files;
what the languages force to differ is kept here and nowhere else: the ``#version``
line, ES's default precisions (a fragment shader's float has none, its int and
sampler default to mediump and lowp, too little for distances and float textures), and
the data tables' sampler (a buffer texture on the desktop, a 2D texture in ES).
"""
from __future__ import annotations

from dataclasses import dataclass

from ..errors import ParameterError


@dataclass(frozen=True)
class Dialect:
    """How one target's shaders begin."""

    name: str
    version: str
    precision: tuple[str, ...] = ()
    libs: tuple[tuple[str, str], ...] = ()  # shaders/lib files this dialect reads in another file's form

    def lib(self, name: str) -> str:
        """The shaders/lib file that stands for ``name`` in this dialect."""
        return dict(self.libs).get(name, name)

    def header(self) -> str:
        """The lines every shader of this dialect starts with."""
        return "\n".join((self.version, *self.precision))

    def convert(self, source: str) -> str:
        """A shader file written for desktop GLSL (``#version 330 core`` on its first line) in this dialect."""
        first, _, rest = source.partition("\n")
        if first.strip() != DESKTOP.version:
            raise ParameterError(f"shader does not start with '{DESKTOP.version}': {first.strip()!r}")
        return f"{self.header()}\n{rest}"


# desktop data tables are buffer textures (samplerBuffer: a cheaper fetch; ES 3.00 has none)
DESKTOP = Dialect("desktop", "#version 330 core", libs=(("data_table", "data_buffer"),))
WEBGL2 = Dialect("webgl2", "#version 300 es",
                 ("precision highp float;", "precision highp int;", "precision highp sampler2D;"))
DIALECTS = {d.name: d for d in (DESKTOP, WEBGL2)}


def dialect(name: str) -> Dialect:
    """The dialect called ``name`` ("desktop" or "webgl2")."""
    try:
        return DIALECTS[name]
    except KeyError:
        raise ParameterError(f"unknown GLSL dialect {name!r}; choose from {', '.join(DIALECTS)}") from None


def of_source(text: str) -> Dialect:
    """The dialect a complete shader source is written in, from its ``#version`` line."""
    first = text.lstrip().partition("\n")[0].strip()
    for d in DIALECTS.values():
        if first == d.version:
            return d
    raise ParameterError(f"shader starts with an unknown version line {first!r}")
