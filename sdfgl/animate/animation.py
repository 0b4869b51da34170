"""sg.animate(): render a clip frame by frame into a writer, with one shader program for all frames.

Per frame only uniforms change: the clock (every ``sg.time()`` in the scene), the camera
(from a path) and the live parameters over them. The program cache is keyed by source,
and the source does not depend on either, so the first frames compile (the image's program, or
where the image has a coarse pass that pass's, the image's in the first frame and the other
tile programs in the second) and the rest draw.
"""
from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Sequence

from ..camera import Camera, OrbitCamera
from ..errors import ParameterError
from ..nodes.base import Node
from ..params import Time
from ..render import Renderer, checked_size, default_renderer
from .paths import CameraPath
from .progress import ProgressBar
from .writers import VIDEO_SUFFIXES, FrameWriter, open_writer

CameraSpec = Camera | CameraPath | Callable[[float], Camera] | None
MAX_FRAMES = 216_000  # frames in one clip: an hour at 60 fps (a longer one is refused before any work)


@dataclass
class AnimationResult:
    """What ``animate`` wrote and how long it took."""

    path: Path
    frames: int
    fps: float
    size: tuple[int, int]
    compiles: int                        # shader programs compiled during the clip (the first frames': 5 at most)
    seconds: float                       # wall time of the whole clip
    render_s: list[float] = field(default_factory=list)   # per frame: render() incl. read-back
    write_s: list[float] = field(default_factory=list)    # per frame: handing the frame to the writer

    @property
    def frames_per_second(self) -> float:
        return self.frames / self.seconds if self.seconds > 0 else 0.0


def clocks(scene: Node) -> list[Time]:
    """The ``sg.time()`` parameters the scene reads."""
    return [p for p in scene.live_params() if isinstance(p, Time)]


def set_time(scene_clocks: Sequence[Time], t: float, frame: int | None = None) -> None:
    """Set every clock to ``t``; a node that refuses the resulting values is named with the frame and time."""
    for c in scene_clocks:
        try:
            c.value = t
        except ParameterError as exc:
            where = f"frame {frame} (t = {t:.4g} s)" if frame is not None else f"t = {t:.4g} s"
            raise ParameterError(f"animate: at {where}: {exc}") from None


def camera_at(camera: CameraSpec, t: float, duration: float, scene: Node) -> Camera:
    """The camera for time ``t`` from a fixed camera, a path, a function of t, or None (framing the scene)."""
    if camera is None:
        return OrbitCamera.framing(*scene.bounds)
    if isinstance(camera, Camera):
        return camera
    if isinstance(camera, CameraPath):
        return camera.camera(t, duration, scene)
    if callable(camera):
        cam = camera(t)
        if not isinstance(cam, Camera):
            raise ParameterError(f"animate: the camera function returned {type(cam).__name__} at t = {t:g}, "
                                 "not an sdfgl Camera")
        return cam
    raise ParameterError(f"animate: 'camera' must be a Camera, a path (sg.turntable, sg.camera_path) or a "
                         f"function of time, got {type(camera).__name__}")


def clip_frames(seconds: Any, fps: float, frames: Any = None) -> int:
    """The frame count of a clip: ``frames``, or ``seconds * fps`` rounded; at least 1 and at
    most :data:`MAX_FRAMES`, else ParameterError naming the value."""
    if frames is None:
        if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) or not math.isfinite(seconds) \
                or seconds <= 0:
            raise ParameterError(f"animate: 'seconds' must be a finite number > 0, got {seconds!r}")
        count = seconds * fps
        if count > MAX_FRAMES:
            raise ParameterError(f"animate: {seconds:g} s at {fps:g} fps is {count:.4g} frames, more than the limit of "
                                 f"{MAX_FRAMES} (an hour at 60 fps); render a long clip in parts (start=)")
        n = round(count)
    else:
        n = frames
        if isinstance(n, bool) or not isinstance(n, int):
            raise ParameterError(f"animate: 'frames' must be a whole number, got {frames!r}")
        if n > MAX_FRAMES:
            raise ParameterError(f"animate: {n} frames is more than the limit of {MAX_FRAMES} (an hour at 60 fps); "
                                 f"render a long clip in parts (start=)")
    if n < 1:
        raise ParameterError(f"animate: the clip must have at least one frame (seconds={seconds!r}, fps={fps!r}, "
                             f"frames={frames!r})")
    return n


def animate(scene: Node, output: str | Path | FrameWriter, seconds: float = 4.0, fps: float = 30.0,
            camera: CameraSpec = None, size: Sequence[int] = (640, 360), start: float = 0.0,
            frames: int | None = None, progress: bool = False, renderer: Renderer | None = None,
            crf: int | None = None, **settings: Any) -> AnimationResult:
    """Render ``scene`` frame by frame into a video, GIF or PNG sequence.

    Every ``sg.time()`` the scene reads is set to ``start + i / fps`` for frame i; the
    shader is compiled once for the clip (times, keyframes and cameras are uniforms). Every
    frame's time is checked against the scene's nodes, and the camera at the first and last
    frame is built, before the first frame is drawn, so a bad value fails in milliseconds.

    Args:
        scene: the sdfgl node to render.
        output: ``.mp4`` / ``.webm`` (needs ``sdfgl[video]``), ``.gif``, a PNG pattern such
            as ``frames/%04d.png`` or a folder (PNG frames), or a ``FrameWriter``.
        seconds: clip length in seconds (frames = round(seconds * fps)).
        fps: frames per second, in (0, 1000].
        camera: a Camera, a path (``sg.turntable(...)``, ``sg.camera_path(...)``), a
            function of the clip time in seconds returning a Camera, or None (frame the scene).
        size: (width, height) of each frame in pixels.
        start: the clock's time at frame 0, in seconds (camera paths still start at 0).
        frames: the frame count, overriding ``seconds * fps`` (1 to :data:`MAX_FRAMES`, an
            hour at 60 fps; render a longer clip in parts with ``start``).
        progress: print a progress bar on stderr.
        renderer: the ``Renderer`` to draw with (default: the shared one).
        crf: video quality, lower is better: 0..51 for MP4 (x264, default 18), 0..63 for
            WebM (VP9, default 32); videos only.
        settings: render()'s settings (``aa``, ``shadows``, ``ao``, ``ground``, ...).

    Returns an :class:`AnimationResult`: the path written, frame count, fps, size, shader
    compiles during the clip (the first two frames': the coarse pass and the image's tile
    programs, 5 at most) and wall times per frame.

    Example:
        >>> import pathlib, tempfile
        >>> t = sg.time()
        >>> with tempfile.TemporaryDirectory() as d:
        ...     res = sg.animate(sg.sphere(1 + 0.2 * sg.sin(t)), pathlib.Path(d) / "pulse.gif",
        ...                      seconds=0.5, fps=4, size=(16, 16))
        >>> res.frames, res.compiles
        (2, 3)
    """
    if not isinstance(scene, Node):
        raise ParameterError(f"animate: 'scene' must be an sdfgl node, got {type(scene).__name__}")
    wh = checked_size(size)
    if isinstance(fps, bool) or not (isinstance(fps, (int, float)) and 0 < fps <= 1000):
        raise ParameterError(f"animate: 'fps' must be a number in (0, 1000], got {fps!r}")
    n = clip_frames(seconds, fps, frames)
    if isinstance(start, bool) or not isinstance(start, (int, float)) or not math.isfinite(start):
        raise ParameterError(f"animate: 'start' must be a finite number of seconds, got {start!r}")
    if crf is not None and not isinstance(output, FrameWriter) and Path(output).suffix.lower() not in VIDEO_SUFFIXES:
        raise ParameterError(f"animate: 'crf' sets the quality of a video (.mp4, .webm); '{Path(output).name}' "
                             f"is not one")
    duration = n / fps
    times = [start + i / fps for i in range(n)]
    scene_clocks = clocks(scene)
    if scene_clocks:  # check every frame's values now, not after minutes of rendering
        old = [c.value for c in scene_clocks]
        try:
            for i, t in enumerate(times):
                set_time(scene_clocks, t, i)
        finally:
            for c, v in zip(scene_clocks, old):
                c.value = v
    for t in (times[0], times[-1]):
        camera_at(camera, t - start, duration, scene)  # a bad camera fails before any work

    r = renderer or default_renderer()
    compiles0 = r.programs.compiles
    writer = output if isinstance(output, FrameWriter) else open_writer(
        output, wh, fps, **({"crf": crf} if crf is not None else {}))
    bar = ProgressBar(n) if progress else None
    result = AnimationResult(writer.path, n, fps, wh, 0, 0.0)
    t0 = _time.perf_counter()
    with writer:
        for i, t in enumerate(times):
            set_time(scene_clocks, t, i)
            cam = camera_at(camera, t - start, duration, scene)
            t1 = _time.perf_counter()
            res = r.render(scene, cam, wh, **settings)
            t2 = _time.perf_counter()
            writer.append(res.color)
            result.render_s.append(t2 - t1)
            result.write_s.append(_time.perf_counter() - t2)
            if bar:
                bar.update(i + 1)
    if bar:
        bar.close()
    result.seconds = _time.perf_counter() - t0
    result.compiles = r.programs.compiles - compiles0
    return result
