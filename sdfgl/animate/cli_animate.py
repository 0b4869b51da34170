"""``sdfgl animate``: render a scene file (or the demo) over time into MP4, WebM, GIF or PNG frames."""
from __future__ import annotations

import argparse

from ..cli import _add_settings, _load, _settings, _size


def cmd_animate(a: argparse.Namespace) -> int:
    from ..camera import OrbitCamera
    from .animation import animate
    from .paths import turntable
    scene, camera, is_demo = _load(a)
    settings = _settings(a)
    if is_demo:
        settings["ground"] = True
    if a.turntable:
        base = camera if isinstance(camera, OrbitCamera) else OrbitCamera.framing(*scene.bounds)
        path = turntable(distance=a.distance or base.distance, pitch=base.pitch if a.pitch is None else a.pitch,
                         target=base.target, fov=base.fov, yaw=base.yaw if a.yaw is None else a.yaw, turns=a.turns)
    else:
        from ..cli import _camera
        path = _camera(a, scene, camera)
    res = animate(scene, a.output, seconds=a.seconds, fps=a.fps, camera=path, size=a.size, start=a.start,
                  frames=a.frames, progress=not a.no_progress, crf=a.crf, **settings)
    render_ms = 1000 * sorted(res.render_s)[len(res.render_s) // 2]
    print(f"wrote {res.path}: {res.frames} frames {res.size[0]}x{res.size[1]} at {res.fps:g} fps in "
          f"{res.seconds:.1f} s ({res.frames_per_second:.2f} frames/s, render median {render_ms:.0f} ms, "
          f"{res.compiles} shader compile{'s' if res.compiles != 1 else ''})")
    return 0


def add_parser(sub: argparse._SubParsersAction) -> None:
    """Register ``sdfgl animate``."""
    p = sub.add_parser("animate", help="render a scene over time (sg.time(), camera paths) to MP4, WebM, GIF or PNGs",
                       description="Render a scene file whose nodes may read sg.time(); frame i is drawn at "
                                   "START + i / FPS. Output by suffix: .mp4/.webm (sdfgl[video]), .gif, "
                                   "frames/%%04d.png or a folder.")
    p.add_argument("scene", nargs="?", help="Python scene file defining 'scene' (and optionally 'camera')")
    p.add_argument("--demo", action="store_true", help="animate the built-in showcase scene")
    p.add_argument("-o", "--output", default="animation.mp4", help="output file or frame pattern (animation.mp4)")
    p.add_argument("--seconds", type=float, default=4.0, help="clip length in seconds (default 4)")
    p.add_argument("--fps", type=float, default=30.0, help="frames per second (default 30)")
    p.add_argument("--frames", type=int, help="number of frames (overrides --seconds)")
    p.add_argument("--start", type=float, default=0.0, help="time of the first frame in seconds (default 0)")
    p.add_argument("--size", type=_size, default=(640, 360), help="WIDTHxHEIGHT (default 640x360)")
    p.add_argument("--turntable", action="store_true", help="orbit the camera once around the target over the clip")
    p.add_argument("--turns", type=float, default=1.0, help="with --turntable: turns over the clip (default 1)")
    p.add_argument("--yaw", type=float, help="camera yaw in degrees (the start, with --turntable)")
    p.add_argument("--pitch", type=float, help="camera pitch in degrees")
    p.add_argument("--distance", type=float, help="camera distance")
    p.add_argument("--crf", type=int, help="video quality, lower is better (x264 default 18, VP9 32)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    _add_settings(p)
    p.set_defaults(func=cmd_animate)
