"""Screenshots of the view: asked for now, saved by the window once a render thread has
finished the image (all samples accumulated), at the view's size, without overlay or panel."""
from __future__ import annotations

import time
from pathlib import Path
from typing import Callable

import numpy as np
from PIL import Image

from ..errors import SdfglError
from .render_thread import Exchange


class Screenshots:
    """Numbered PNG files in ``directory``."""

    def __init__(self, directory: str | Path) -> None:
        self.directory = Path(directory)
        self.asked = 0

    def ask(self, exchange: Exchange) -> Path:
        """The path the next finished image will be saved to (the render threads are told)."""
        try:
            self.directory.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise SdfglError(f"cannot write screenshots to '{self.directory}': {exc}") from exc
        self.asked += 1
        path = self.directory / f"sdfgl-{time.strftime('%Y%m%d-%H%M%S')}-{self.asked - 1:03d}.png"
        with exchange.cond:
            exchange.shot_paths.append(str(path))
            exchange.cond.notify_all()
        return path

    @staticmethod
    def save(paths: list[str], img: np.ndarray, on_error: Callable[[str], None]) -> list[str]:
        """Write ``img`` (a render thread finished it) to each of ``paths``; the paths written.
        A failure goes to ``on_error``."""
        saved = []
        for path in paths:
            try:
                Image.fromarray(img).save(path)
            except OSError as exc:
                on_error(f"cannot write screenshot '{path}': {exc}")
                continue
            saved.append(path)
            print(f"sdfgl: saved {path}")
        return saved
