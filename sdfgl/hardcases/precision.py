"""Hard cases of float32 precision: thin walls' normals, endless repetition far from the origin,
tiny near objects before a far backdrop."""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..camera import Camera, OrbitCamera
from ..nodes import box, difference, implicit, sphere, union
from ..nodes.base import Node
from .spec import HardCase

Build = Callable[[], tuple[Node, Camera]]
IMPLICIT = {"method": "auto"}  # an implicit field: the distance methods refuse it


def _sdf_shell(thickness: float, radius: float, yaw: float, pitch: float) -> Build:
    # a spherical shell as |f| - t/2, cut open by a box so that both faces and the rim show
    def build() -> tuple[Node, Camera]:
        cut = box((2.4 * radius, 2.4 * radius, 2.4 * radius)).translate((0, 0, 1.25 * radius))
        shell = difference(sphere(radius).shell(thickness), cut)
        return shell, OrbitCamera(distance=3.2 * radius, yaw=yaw, pitch=pitch)
    return build


def _implicit_shell(thickness: float, yaw: float, pitch: float) -> Build:
    # the same wall as one implicit field: (r^2 - a^2)(r^2 - b^2) < 0 between the radii
    def build() -> tuple[Node, Camera]:
        a2, b2 = (1.0 - thickness / 2) ** 2, (1.0 + thickness / 2) ** 2
        f = implicit(f"(x*x + y*y + z*z - {a2!r}) * (x*x + y*y + z*z - {b2!r})", bounds=((-1.1,) * 3, (1.1,) * 3))
        return f, OrbitCamera(distance=3.0, yaw=yaw, pitch=pitch)
    return build


def _thin_plate(thickness: float, tilt: float) -> Build:
    # a square plate seen from above at an angle: both faces lie within the normal stencil
    def build() -> tuple[Node, Camera]:
        plate = box((2.0, thickness, 1.6)).rotate(tilt, (1, 0, 0.3))
        return plate, OrbitCamera(distance=3.5, yaw=25, pitch=40)
    return build


def _far_repeat(at: float, period: float, yaw: float, turn: float = 0.0) -> Build:
    # endless rows of spheres on the ground (turned ``turn`` degrees about the vertical), seen
    # from a camera ``at`` from the world origin
    def build() -> tuple[Node, Camera]:
        scene = sphere(0.3 * period).repeat((period, 0.0, period))
        if turn:
            scene = scene.rotate(turn, (0, 1, 0))
        target = np.array([at * 0.7071, 0.0, -at * 0.7071]) + 0.123 * period
        return scene, OrbitCamera(target=tuple(target), distance=4 * period, yaw=yaw, pitch=30)
    return build


def _far_lattice(at: float, angle: float, axis: tuple[float, float, float]) -> Build:
    # an endless 3D lattice of small spheres, turned, seen from a camera ``at`` from the origin
    # (rays end at max_dist: a ray that grazes sphere after sphere of an endless lattice runs
    # out of steps wherever it is)
    def build() -> tuple[Node, Camera]:
        scene = sphere(0.22).repeat(1.0).rotate(angle, axis)
        target = at * np.array([0.48, -0.6, 0.64]) + 0.37
        return scene, OrbitCamera(target=tuple(target), distance=2.5, yaw=30, pitch=20)
    return build


def _near_tiny(size: float, eye_gap: float, wall: float) -> Build:
    # a cube ``size`` across, ``eye_gap`` ahead of the eye, and a wall ``wall`` beyond it
    def build() -> tuple[Node, Camera]:
        eye = np.array([0.0, 0.0, 0.0])
        c = np.array([0.0, 0.0, -eye_gap])
        near = (box(size) - sphere(0.62 * size)).rotate(30, (1, 1, 0)).translate(tuple(c))
        back = box((4 * wall, 4 * wall, 1.0)).translate((0, 0, -wall))
        fov = float(np.degrees(2 * np.arctan(0.9 * size / eye_gap)))
        return union(near, back), Camera.look_at(tuple(eye), tuple(c), fov=fov)
    return build


PRECISION_CASES: tuple[HardCase, ...] = (
    HardCase("shell_sdf_1e-3", "a spherical SDF shell 1e-3 thick, cut open: the normal stencil must not straddle "
             "the wall", _sdf_shell(1e-3, 1.0, 35, 25)),
    HardCase("shell_sdf_1e-4", "an SDF shell 1e-4 thick, cut open, seen from below", _sdf_shell(1e-4, 1.0, -120, -30)),
    HardCase("shell_implicit_1e-3", "a spherical shell 1e-3 thick as one implicit polynomial",
             _implicit_shell(1e-3, 20, 30), settings=IMPLICIT),
    HardCase("shell_implicit_2e-3", "a spherical shell 2e-3 thick as one implicit polynomial",
             _implicit_shell(2e-3, -40, 10), settings=IMPLICIT),
    HardCase("shell_sdf_3e-4_r3", "an SDF shell 3e-4 thick of radius 3", _sdf_shell(3e-4, 3.0, 110, 20)),
    HardCase("shell_sdf_1e-3_r5", "an SDF shell 1e-3 thick of radius 5", _sdf_shell(1e-3, 5.0, 10, 35)),
    HardCase("plate_1e-4", "a tilted square plate 1e-4 thick", _thin_plate(1e-4, 12)),
    HardCase("plate_5e-4", "a tilted square plate 5e-4 thick", _thin_plate(5e-4, -35)),
    HardCase("repeat_1e5", "endless rows of spheres seen 1e5 from the origin", _far_repeat(1e5, 1.0, 20)),
    HardCase("repeat_1e6", "endless rows of spheres seen 1e6 from the origin", _far_repeat(1e6, 2.0, -65)),
    HardCase("repeat_1e6_turned", "endless rows of spheres turned 33 degrees, seen 1e6 from the origin",
             _far_repeat(1e6, 1.5, 75, turn=33)),
    HardCase("repeat_3e6", "endless rows of spheres seen 3e6 from the origin", _far_repeat(3e6, 0.5, 140)),
    HardCase("lattice_1e5_rot", "an endless turned lattice of spheres 1e5 from the origin",
             _far_lattice(1e5, 25, (0.2, 1.0, 0.1)), max_dist=12.0),
    HardCase("lattice_1e6_rot", "an endless turned lattice of spheres 1e6 from the origin",
             _far_lattice(1e6, 40, (1.0, 0.3, -0.5)), max_dist=12.0),
    HardCase("near_tiny_3mm", "a 3 mm object 5 mm from the eye before a wall 1000 away", _near_tiny(3e-3, 5e-3, 1000)),
    HardCase("near_tiny_1mm", "a 1 mm object 2 mm from the eye before a wall 500 away", _near_tiny(1e-3, 2e-3, 500)),
    HardCase("near_tiny_1cm", "a 1 cm object 3 cm from the eye before a wall 2000 away",
             _near_tiny(1e-2, 3e-2, 2000), max_dist=4000.0),
)
