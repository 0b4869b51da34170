"""Text over the viewer's image laid out to stay legible at any window size."""
from __future__ import annotations

from typing import Any

from PIL import Image, ImageDraw, ImageFont

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


def overlay_image(text: str, x0: int, size: tuple[int, int], error: bool,
                  shorter: tuple[str, str] | None = None) -> tuple[Image.Image, int | None, bool]:
    """A transparent RGBA image of ``size`` with ``text`` on a dark box at (x0, 10), laid out by
    :func:`layout_text` (``shorter`` as there), red for an ``error``; and the font size used
    (None: no text) and whether all of the text fits."""
    img = Image.new("RGBA", size, (0, 0, 0, 0))
    if not text:
        return img, None, True
    draw = ImageDraw.Draw(img)
    x0 = x0 if x0 + 200 < size[0] else 10  # a narrow view: over the panel rather than clipped
    font, shown, fits = layout_text(draw, text, size[0] - x0 - 10, size[1] - 20, shorter=shorter)
    box = draw.multiline_textbbox((x0, 10), shown, font=font)
    draw.rectangle((box[0] - 6, box[1] - 6, box[2] + 6, box[3] + 6), fill=(0, 0, 0, 170))
    draw.multiline_text((x0, 10), shown, font=font, fill=(255, 120, 110, 255) if error else (235, 235, 235, 255))
    return img, font.size, fits
