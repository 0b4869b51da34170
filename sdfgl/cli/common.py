"""Argument and scene code every ``sdfgl`` subcommand shares.

A subcommand registers its scene argument with :func:`add_scene_arguments`, its render
settings with :func:`add_settings_arguments` and its viewpoint with
:func:`add_camera_arguments`; at run time :func:`load_scene_args` loads the scene (a ``.py``
file, a ``.json`` document or ``--demo``), :func:`render_settings` merges the defaults, the
file's ``settings`` and the flags given, and :func:`camera_from_args` applies the camera
flags, so each flag means the same in every subcommand.
"""
from __future__ import annotations

import argparse
import math
from dataclasses import MISSING, fields
from typing import TYPE_CHECKING, Any

from ..errors import SdfglError
from ..settings import METHODS, OUTPUTS, Settings

if TYPE_CHECKING:  # the scene graph loads only when a command runs, not for --help
    from ..scenefile import SceneFile

SCENE_HELP = ("scene file: Python defining 'scene' (and optionally 'camera', 'settings', 'camera_path'), "
              "or a .json document")
DEFAULTS: dict[str, Any] = {f.name: f.default for f in fields(Settings) if f.default is not MISSING}
"""The render settings' defaults, read from :class:`sdfgl.settings.Settings`."""
SETTING_FLAGS = ("aa", "shadows", "ao", "ground", "method", "max_steps")
"""The settings :func:`add_settings_arguments` puts on the command line."""
CAMERA_FLAGS = ("yaw", "pitch", "distance", "fov", "target")
"""The flags :func:`add_camera_arguments` adds."""


def finite_number(text: str) -> float:
    """argparse type: a finite float (NaN and inf are refused at parse time)."""
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return x


def vector3(text: str) -> tuple[float, float, float]:
    """argparse type: three finite numbers, ``0,1,0`` or ``"0 1 0"``."""
    parts = [p for p in text.replace(",", " ").split() if p]
    if len(parts) != 3:
        raise argparse.ArgumentTypeError(f"expected three numbers like 0,1,0, got {text!r}")
    x, y, z = (finite_number(p) for p in parts)
    return x, y, z


def image_size(text: str) -> tuple[int, int]:
    """argparse type: ``WIDTHxHEIGHT`` such as ``800x600``, each in 1..16384."""
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size must look like 800x600, got {text!r}") from None
    if not (1 <= w <= 16384 and 1 <= h <= 16384):
        raise argparse.ArgumentTypeError(f"size must be two whole numbers in 1..16384 like 800x600, got {text!r}")
    return w, h


def output_names(text: str) -> tuple[str, ...]:
    """argparse type: a comma list of render outputs (color, depth, normal, steps)."""
    names = tuple(x.strip() for x in text.split(",") if x.strip())
    bad = [n for n in names if n not in OUTPUTS]
    if bad or not names:
        raise argparse.ArgumentTypeError(f"outputs must be a comma list of {', '.join(OUTPUTS)}, got {text!r}")
    return names


def add_scene_arguments(p: argparse.ArgumentParser, demo_help: str, scene_help: str = SCENE_HELP) -> None:
    """The positional scene file and ``--demo`` (the built-in showcase scene)."""
    p.add_argument("scene", nargs="?", help=scene_help)
    p.add_argument("--demo", action="store_true", help=demo_help)


def add_settings_arguments(p: argparse.ArgumentParser) -> None:
    """``--aa --shadows --no-ao --ground --method --max-steps``; defaults come from
    :class:`~sdfgl.settings.Settings`, and only the flags given override a scene file's settings."""
    shadows = DEFAULTS["shadows"] or "off"
    p.add_argument("--aa", type=int, choices=range(1, 5), metavar="{1,2,3,4}",
                   help=f"samples per pixel side (default {DEFAULTS['aa']})")
    p.add_argument("--shadows", choices=("off", "hard", "soft"), help=f"(default {shadows})")
    p.add_argument("--no-ao", dest="ao", action="store_const", const=False, help="turn ambient occlusion off")
    p.add_argument("--ground", action="store_const", const=True,
                   help="add an analytic ground plane under the scene")
    p.add_argument("--method", choices=METHODS,
                   help=f"marching method (default {DEFAULTS['method']}: enhanced, newton for implicit fields)")
    p.add_argument("--max-steps", type=int,
                   help=f"marching rounds per primary ray away from surfaces, 1..100000 (default "
                        f"{DEFAULTS['max_steps']}; near-surface rounds are counted apart, up to twice that in all)")


def settings_overrides(a: argparse.Namespace) -> dict[str, Any]:
    """The render settings given on the command line (flags left out are absent)."""
    given = {k: getattr(a, k, None) for k in SETTING_FLAGS}
    if given["shadows"] == "off":
        given["shadows"] = False
    return {k: v for k, v in given.items() if v is not None}


def render_settings(a: argparse.Namespace, sf: "SceneFile") -> dict[str, Any]:
    """The defaults of the command line's settings, then the scene file's ``settings``, then the flags given."""
    return {**{k: DEFAULTS[k] for k in SETTING_FLAGS}, **sf.settings, **settings_overrides(a)}


def require_scene(a: argparse.Namespace, command: str) -> None:
    """Refuse a command without a scene file or --demo (no silent default scene)."""
    if getattr(a, "scene", None) is None and not getattr(a, "demo", False):
        raise SdfglError(f"{command}: give a scene file (.py or .json) or --demo")


def load_scene_args(a: argparse.Namespace) -> "SceneFile":
    """The scene of ``a.scene`` (a ``.py`` or ``.json`` file) or ``--demo`` (also when no file is given)."""
    from ..scenefile import load_demo, load_scene_file
    if getattr(a, "demo", False) or a.scene is None:
        if a.scene is not None:
            raise SdfglError("give either a scene file or --demo, not both")
        return load_demo()
    return load_scene_file(a.scene)


def add_camera_arguments(p: argparse.ArgumentParser) -> None:
    """``--yaw --pitch --distance --fov --target``: an orbit camera about the scene file's
    camera (or one framing the scene), changed only in what is given."""
    g = p.add_argument_group("camera (an orbit camera; unset values come from the scene file or framing)")
    g.add_argument("--yaw", type=finite_number, metavar="DEG", help="turn about the vertical axis, degrees")
    g.add_argument("--pitch", type=finite_number, metavar="DEG", help="lift the eye, degrees in [-89.9, 89.9]")
    g.add_argument("--distance", type=finite_number, metavar="D", help="eye-to-target distance (> 0)")
    g.add_argument("--fov", type=finite_number, metavar="DEG", help="vertical field of view, degrees")
    g.add_argument("--target", type=vector3, metavar="X,Y,Z", help="the point looked at")


def camera_flags_given(a: argparse.Namespace) -> bool:
    """Whether any of the camera flags was given."""
    return any(getattr(a, k, None) is not None for k in CAMERA_FLAGS)


def camera_from_args(a: argparse.Namespace, scene: Any, camera: Any) -> Any:
    """``camera`` with the command line's camera flags applied (unchanged if none is given)."""
    from ..camera import OrbitCamera
    if not camera_flags_given(a):
        return camera
    given = {k: getattr(a, k, None) for k in CAMERA_FLAGS}
    # a look-at camera becomes the orbit through its eye about its target; the projection is kept
    base = OrbitCamera.of(camera, *scene.bounds) if camera is not None else OrbitCamera.framing(*scene.bounds)
    pick = {k: (v if v is not None else getattr(base, k)) for k, v in given.items()}
    return OrbitCamera(pick["target"], pick["distance"], pick["yaw"], pick["pitch"], pick["fov"], base.projection,
                       base._ortho_height)


def add_mesh_arguments(p: argparse.ArgumentParser) -> None:
    """``--mesh PATH`` (repeatable) and ``--mesh-color``: meshes drawn by rasterisation with the scene."""
    p.add_argument("--mesh", action="append", metavar="PATH", default=[],
                   help="a mesh file (STL, OBJ, PLY, GLB/glTF, 3MF, OFF) drawn by rasterisation in the same "
                        "frame, hidden by and shadowed by the scene; repeat for more")
    p.add_argument("--mesh-color", default="#cccccc", metavar="COLOR",
                   help="the colour of the --mesh meshes (default #cccccc)")


def meshes_from_args(a: argparse.Namespace) -> list[Any]:
    """The ``--mesh`` files as raster meshes (sg.raster) of colour ``--mesh-color``."""
    from ..raster import raster
    return [raster(path, color=a.mesh_color) for path in a.mesh]
