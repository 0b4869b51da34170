"""Frame writers: PNG sequences, GIF, MP4 and WebM, written as frames arrive.

Each writer takes uint8 (H, W, 3) frames one at a time and keeps none of them, so memory
stays flat however long the clip. Files appear atomically: a clip is written under a
temporary name beside the target and renamed when closed (a failed run leaves no
half-written file); each PNG of a sequence is renamed into place when complete.

MP4 (H.264) and WebM (VP9) go through imageio-ffmpeg (the ``sdfgl[video]`` extra), whose
wheel carries its own ffmpeg binary. GIFs are encoded by Pillow frame by frame, each
with its own 256-colour palette.
"""
from __future__ import annotations

import os
import re
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ParameterError, SdfglError
from ..files import cannot_write, commit, temp_path, written_atomically

if TYPE_CHECKING:  # pragma: no cover - Pillow is imported where frames are written
    from PIL import Image

VIDEO_SUFFIXES = {".mp4": "libx264", ".m4v": "libx264", ".mov": "libx264", ".webm": "libvpx-vp9"}
CRF_RANGE = {"libx264": (0, 51), "libvpx-vp9": (0, 63)}  # the quality scale each encoder accepts
FRAME_PATTERN = re.compile(r"%0?\d*d")


def save_image_atomic(image: "Image.Image", path: Path, fmt: str = "PNG") -> None:
    """Write ``image`` to ``path`` whole or not at all (see :mod:`sdfgl.files`)."""
    try:
        with written_atomically(path, "image file") as tmp:
            image.save(tmp, format=fmt)
    except ValueError as exc:
        raise SdfglError(f"cannot write image file '{path}': {exc}") from exc


def check_clip(path: Path, frames: int) -> None:
    """Decode the clip at ``path`` with ffmpeg and check it holds ``frames`` frames (a clip
    cut short by a full disk or a failed encoder has no index and does not decode)."""
    import imageio_ffmpeg
    try:
        found, _ = imageio_ffmpeg.count_frames_and_secs(str(path))
    except (OSError, RuntimeError, ValueError):
        raise SdfglError("the clip ffmpeg wrote does not decode (see ffmpeg's messages above)") from None
    if found != frames:
        raise SdfglError(f"the clip ffmpeg wrote holds {found} of {frames} frames")


class FrameWriter:
    """Base: ``append(frame)`` for each uint8 (H, W, 3) frame, then ``close()`` (or use ``with``)."""

    def __init__(self, path: str | Path, size: tuple[int, int], fps: float) -> None:
        self.path, self.size, self.fps = Path(path), (int(size[0]), int(size[1])), float(fps)
        self.count = 0
        if not self.path.parent.is_dir():
            try:
                self.path.parent.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise SdfglError(f"cannot create the folder of '{self.path}': {exc}") from exc

    def _check(self, frame: np.ndarray) -> np.ndarray:
        w, h = self.size
        if frame.dtype != np.uint8 or frame.shape != (h, w, 3):
            raise ParameterError(f"{type(self).__name__}: frames must be uint8 ({h}, {w}, 3), "
                                 f"got {frame.dtype} {frame.shape}")
        return np.ascontiguousarray(frame)

    def append(self, frame: np.ndarray) -> None:
        self._write(self._check(frame))
        self.count += 1

    def _write(self, frame: np.ndarray) -> None:  # pragma: no cover
        raise NotImplementedError

    def close(self) -> None:
        """Finish the file (the clip appears under its name now)."""

    def abort(self) -> None:
        """Drop what was written (called when rendering fails)."""

    def __enter__(self) -> "FrameWriter":
        return self

    def __exit__(self, exc_type: Any, *_: Any) -> None:
        if exc_type is None:
            self.close()
        else:
            self.abort()


class PngSequenceWriter(FrameWriter):
    """``frames/%04d.png``: one PNG per frame (a folder path gets ``frame_%04d.png`` inside it)."""

    def __init__(self, path: str | Path, size: tuple[int, int], fps: float, start: int = 0) -> None:
        p = Path(path)
        if not FRAME_PATTERN.search(p.name):
            p = p / "frame_%04d.png"
        super().__init__(p, size, fps)
        self.start = start
        self.written: list[Path] = []

    def frame_path(self, i: int) -> Path:
        return self.path.with_name(FRAME_PATTERN.sub(lambda m: m.group(0) % i, self.path.name, count=1))

    def _write(self, frame: np.ndarray) -> None:
        p = self.frame_path(self.start + self.count)
        from PIL import Image
        save_image_atomic(Image.fromarray(frame), p, "PNG")
        self.written.append(p)


class GifWriter(FrameWriter):
    """Animated GIF, looping; each frame quantized to its own palette (dithered) and appended to the file."""

    def __init__(self, path: str | Path, size: tuple[int, int], fps: float, loop: int = 0) -> None:
        super().__init__(path, size, fps)
        self.loop = loop
        self._tmp = temp_path(self.path)
        try:
            self._fp = open(self._tmp, "wb")  # noqa: SIM115 - closed in close()/abort()
        except OSError as exc:
            raise cannot_write("GIF", self.path, exc) from exc
        self._duration = max(20, int(round(1000.0 / self.fps / 10.0)) * 10)  # GIF counts centiseconds

    def _write(self, frame: np.ndarray) -> None:
        from PIL import GifImagePlugin, Image
        im = Image.fromarray(frame).quantize(256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.FLOYDSTEINBERG)
        try:
            if self.count == 0:
                header, _ = GifImagePlugin.getheader(im, info={"loop": self.loop})
                self._fp.write(b"".join(header))
            for chunk in GifImagePlugin.getdata(im, duration=self._duration, disposal=1, include_color_table=True):
                self._fp.write(chunk)
        except OSError as exc:
            self.abort()
            raise cannot_write("GIF", self.path, exc) from exc

    def close(self) -> None:
        if self._fp.closed:
            return
        if self.count == 0:
            self.abort()
            raise SdfglError(f"GIF '{self.path}': no frames were written")
        try:
            self._fp.write(b";")  # trailer
            self._fp.close()
        except OSError as exc:
            self.abort()
            raise cannot_write("GIF", self.path, exc) from exc
        commit(self._tmp, self.path, "GIF")

    def abort(self) -> None:
        try:
            self._fp.close()
        except OSError:
            pass  # the file is dropped anyway
        self._tmp.unlink(missing_ok=True)


class VideoWriter(FrameWriter):
    """MP4 (H.264, yuv420p) or WebM (VP9) through imageio-ffmpeg's own ffmpeg; ``crf`` sets the quality."""

    def __init__(self, path: str | Path, size: tuple[int, int], fps: float, crf: int | None = None) -> None:
        super().__init__(path, size, fps)
        codec = VIDEO_SUFFIXES[self.path.suffix.lower()]
        lo, hi = CRF_RANGE[codec]
        if crf is not None and (isinstance(crf, bool) or not isinstance(crf, int) or not lo <= crf <= hi):
            raise ParameterError(f"video '{self.path.name}': 'crf' must be a whole number in {lo}..{hi} for "
                                 f"{codec}, got {crf!r}")
        try:
            import imageio_ffmpeg
        except ImportError:
            raise SdfglError(f"writing '{self.path.name}' needs imageio-ffmpeg: pip install 'sdfgl[video]'") from None
        if codec == "libx264":
            out = ["-crf", str(18 if crf is None else crf), "-preset", "veryfast", "-movflags", "+faststart"]
        else:  # VP9 in constant-quality mode
            out = ["-crf", str(32 if crf is None else crf), "-b:v", "0", "-row-mt", "1", "-deadline", "realtime",
                   "-cpu-used", "8"]
        self._tmp = temp_path(self.path)
        # yuv420p needs even sizes: macro_block_size=2 lets imageio-ffmpeg round an odd size up
        self._gen = imageio_ffmpeg.write_frames(str(self._tmp), self.size, fps=self.fps, codec=codec, quality=None,
                                                macro_block_size=2, ffmpeg_log_level="error", output_params=out)
        # Start ffmpeg now, before any frame is drawn: its launch forks, and sdfgl's at-fork
        # handler replaces the GL context (see sdfgl.gl.context), which would cost the clip's
        # program a second compile if it came after the first frame.
        try:
            self._gen.send(None)
        except (OSError, RuntimeError) as exc:
            self.abort()
            raise SdfglError(f"video '{self.path}': ffmpeg failed to start: {exc}") from exc

    def _write(self, frame: np.ndarray) -> None:
        try:
            self._gen.send(frame)
        except (OSError, RuntimeError) as exc:
            self.abort()
            raise SdfglError(f"video '{self.path}': ffmpeg failed: {exc}") from exc

    def close(self) -> None:
        if self._gen is None:
            return
        if self.count == 0:
            self.abort()
            raise SdfglError(f"video '{self.path}': no frames were written")
        try:
            self._gen.close()
        except (OSError, RuntimeError) as exc:
            self.abort()
            raise SdfglError(f"video '{self.path}': ffmpeg failed: {exc}") from exc
        self._gen = None
        commit(self._tmp, self.path, "video", check=lambda p: check_clip(p, self.count))

    def abort(self) -> None:
        if self._gen is not None:
            try:
                self._gen.close()
            except (OSError, RuntimeError):
                pass
            self._gen = None
        self._tmp.unlink(missing_ok=True)


def open_writer(path: str | Path, size: tuple[int, int], fps: float, **options: Any) -> FrameWriter:
    """The writer for ``path``: ``.mp4/.m4v/.mov/.webm`` video, ``.gif``, or a PNG sequence
    (``frames/%04d.png``, or a folder)."""
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix in VIDEO_SUFFIXES:
        return VideoWriter(p, size, fps, **options)
    if suffix == ".gif":
        return GifWriter(p, size, fps, **options)
    if FRAME_PATTERN.search(p.name) or suffix == "" or p.is_dir():
        if suffix not in ("", ".png"):
            raise ParameterError(f"animate: frame sequences are written as PNG, got '{p.name}'")
        return PngSequenceWriter(p, size, fps, **options)
    raise ParameterError(f"animate: cannot tell the format of '{p}': use .mp4, .webm, .gif, "
                         "a pattern like frames/%04d.png, or a folder")
