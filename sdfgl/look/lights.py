"""Directional and point lights (validated values; their GLSL is written by look.shading)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from ..errors import ParameterError
from ..values import validate as v
from ..values.colors import parse

MAX_LIGHTS = 8  # each light is unrolled code (and a shadow march), so the count is capped
SHADOW_KINDS = (None, False, "hard", "soft")


@dataclass(frozen=True)
class Light:
    """One light. Build with :func:`directional_light` or :func:`point_light`.

    kind: "directional" or "point"; vector: unit direction toward the light, or the
    light's position; color: linear RGB; intensity: a factor on the colour; shadow:
    None (follow the ``shadows`` setting), False, "hard" or "soft"; fill: a fill light
    (no highlight, darkened by ambient occlusion instead of a shadow); range: a point
    light's intensity halves at this distance (None: no falloff).
    """

    kind: str
    vector: tuple[float, float, float]
    color: tuple[float, float, float] = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    shadow: Any = None
    fill: bool = False
    range: float | None = None

    def radiance(self) -> tuple[float, float, float]:
        """Colour times intensity."""
        return tuple(c * self.intensity for c in self.color)  # type: ignore[return-value]

    def shadow_kind(self, setting: Any) -> Any:
        """The shadow this light casts under the ``shadows`` setting: False, "hard" or "soft"."""
        if self.fill:
            return False
        return setting if self.shadow is None else self.shadow


def _common(name: str, color: Any, intensity: Any, shadow: Any, fill: Any) -> tuple:
    rgb = parse(name, "color", color)
    inten = v.scalar(name, "intensity", intensity, nonnegative=True)
    v.fixed(name, "lights are compiled into the shader", intensity=inten)
    if shadow is True:
        shadow = "soft"
    if shadow not in SHADOW_KINDS:
        raise ParameterError(f"{name}: parameter 'shadow' must be None (follow the 'shadows' setting), False, "
                             f"'hard' or 'soft', got {shadow!r}")
    if not isinstance(fill, bool):
        raise ParameterError(f"{name}: parameter 'fill' must be True or False, got {fill!r}")
    if fill and shadow:
        raise ParameterError(f"{name}: a fill light casts no shadow (it is darkened by ambient occlusion)")
    return rgb, float(inten), shadow


def directional_light(direction: Sequence[float] = (0.5, 0.7, 0.4), color: Any = "white", intensity: float = 1.0,
                      shadow: Any = None, fill: bool = False) -> Light:
    """A light infinitely far away in ``direction`` (pointing from the scene toward the light).

    Args:
        direction: toward the light (normalised; not zero).
        color: a colour: "#rrggbb", a CSS name, 0..255 integers or 0..1 floats (linear).
        intensity: a factor on the colour, >= 0.
        shadow: None (follow the ``shadows`` setting), False, "hard" or "soft".
        fill: a fill light: no highlight, darkened by ambient occlusion, no shadow.

    Lights are compiled into the shader (changing one recompiles); pass up to 8 as
    ``render(..., lights=[...])``.

    Example:
        >>> key = sg.directional_light((0, 1, 0), "white", 0.8, shadow="soft")
        >>> key.vector, key.intensity
        ((0.0, 1.0, 0.0), 0.8)
    """
    d = v.vector("directional_light", "direction", direction, nonzero=True)
    v.fixed("directional_light", "lights are compiled into the shader", direction=d)
    rgb, inten, sh = _common("directional_light", color, intensity, shadow, fill)
    unit = np.asarray(d, dtype=np.float64) / np.linalg.norm(d)
    return Light("directional", tuple(float(x) for x in unit), rgb, inten, sh, fill)  # type: ignore[arg-type]


def point_light(position: Sequence[float], color: Any = "white", intensity: float = 1.0, shadow: Any = None,
                range: float | None = None, fill: bool = False) -> Light:  # noqa: A002 - the usual word
    """A light at ``position``.

    Args:
        position: the light's position (x, y, z).
        color: a colour, as for :func:`directional_light`.
        intensity: a factor on the colour, >= 0.
        shadow: None (follow the ``shadows`` setting), False, "hard" or "soft".
        range: None (no falloff), or the distance d at which the intensity halves: it falls
            as 1 / (1 + (d / range)^2).
        fill: a fill light: no highlight, darkened by ambient occlusion, no shadow.

    Example:
        >>> lamp = sg.point_light((0, 2, 0), "orange", 1.5, range=3)
        >>> lamp.kind, lamp.range
        ('point', 3.0)
    """
    pos = v.vector("point_light", "position", position)
    v.fixed("point_light", "lights are compiled into the shader", position=pos)
    rgb, inten, sh = _common("point_light", color, intensity, shadow, fill)
    rng = None
    if range is not None:
        rng = float(v.scalar("point_light", "range", range, positive=True))
    return Light("point", tuple(float(x) for x in pos), rgb, inten, sh, fill, rng)  # type: ignore[arg-type]


_KEY = np.array([0.5, 0.7, 0.4]) / math.sqrt(0.9)
# The original look: a warm key light (shadowed per the 'shadows' setting) and a dim back light.
DEFAULT_LIGHTS = (
    Light("directional", (0.52704628, 0.73786479, 0.42163702), (1.0, 0.92, 0.8)),
    Light("directional", tuple(float(x) for x in np.array([-_KEY[0], 0.0, -_KEY[2]]) /  # type: ignore[arg-type]
                               math.hypot(_KEY[0], _KEY[2])), (0.16, 0.14, 0.12), fill=True),
)
DEFAULT_AMBIENT = ((0.3, 0.38, 0.5), (0.0, 0.0, 0.0))  # (sky, ground) hemisphere


def check_lights(value: Any) -> tuple[Light, ...] | None:
    """The ``lights`` setting: None (the default rig) or a sequence of up to MAX_LIGHTS lights."""
    if value is None:
        return None
    if isinstance(value, Light):
        value = (value,)
    if isinstance(value, (str, bytes)) or not isinstance(value, (Sequence, tuple)):
        raise ParameterError(f"setting 'lights' must be None or a list of sg.directional_light / sg.point_light, "
                             f"got {type(value).__name__}")
    lights = tuple(value)
    for i, lt in enumerate(lights):
        if not isinstance(lt, Light):
            raise ParameterError(f"setting 'lights[{i}]' must be made by sg.directional_light or sg.point_light, "
                                 f"got {type(lt).__name__} {lt!r}")
    if len(lights) > MAX_LIGHTS:
        raise ParameterError(f"setting 'lights' holds {len(lights)} lights; at most {MAX_LIGHTS} are supported")
    return lights


def check_ambient(value: Any) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """The ``ambient`` setting: one colour (uniform) or a (sky, ground) pair of colours."""
    if value is None:
        return DEFAULT_AMBIENT
    if isinstance(value, (tuple, list)) and len(value) == 2:
        return parse("setting 'ambient'", "sky", value[0]), parse("setting 'ambient'", "ground", value[1])
    c = parse("setting 'ambient'", "color", value)
    return c, c
