"""``sdfgl view``: an interactive window on a scene file (reloaded when saved) or the demo."""
from __future__ import annotations

import argparse
from typing import Any

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
    v.add_argument("--panel", action=argparse.BooleanOptionalAction, default=None,
                   help="open with the side panel shown / hidden (default: shown if the window is >= 800 wide)")
    add_camera_arguments(v)
    add_settings_arguments(v)
    v.set_defaults(func=run)


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
            sf = load_scene_args(a)
            camera = camera_from_args(a, sf.scene, sf.camera)
        v = Viewer(camera=camera, path=a.scene, **common, **settings_overrides(a))
    v.run()
    return 0
