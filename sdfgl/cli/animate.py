"""``sdfgl animate``: render a scene file (or the demo) over time into MP4, WebM, GIF or PNG frames."""
from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..extras import require_extra
from .common import (add_camera_arguments, add_scene_arguments, add_settings_arguments, camera_flags_given,
                     camera_from_args, image_size, load_scene_args, render_settings)

if TYPE_CHECKING:
    from ..scenefile import SceneFile


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl animate``."""
    p = sub.add_parser("animate", help="render a scene over time (sg.time(), camera paths) to MP4, WebM, GIF or PNGs",
                       description="Render a scene file whose nodes may read sg.time(); frame i is drawn at "
                                   "START + i / FPS. The camera is --turntable, else the camera flags, else the "
                                   "file's 'camera_path', else its 'camera' (or one framing the scene). Output by "
                                   "suffix: .mp4/.webm (sdfgl[video]), .gif, frames/%04d.png or a folder.")
    add_scene_arguments(p, "animate the built-in showcase scene")
    p.add_argument("-o", "--output", default="animation.mp4", help="output file or frame pattern (animation.mp4)")
    p.add_argument("--seconds", type=float, default=4.0, help="clip length in seconds (default 4)")
    p.add_argument("--fps", type=float, default=30.0, help="frames per second (default 30)")
    p.add_argument("--frames", type=int, help="number of frames (overrides --seconds); a clip holds at most "
                                              "an hour at 60 fps")
    p.add_argument("--start", type=float, default=0.0, help="time of the first frame in seconds (default 0)")
    p.add_argument("--size", type=image_size, default=(640, 360), help="WIDTHxHEIGHT (default 640x360)")
    p.add_argument("--turntable", action="store_true", help="orbit the camera once around the target over the clip")
    p.add_argument("--turns", type=float, default=1.0, help="with --turntable: turns over the clip (default 1)")
    p.add_argument("--crf", type=int, help="video quality, lower is better: .mp4 (x264) 0..51, default 18; "
                                           ".webm (VP9) 0..63, default 32")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_camera_arguments(p)
    add_settings_arguments(p)
    p.set_defaults(func=run)


def camera_spec(a: argparse.Namespace, sf: "SceneFile") -> Any:
    """The clip's camera: a turntable, the flags' fixed camera, the file's camera path or its camera."""
    from ..animate.paths import turntable
    from ..camera import OrbitCamera
    if a.turntable:
        base = sf.camera if isinstance(sf.camera, OrbitCamera) else OrbitCamera.framing(*sf.scene.bounds)
        base = camera_from_args(a, sf.scene, base)
        return turntable(distance=base.distance, pitch=base.pitch, target=base.target, fov=base.fov, yaw=base.yaw,
                         turns=a.turns)
    if camera_flags_given(a):
        return camera_from_args(a, sf.scene, sf.camera)
    return sf.camera_path if sf.camera_path is not None else sf.camera


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl animate`` (a video output checks for imageio-ffmpeg before any frame)."""
    from ..animate.animation import animate
    from ..animate.writers import VIDEO_SUFFIXES
    if Path(a.output).suffix.lower() in VIDEO_SUFFIXES:
        require_extra("video", "imageio_ffmpeg", purpose=f"writing '{a.output}'")
    sf = load_scene_args(a)
    res = animate(sf.scene, a.output, seconds=a.seconds, fps=a.fps, camera=camera_spec(a, sf), size=a.size,
                  start=a.start, frames=a.frames, progress=not a.no_progress, crf=a.crf, **render_settings(a, sf))
    render_ms = 1000 * sorted(res.render_s)[len(res.render_s) // 2]
    print(f"wrote {res.path}: {res.frames} frames {res.size[0]}x{res.size[1]} at {res.fps:g} fps in "
          f"{res.seconds:.1f} s ({res.frames_per_second:.2f} frames/s, render median {render_ms:.0f} ms, "
          f"{res.compiles} shader compile{'s' if res.compiles != 1 else ''})")
    return 0
