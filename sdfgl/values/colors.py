"""Colours as users write them: 0..1 floats, 0..255 integers, hex strings and CSS names.

Floats in [0, 1] are linear values, as the shader uses them (it gamma-encodes at the
end). Hex strings, CSS/X11 names and 0..255 integer triples are what colour pickers
give: sRGB-encoded, so they are decoded to linear here and render as the colour named.
"""
from __future__ import annotations

from numbers import Integral, Real
from typing import Any

import numpy as np

from ..errors import ParameterError
from .float32 import FLOAT32_MAX
from .live import LiveValue


def srgb_to_linear(c: np.ndarray) -> np.ndarray:
    """The sRGB transfer function inverted (components in [0, 1])."""
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(c: np.ndarray) -> np.ndarray:
    """The sRGB transfer function (components in [0, 1]): what file formats that store sRGB
    colours (3MF's display colours) are given."""
    c = np.clip(np.asarray(c, dtype=np.float64), 0.0, 1.0)
    return np.where(c <= 0.0031308, c * 12.92, 1.055 * c ** (1 / 2.4) - 0.055)


def parse(node: str, name: str, value: Any) -> tuple[float, float, float]:
    """A linear RGB triple from a colour in any accepted form; ParameterError naming ``node.name``.

    Accepted: "#rgb", "#rrggbb", a CSS colour name ("steelblue"), a triple of 0..255
    integers (with some component above 1), or a triple of numbers in [0, 1] (linear).
    """
    if isinstance(value, str):
        from PIL import ImageColor
        try:
            rgb = ImageColor.getrgb(value.strip())
        except ValueError:
            raise ParameterError(f"{node}: parameter '{name}' is not a colour: {value!r} (use '#rrggbb', "
                                 f"'#rgb', a CSS name such as 'steelblue', 0..255 integers or 0..1 floats)") from None
        return tuple(float(x) for x in srgb_to_linear(np.array(rgb[:3]) / 255.0))  # type: ignore[return-value]
    if isinstance(value, (bytes, dict)) or not hasattr(value, "__len__"):
        raise ParameterError(f"{node}: parameter '{name}' must be a colour (a name, '#rrggbb' or three numbers), "
                             f"got {type(value).__name__} {value!r}")
    items = list(value)
    if len(items) != 3:
        raise ParameterError(f"{node}: parameter '{name}' must have 3 components, got {len(items)}")
    for i, x in enumerate(items):
        if isinstance(x, bool) or not isinstance(x, (Real, np.floating, np.integer)) or not abs(x) <= FLOAT32_MAX:
            raise ParameterError(f"{node}: parameter '{name}[{i}]' must be a finite number, got {x!r}")
    ints = all(isinstance(x, (Integral, np.integer)) for x in items)
    if ints and any(int(x) > 1 for x in items):
        if any(not 0 <= int(x) <= 255 for x in items):
            raise ParameterError(f"{node}: 0..255 colour components must lie in 0..255, got {tuple(items)}")
        return tuple(float(x) for x in srgb_to_linear(np.array(items, dtype=float) / 255.0))  # type: ignore[return-value]
    c = tuple(float(x) for x in items)
    if any(x < 0 or x > 1 for x in c):
        raise ParameterError(f"{node}: colour components must lie in [0, 1] (linear floats) or be 0..255 integers, "
                             f"got {c}")
    return c  # type: ignore[return-value]


def parse_or_live(node: str, name: str, value: Any) -> Any:
    """Like :func:`parse`, but a live 3-vector parameter passes through (checked by the caller)."""
    if isinstance(value, LiveValue):
        return value
    return parse(node, name, value)
