"""``sdfgl view``: an interactive window on a scene file (reloaded when saved) or the demo."""
from __future__ import annotations

import argparse
import math
from typing import Any

from ..scenefile_process import DEFAULT_TIMEOUT_S, SceneFileLoader

from .common import (SCENE_HELP, add_camera_arguments, add_scene_arguments, add_settings_arguments,
                     camera_flags_given, camera_from_args, image_size, load_scene_args, render_settings,
                     settings_overrides)


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl view`` (the viewer's key list is imported only when its help can show)."""
    keys = ""
    if command in (None, "view"):
        from ..viewer import KEYS_HELP
        keys = "keys:\n" + KEYS_HELP
    v = sub.add_parser("view", help="open an interactive window on a scene file (reloaded when saved)",
                       formatter_class=argparse.RawDescriptionHelpFormatter, epilog=keys)
    add_scene_arguments(v, "view the built-in showcase scene", SCENE_HELP + " (default: the demo)")
    v.add_argument("--size", type=image_size, default=(960, 540), help="window size WIDTHxHEIGHT (default 960x540)")
    v.add_argument("--target-ms", type=float, default=50.0,
                   help="frame time to hold while the camera moves, by lowering the resolution (default 50)")
    v.add_argument("--no-adaptive", action="store_true", help="always render at full resolution")
    v.add_argument("--max-samples", type=int, default=16, help="jittered samples accumulated when idle (16)")
    v.add_argument("--screenshot-dir", default=".", help="where P saves screenshots (default: here)")
    v.add_argument("--state-file", help="keep a JSON file with the view's state up to date (for scripts)")
    v.add_argument("--load-timeout", type=positive_seconds, default=DEFAULT_TIMEOUT_S, metavar="SECONDS",
                   help="stop loading the scene file after this long, at the start (then exit) and on each "
                        f"reload (then keep the last scene) (default {DEFAULT_TIMEOUT_S:g})")
    v.add_argument("--panel", action=argparse.BooleanOptionalAction, default=None,
                   help="open with the side panel shown / hidden (default: shown if the window is >= 800 wide)")
    add_camera_arguments(v)
    add_settings_arguments(v)
    v.set_defaults(func=run)


def positive_seconds(text: str) -> float:
    """A number of seconds > 0 (argparse type)."""
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds, got {text!r}") from None
    if not (math.isfinite(x) and x > 0):
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0, got {text!r}")
    return x


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl view`` until the window closes."""
    from ..viewer import Viewer
    common = dict(size=a.size, target_ms=a.target_ms, adaptive=not a.no_adaptive, max_samples=a.max_samples,
                  state_file=a.state_file, screenshot_dir=a.screenshot_dir, panel=a.panel)
    if a.scene is None or a.demo:
        sf = load_scene_args(a)
        v = Viewer(sf.scene, camera_from_args(a, sf.scene, sf.camera), **common, **render_settings(a, sf))
    else:
        camera = None
        if camera_flags_given(a):
            loader = SceneFileLoader(a.load_timeout)
            try:
                sf = loader.wait(a.scene)  # the file is run in a child process, as the window runs it
            finally:
                loader.close()
            camera = camera_from_args(a, sf.scene, sf.camera)
        v = Viewer(camera=camera, path=a.scene, load_timeout=a.load_timeout, **common, **settings_overrides(a))
    v.run()
    return 0
