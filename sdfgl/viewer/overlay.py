"""Text over the viewer's image laid out to stay legible at any window size."""
from __future__ import annotations

from typing import Any

from PIL import ImageDraw, ImageFont

MAX_FONT, MIN_FONT = 22, 10  # pixels; below MIN_FONT PIL's default font is not legible


def _wrap(draw: ImageDraw.ImageDraw, text: str, font: Any, width: int) -> str:
    """``text`` with each line broken at spaces so that it fits ``width`` pixels where it can."""
    out = []
    for line in text.split("\n"):
        words, cur = line.split(" "), ""
        for w in words:
            trial = f"{cur} {w}" if cur else w
            if cur and draw.textlength(trial, font=font) > width:
                out.append(cur.rstrip())
                cur = "  " + w  # continuation lines are indented
            else:
                cur = trial
        out.append(cur)
    return "\n".join(out)


def _fits(draw: ImageDraw.ImageDraw, text: str, font: Any, width: int, height: int) -> bool:
    box = draw.multiline_textbbox((0, 0), text, font=font)
    return box[2] - box[0] <= width and box[3] - box[1] <= height


def layout_text(draw: ImageDraw.ImageDraw, text: str, width: int, height: int,
                shorter: tuple[str, str] | None = None) -> tuple[Any, str, bool]:
    """The largest font (MAX_FONT..MIN_FONT px) and the wrapped text that fit ``width`` x ``height``,
    and whether they fit.

    ``shorter`` = (long, short): when ``text`` fits at no legible size, ``long`` in it is replaced by
    ``short`` (the help's short form); when nothing fits, the smallest legible font is used and the
    window clips the rest."""
    candidates = [text]
    if shorter is not None and shorter[0] in text:
        candidates.append(text.replace(*shorter))
    for candidate in candidates:
        for size in range(MAX_FONT, MIN_FONT - 1, -1):
            font = ImageFont.load_default(size=size)
            wrapped = _wrap(draw, candidate, font, width)
            if _fits(draw, wrapped, font, width, height):
                return font, wrapped, True
    font = ImageFont.load_default(size=MIN_FONT)
    return font, _wrap(draw, candidates[-1], font, width), False
