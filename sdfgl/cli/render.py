"""``sdfgl render``: render a scene file (or the demo) headless to an image."""
from __future__ import annotations

import argparse
from typing import Any

from ..settings import OUTPUTS
from .common import (add_camera_arguments, add_mesh_arguments, add_scene_arguments, add_settings_arguments,
                     camera_from_args, finite_number, image_size, load_scene_args, meshes_from_args, output_names,
                     render_settings, require_scene)


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl render``."""
    r = sub.add_parser("render", help="render a scene file (or the demo) headless to an image")
    add_scene_arguments(r, "render the built-in showcase scene")
    r.add_argument("-o", "--output", default="out.png",
                   help="image path (default out.png); a .npz path gets every output as float arrays")
    r.add_argument("--outputs", type=output_names, metavar="LIST",
                   help=f"also write these images beside the colour one: a comma list of {', '.join(OUTPUTS[1:])} "
                        f"(e.g. depth,normal -> out.depth.png, out.normal.png)")
    r.add_argument("--size", type=image_size, default=(800, 600), help="WIDTHxHEIGHT (default 800x600)")
    r.add_argument("--no-ground", action="store_true",
                   help="leave the ground plane out (that --demo or the scene file asks for)")
    r.add_argument("--background", help="a colour ('#ffffff', 'white') or TOP,BOTTOM for a gradient")
    r.add_argument("--alpha", action="store_true", help="transparent background: RGBA PNG, alpha = coverage")
    r.add_argument("--fog", type=finite_number, help="fade surfaces into the background over this distance")
    r.add_argument("--ortho", action="store_true", help="orthographic camera framing the scene")
    add_mesh_arguments(r)
    add_camera_arguments(r)
    add_settings_arguments(r)
    r.set_defaults(func=run)


def look_settings(a: argparse.Namespace) -> dict[str, object]:
    """The look options of ``sdfgl render``: --background, --alpha, --fog."""
    out: dict[str, object] = {}
    if a.background:
        parts = a.background.split(",")
        out["background"] = parts[0] if len(parts) == 1 else tuple(parts)
    if a.alpha:
        out["alpha"] = True
    if a.fog is not None:
        out["fog"] = a.fog
    return out


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl render``; the status line reports the settings rendered with."""
    from ..outputs import save_outputs
    from ..render import render
    require_scene(a, "render")
    sf = load_scene_args(a)
    scene = sf.scene
    settings = render_settings(a, sf)
    if a.no_ground:
        settings["ground"] = False
    outputs = tuple(dict.fromkeys(("color",) + (a.outputs or ())))
    if a.output.lower().endswith(".npz") and a.outputs is None:
        outputs = OUTPUTS
    settings.update(look_settings(a))
    cam = camera_from_args(a, scene, sf.camera)
    if a.ortho:
        from ..camera import OrbitCamera
        yaw, pitch = (cam.yaw, cam.pitch) if isinstance(cam, OrbitCamera) else (30.0, 20.0)
        cam = OrbitCamera.framing(*scene.bounds, yaw, pitch, aspect=a.size[0] / a.size[1], projection="orthographic")
    res = render(scene, cam, a.size, meshes=meshes_from_args(a), outputs=outputs, **settings)
    paths = save_outputs(res, a.output, outputs)
    t = res.timings
    print(f"wrote {', '.join(str(p) for p in paths)} ({a.size[0]}x{a.size[1]}, aa {res.settings.aa}): "
          f"compile {t['compile_s'] * 1000:.0f} ms, draw {t['draw_s'] * 1000:.0f} ms")
    return 0
