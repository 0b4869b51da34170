"""Lights of a path-traced render: a sky (environment map) and a sun (directional light).

The defaults match the real-time renderer's look: the sky is its background gradient
(horizon to zenith above, horizon to a warm grey below) and the sun comes from its key
light's direction with its colour. The sky is a latitude-longitude bitmap that depends
on the height of the direction only; :meth:`Sky.radiance` gives the same colours for
compositing the visible background, so the path tracer's hidden environment and the
image's background are one function.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError

KEY_DIRECTION = (0.5, 0.7, 0.4)          # towards the light, as the real-time key light
KEY_COLOR = (1.0, 0.92, 0.8)


def _rgb(owner: str, name: str, value: object) -> tuple[float, float, float]:
    try:
        rgb = tuple(float(c) for c in value)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        rgb = ()
    if len(rgb) != 3 or not all(np.isfinite(rgb)) or min(rgb) < 0:
        raise ParameterError(f"pbr {owner}: parameter '{name}' must be three numbers >= 0, got {value!r}")
    return rgb  # type: ignore[return-value]


@dataclass(frozen=True)
class Sky:
    """An environment that varies with height: ``horizon`` to ``zenith`` above, ``horizon``
    to ``below`` under the horizon (linear RGB radiance, as the image's background).

    ``intensity`` scales the sky as a light only (default 0.45, so that with the default
    sun the balance of direct and sky light is the real-time renderer's, whose sky fill
    is dimmer than its background); the background is drawn at the colours given.
    """

    horizon: tuple[float, float, float] = (0.86, 0.88, 0.91)
    zenith: tuple[float, float, float] = (0.38, 0.56, 0.84)
    below: tuple[float, float, float] = (0.55, 0.54, 0.52)
    intensity: float = 0.45

    def __post_init__(self) -> None:
        for name in ("horizon", "zenith", "below"):
            object.__setattr__(self, name, _rgb("sky", name, getattr(self, name)))
        if not (isinstance(self.intensity, (int, float)) and 0 <= self.intensity < 1e6):
            raise ParameterError(f"pbr sky: parameter 'intensity' must be a number in [0, 1e6), got {self.intensity!r}")

    def radiance(self, directions: np.ndarray) -> np.ndarray:
        """Linear RGB background colour seen along unit ``directions`` (..., 3)."""
        h = np.clip(directions[..., 1:2], -1.0, 1.0)
        up = np.asarray(self.horizon) + (np.asarray(self.zenith) - self.horizon) * np.sqrt(np.maximum(h, 0))
        down = np.asarray(self.horizon) + (np.asarray(self.below) - self.horizon) * np.sqrt(np.maximum(-h, 0))
        return np.where(h >= 0, up, down)

    def bitmap(self, height: int = 256) -> np.ndarray:
        """A latitude-longitude image (height x 2 height x 3) for Mitsuba's ``envmap``
        (lighting: radiance times ``intensity``): row v looks along height cos(pi v)."""
        v = (np.arange(height) + 0.5) / height
        y = np.cos(np.pi * v)
        d = np.zeros((height, 3))
        d[:, 1] = y
        rows = (self.radiance(d) * self.intensity).astype(np.float32)
        return np.ascontiguousarray(np.broadcast_to(rows[:, None, :], (height, 2 * height, 3)))


@dataclass(frozen=True)
class Sun:
    """A directional light from ``direction`` (pointing towards the light) with linear RGB
    ``color`` times ``intensity`` as irradiance (the default, pi, makes a white diffuse
    surface facing the sun as bright as the real-time key light does)."""

    direction: tuple[float, float, float] = KEY_DIRECTION
    color: tuple[float, float, float] = KEY_COLOR
    intensity: float = math.pi

    def __post_init__(self) -> None:
        d = np.asarray(_rgb_any("sun", "direction", self.direction))
        if not np.linalg.norm(d) > 0:
            raise ParameterError(f"pbr sun: parameter 'direction' must be a non-zero vector, got {self.direction!r}")
        object.__setattr__(self, "direction", tuple((d / np.linalg.norm(d)).tolist()))
        object.__setattr__(self, "color", _rgb("sun", "color", self.color))
        if not (isinstance(self.intensity, (int, float)) and 0 <= self.intensity < 1e6):
            raise ParameterError(f"pbr sun: parameter 'intensity' must be a number in [0, 1e6), got {self.intensity!r}")

    def emitter(self) -> dict:
        return {"type": "directional", "direction": [-x for x in self.direction],
                "irradiance": {"type": "rgb", "value": [c * self.intensity for c in self.color]}}


def _rgb_any(owner: str, name: str, value: object) -> tuple[float, float, float]:
    try:
        v = tuple(float(c) for c in value)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        v = ()
    if len(v) != 3 or not all(np.isfinite(v)):
        raise ParameterError(f"pbr {owner}: parameter '{name}' must be three finite numbers, got {value!r}")
    return v  # type: ignore[return-value]
