"""``sdfgl html``: write the one-file interactive HTML view of a scene file (or the demo)."""
from __future__ import annotations

import argparse


def cmd_html(a: argparse.Namespace) -> int:
    from ..cli import _load, _settings
    from ..cli_common import camera_from_args, require_scene
    from .html import save_html
    require_scene(a, "html")
    scene, camera, is_demo = _load(a)
    settings = _settings(a)
    if is_demo:
        settings["ground"] = True
    path = save_html(scene, a.output, camera_from_args(a, scene, camera), a.size, title=a.title, **settings)
    print(f"wrote {path} ({path.stat().st_size / 1024:.0f} KiB, view {a.size[0]}x{a.size[1]}): open it in a browser")
    return 0


def add_parser(sub: "argparse._SubParsersAction[argparse.ArgumentParser]") -> None:
    """Register the ``html`` subcommand."""
    from ..cli import _add_settings, _size
    from ..cli_common import add_camera_arguments
    h = sub.add_parser("html", help="write a one-file interactive HTML view (WebGL2, no network needed)")
    h.add_argument("scene", nargs="?", help="scene file: Python defining 'scene' (and optionally 'camera', "
                                            "'settings'), or a .json document")
    h.add_argument("--demo", action="store_true", help="use the built-in showcase scene")
    h.add_argument("-o", "--output", default="scene.html", help="HTML path (default scene.html)")
    h.add_argument("--size", type=_size, default=(800, 500), help="view WIDTHxHEIGHT in pixels (default 800x500)")
    h.add_argument("--title", help="page title (default: the scene)")
    add_camera_arguments(h)
    _add_settings(h)
    h.set_defaults(func=cmd_html)
