"""Hard cases of the marcher's acceptance: near objects before far straight surfaces, Newton steps
near the clip box's exit, critical points of implicit fields outside the solid, fine displacement."""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..camera import Camera
from ..nodes import box, cylinder, plane, sphere, union
from ..nodes.base import Node
from .spec import Expect, HardCase

Build = Callable[[], tuple[Node, Camera]]


def _on_ground(shape: str, size: float, eye_y: float, yaw: float) -> Build:
    # one object standing on an endless ground plane, the eye a little above the plane
    def build() -> tuple[Node, Camera]:
        if shape == "box":
            obj = box(size).rotate(yaw, (0, 1, 0)).translate((0, size / 2, 0))
        elif shape == "sphere":
            obj = sphere(size / 2).translate((0, size / 2, 0))
        else:
            obj = cylinder(size / 2, size).translate((0, size / 2, 0))
        d = 4.0 * size
        eye = (d * np.sin(np.radians(yaw)), eye_y, d * np.cos(np.radians(yaw)))
        return plane((0, 1, 0), (0, 0, 0)) | obj, Camera.look_at(eye, (0, eye_y * 0.5 + 0.2 * size, 0), fov=50)
    return build


def _many_boxes(method: str | None = None) -> Build:
    def build() -> tuple[Node, Camera]:
        rng = np.random.default_rng(7)
        boxes = [box(float(s)).translate((float(x), float(s) / 2, float(z)))
                 for x, z, s in zip(rng.uniform(-20, 20, 200), rng.uniform(-40, 0, 200), rng.uniform(0.1, 0.6, 200))]
        return plane((0, 1, 0), (0, 0, 0)) | union(*boxes), Camera.look_at((0.3, 0.15, 4.0), (0, 0.1, -10), fov=60)
    return build


def _slab_floor(eye_y: float) -> Build:
    def build() -> tuple[Node, Camera]:
        floor = box((300.0, 0.5, 300.0)).translate((0, -0.25, 0))
        objs = union(box(0.4).translate((0.3, 0.2, -1.0)), sphere(0.25).translate((-0.6, 0.25, -2.5)),
                     cylinder(0.15, 0.8).translate((1.1, 0.4, -4.0)))
        return floor | objs, Camera.look_at((0, eye_y, 1.5), (0, 0.15, -3), fov=55)
    return build


GROUND_CASES: tuple[HardCase, ...] = (
    HardCase("ground_box_low", "a box on an endless plane, the eye 0.1 above the plane", _on_ground("box", 1.0, 0.1, 30)),
    HardCase("ground_box_tiny_eye", "a small box on a plane, the eye 0.05 above it",
             _on_ground("box", 0.4, 0.05, -20)),
    HardCase("ground_sphere_low", "a sphere on a plane, the eye 0.3 above it", _on_ground("sphere", 2.0, 0.3, 10)),
    HardCase("ground_cylinder_low", "a cylinder on a plane, the eye 0.5 above it",
             _on_ground("cylinder", 3.0, 0.5, 60)),
    HardCase("ground_box_sphere_method", "a box on a plane seen from 0.1 above, plain sphere tracing",
             _on_ground("box", 1.0, 0.1, 45), settings={"method": "sphere"}),
    HardCase("ground_many_boxes", "200 small boxes on a plane seen from 0.15 above", _many_boxes()),
    HardCase("ground_many_boxes_sphere", "200 small boxes on a plane, plain sphere tracing", _many_boxes(),
             settings={"method": "sphere"}),
    HardCase("ground_slab_low", "objects on a bounded floor slab, the eye 0.2 above it", _slab_floor(0.2)),
)

MARCHING_CASES: tuple[HardCase, ...] = GROUND_CASES
