"""Pieces every ``sdfgl`` subcommand shares: camera flags and scene loading.

A subcommand that shows a scene from a viewpoint (render, view, shader, mesh, ...) calls
:func:`add_camera_arguments` on its parser and :func:`camera_from_args` after loading, so
``--yaw --pitch --distance --fov --target`` mean the same everywhere.
"""
from __future__ import annotations

import argparse
import math
from typing import Any

from .errors import SdfglError


def finite_number(text: str) -> float:
    """argparse type: a finite float (NaN and inf are refused at parse time)."""
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return x


def _vec3(text: str) -> tuple[float, float, float]:
    parts = [p for p in text.replace(",", " ").split() if p]
    if len(parts) != 3:
        raise argparse.ArgumentTypeError(f"expected three numbers like 0,1,0, got {text!r}")
    x, y, z = (finite_number(p) for p in parts)
    return x, y, z


def add_camera_arguments(p: argparse.ArgumentParser) -> None:
    """``--yaw --pitch --distance --fov --target``: an orbit camera about the scene file's
    camera (or one framing the scene), changed only in what is given."""
    g = p.add_argument_group("camera (an orbit camera; unset values come from the scene file or framing)")
    g.add_argument("--yaw", type=finite_number, metavar="DEG", help="turn about the vertical axis, degrees")
    g.add_argument("--pitch", type=finite_number, metavar="DEG", help="lift the eye, degrees in [-89.9, 89.9]")
    g.add_argument("--distance", type=finite_number, metavar="D", help="eye-to-target distance (> 0)")
    g.add_argument("--fov", type=finite_number, metavar="DEG", help="vertical field of view, degrees")
    g.add_argument("--target", type=_vec3, metavar="X,Y,Z", help="the point looked at")


def camera_from_args(a: argparse.Namespace, scene: Any, camera: Any) -> Any:
    """``camera`` with the command line's camera flags applied (unchanged if none is given)."""
    from .camera import OrbitCamera
    given = {k: getattr(a, k, None) for k in ("yaw", "pitch", "distance", "fov", "target")}
    if all(v is None for v in given.values()):
        return camera
    # a look-at camera becomes the orbit through its eye about its target; the projection is kept
    base = OrbitCamera.of(camera, *scene.bounds) if camera is not None else OrbitCamera.framing(*scene.bounds)
    pick = {k: (v if v is not None else getattr(base, k)) for k, v in given.items()}
    return OrbitCamera(pick["target"], pick["distance"], pick["yaw"], pick["pitch"], pick["fov"], base.projection,
                       base._ortho_height)


def require_scene(a: argparse.Namespace, command: str) -> None:
    """Refuse a command without a scene file or --demo (no silent default scene)."""
    if getattr(a, "scene", None) is None and not getattr(a, "demo", False):
        raise SdfglError(f"{command}: give a scene file (.py or .json) or --demo")
