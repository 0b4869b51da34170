"""Hard cases of the marcher's acceptance: near objects before far straight surfaces, Newton steps
near the clip box's exit, critical points of implicit fields outside the solid, fine displacement."""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..camera import Camera, OrbitCamera
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


def _many_boxes(n: int, eye_y: float, seed: int) -> Build:
    # n small boxes scattered over a plane, the eye eye_y above it
    def build() -> tuple[Node, Camera]:
        rng = np.random.default_rng(seed)
        boxes = [box(float(s)).translate((float(x), float(s) / 2, float(z)))
                 for x, z, s in zip(rng.uniform(-20, 20, n), rng.uniform(-40, 0, n), rng.uniform(0.1, 0.6, n))]
        return plane((0, 1, 0), (0, 0, 0)) | union(*boxes), Camera.look_at((0.3, eye_y, 4.0), (0, 0.1, -10), fov=60)
    return build


def _slab_floor(eye_y: float) -> Build:
    def build() -> tuple[Node, Camera]:
        floor = box((300.0, 0.5, 300.0)).translate((0, -0.25, 0))
        objs = union(box(0.4).translate((0.3, 0.2, -1.0)), sphere(0.25).translate((-0.6, 0.25, -2.5)),
                     cylinder(0.15, 0.8).translate((1.1, 0.4, -4.0)))
        return floor | objs, Camera.look_at((0, eye_y, 1.5), (0, 0.15, -3), fov=55)
    return build


# wrong-surface hits at most 0.2 % of the hits (about half the pixels hit)
_GROUND = Expect(outlier_frac=0.001)
_BOXES = Expect(outlier_frac=0.001, surface_px_max=1.0)  # hundreds of box edges a pixel or two wide

GROUND_CASES: tuple[HardCase, ...] = (
    HardCase("ground_box_low", "a box on an endless plane, the eye 0.1 above the plane",
             _on_ground("box", 1.0, 0.1, 30),
    expect=_GROUND),
    HardCase("ground_box_tiny_eye", "a small box on a plane, the eye 0.05 above it",
             _on_ground("box", 0.4, 0.05, -20), expect=_GROUND),
    HardCase("ground_sphere_low", "a sphere on a plane, the eye 0.3 above it", _on_ground("sphere", 2.0, 0.3, 10),
    expect=_GROUND),
    HardCase("ground_cylinder_low", "a cylinder on a plane, the eye 0.5 above it",
             _on_ground("cylinder", 3.0, 0.5, 60), expect=_GROUND),
    HardCase("ground_box_sphere_method", "a box on a plane seen from 0.1 above, plain sphere tracing",
             _on_ground("box", 1.0, 0.1, 45), settings={"method": "sphere"}, expect=_GROUND),
    HardCase("ground_many_boxes", "200 small boxes on a plane seen from 0.15 above", _many_boxes(200, 0.15, 7),
             expect=_BOXES),
    HardCase("ground_boxes_sphere", "60 small boxes on a plane seen from 0.3 above, plain sphere tracing",
             _many_boxes(60, 0.3, 3), settings={"method": "sphere"}, expect=_BOXES),
    HardCase("ground_slab_low", "objects on a bounded floor slab, the eye 0.2 above it", _slab_floor(0.2),
    expect=_GROUND),
)



def _implicit(expr: str, lo: tuple[float, float, float], hi: tuple[float, float, float],
              eye: tuple[float, float, float], at: tuple[float, float, float], fov: float) -> Build:
    def build() -> tuple[Node, Camera]:
        from ..nodes.implicit import implicit
        return implicit(expr, bounds=(lo, hi)), Camera.look_at(eye, at, fov=fov)
    return build


_AUTO = {"method": "auto"}  # auto: newton (implicit); the distance methods refuse an implicit field


# the clip box cuts these solids: its faces are no sign change of the field, so the hit-to-surface
# figure (the nearest sign change of the twin) says nothing there
_CUT = Expect(surface_px_max=float("inf"))

# Newton near the clip box's exit: the solid begins a short way before the far side of the box
EXIT_CASES: tuple[HardCase, ...] = (
    HardCase("implicit_cone_far_side", "implicit cone x^2 + y^2 - z^2 whose vertex lies near the box's far side",
             _implicit("x**2 + y**2 - z**2", (-1.5, -1.5, -1.5), (1.5, 1.5, 0.3), (0.4, 0.3, 6.0), (0, 0, -1), 30),
             settings=_AUTO, expect=_CUT),
    HardCase("implicit_cone_far_side_tilted", "implicit cone seen from the side, its nappe ending at the box",
             _implicit("x**2 + z**2 - 0.5*y**2", (-1.0, -1.0, -1.0), (1.0, 0.2, 1.0), (3.5, 2.5, 3.0), (0, -0.3, 0),
                       40),
             settings=_AUTO, expect=_CUT),
    HardCase("whitney_far_side", "Whitney umbrella x^2 - y^2 z with its solid near the box's far side",
             _implicit("x**2 - y**2*z", (-1.0, -1.0, -0.5), (1.0, 1.0, 1.0), (0.3, 0.5, -5.0), (0, 0, 0.5), 35),
             settings=_AUTO, expect=_CUT),
    HardCase("whitney_far_side_oblique", "Whitney umbrella seen obliquely, clipped near its handle",
             _implicit("x**2 - y**2*z", (-1.2, -1.2, -1.2), (1.2, 1.2, 0.4), (2.5, -3.0, 4.0), (0, 0, 0), 40),
             settings=_AUTO, expect=_CUT),
)

# critical points of f outside the solid (grad f = 0 where f > 0): f / |grad f| is huge there
CRITICAL_CASES: tuple[HardCase, ...] = (
    HardCase("quartic_lobes_eye_between", "two lobes of a quartic, the eye near the critical point between them",
             _implicit("((x-1)**2 + y**2 + z**2 - 0.5)*((x+1)**2 + y**2 + z**2 - 0.5) - 0.01",
                       (-2.0, -1.0, -1.0), (2.0, 1.0, 1.0), (0.05, 0.02, 0.4), (1, 0, 0), 70), settings=_AUTO),
    HardCase("implicit_shell_eye_centre", "a thin implicit spherical shell, the eye near its centre",
             _implicit("(x**2 + y**2 + z**2 - 1)**2 - 0.0004", (-1.2, -1.2, -1.2), (1.2, 1.2, 1.2),
                       (0.02, 0.01, 0.03), (0.3, 0.2, -1), 90), settings=_AUTO),
    HardCase("implicit_shell_eye_off", "a thin implicit shell of radius 2, the eye 0.3 from its centre",
             _implicit("(x**2 + y**2 + z**2 - 4)**2 - 0.01", (-2.5, -2.5, -2.5), (2.5, 2.5, 2.5),
                       (0.3, 0.0, 0.0), (-1, -0.4, 0.3), 80), settings=_AUTO),
)


def _bumpy(amplitude: float, frequency: float, distance: float) -> Build:
    def build() -> tuple[Node, Camera]:
        from ..nodes.noise import displace
        return displace(sphere(1.0), amplitude, frequency, octaves=3), OrbitCamera(distance=distance, yaw=25, pitch=20)
    return build


# fine noise displacement: bumps a fraction of a footprint to a footprint deep, a few wide
NOISE_CASES: tuple[HardCase, ...] = (
    HardCase("noise_fine_bumps", "a sphere displaced by fine noise (amplitude 0.03, frequency 8)",
             _bumpy(0.03, 8.0, 3.5)),
    # bumps half a footprint wide at 64x48: rays clip their tips a footprint before the surface behind;
    # the normal varies across a pixel there (the stencil and the reference's point normal part)
    HardCase("noise_tiny_bumps", "a sphere displaced by noise finer than a pixel (amplitude 0.02, frequency 40)",
             _bumpy(0.02, 40.0, 3.5), expect=Expect(depth_px_p99=0.5, normal_deg_median=2.0, normal_deg_p99=90.0)),
    HardCase("noise_finer_bumps", "a sphere displaced by finer noise (amplitude 0.015, frequency 14)",
             _bumpy(0.015, 14.0, 3.0), expect=Expect(surface_px_max=0.6)),  # one silhouette pixel 0.52
    HardCase("noise_bumps_far", "fine noise on a sphere seen from afar (amplitude 0.06, frequency 6)",
             _bumpy(0.06, 6.0, 6.0)),
)

MARCHING_CASES: tuple[HardCase, ...] = GROUND_CASES + EXIT_CASES + CRITICAL_CASES + NOISE_CASES
