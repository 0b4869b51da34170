"""``sdfgl html``: write the one-file interactive HTML view of a scene file (or the demo)."""
from __future__ import annotations

import argparse
from typing import Any

from .common import (add_camera_arguments, add_scene_arguments, add_settings_arguments, camera_from_args,
                     image_size, load_scene_args, render_settings, require_scene)


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl html``."""
    h = sub.add_parser("html", help="write a one-file interactive HTML view (WebGL2, no network needed)")
    add_scene_arguments(h, "use the built-in showcase scene")
    h.add_argument("-o", "--output", default="scene.html", help="HTML path (default scene.html)")
    h.add_argument("--size", type=image_size, default=(800, 500), help="view WIDTHxHEIGHT in pixels (default 800x500)")
    h.add_argument("--title", help="page title (default: the scene)")
    add_camera_arguments(h)
    add_settings_arguments(h)
    h.set_defaults(func=run)


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl html``."""
    from ..web.html import save_html
    require_scene(a, "html")
    sf = load_scene_args(a)
    path = save_html(sf.scene, a.output, camera_from_args(a, sf.scene, sf.camera), a.size, title=a.title,
                     **render_settings(a, sf))
    print(f"wrote {path} ({path.stat().st_size / 1024:.0f} KiB, view {a.size[0]}x{a.size[1]}): open it in a browser")
    return 0
