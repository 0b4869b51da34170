"""``sdfgl shader``: print the generated fragment shader of a scene file (or the demo)."""
from __future__ import annotations

import argparse
import sys
from typing import Any

from .common import (add_camera_arguments, add_scene_arguments, add_settings_arguments, camera_from_args,
                     load_scene_args, render_settings, require_scene)


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl shader``."""
    s = sub.add_parser("shader", help="print the generated fragment shader")
    add_scene_arguments(s, "use the built-in showcase scene")
    add_camera_arguments(s)
    add_settings_arguments(s)
    s.set_defaults(func=run)


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl shader``: the GLSL goes to standard output."""
    from ..camera import OrbitCamera
    from ..compiler.generate import generate
    from ..render import shader_origin
    from ..settings import Settings
    require_scene(a, "shader")
    sf = load_scene_args(a)
    scene = sf.scene
    cam = camera_from_args(a, scene, sf.camera) or OrbitCamera.framing(*scene.bounds)
    sys.stdout.write(generate(scene, Settings.build(**render_settings(a, sf)), shader_origin(scene, cam.eye),
                              projection=cam.projection).text)
    return 0
