"""Hard cases of float32 precision: thin walls' normals, endless repetition far from the origin,
tiny near objects before a far backdrop."""
from __future__ import annotations

from typing import Callable

from ..camera import Camera, OrbitCamera
from ..nodes import box, difference, implicit, sphere
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
)
