"""The background of misses: the default sky, one colour, or a top-to-bottom gradient."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..errors import ParameterError
from ..values.colors import parse


@dataclass(frozen=True)
class Background:
    """kind "sky" (the default environment: horizon, zenith and below-horizon colours by
    ray elevation), "color" (colors[0]) or "gradient" (colors[0] at the top of the image
    to colors[1] at the bottom); colours are linear RGB."""

    kind: str = "sky"
    colors: tuple[tuple[float, float, float], ...] = ()


def check_background(value: Any) -> Background:
    """The ``background`` setting: None or "sky", a colour, or a (top, bottom) pair of colours."""
    if value is None or (isinstance(value, str) and value == "sky"):
        return Background()
    if isinstance(value, Background):
        return value
    if isinstance(value, (tuple, list)) and len(value) == 2:
        return Background("gradient", (parse("setting 'background'", "top", value[0]),
                                       parse("setting 'background'", "bottom", value[1])))
    try:
        return Background("color", (parse("setting 'background'", "color", value),))
    except ParameterError as exc:
        raise ParameterError(f"{exc} -- 'background' takes None/'sky', a colour, or a (top, bottom) pair of "
                             f"colours; alpha=True makes it transparent") from None
