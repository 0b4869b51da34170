"""The first hard cases: grazing rays, far and large worlds, warps, offsets, thin parts."""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..camera import Camera, OrbitCamera
from ..nodes import box, box_frame, difference, plane, product, rounded_box, sphere, torus, union
from ..nodes.base import Node
from .spec import Expect, HardCase


def _grazing_sphere() -> tuple[Node, Camera]:
    return sphere(1.0), OrbitCamera(distance=1.15, yaw=0, pitch=0, fov=100)


def _horizon_plane() -> tuple[Node, Camera]:
    return plane((0, 1, 0), (0, 0, 0)), Camera.look_at((0, 0.25, 0), (0, 0.2, -10), fov=60)


def _rounded_box() -> tuple[Node, Camera]:
    return rounded_box(2.0, 0.3), OrbitCamera(distance=5, yaw=30, pitch=25)


def _tunnel() -> tuple[Node, Camera]:
    apex, s = np.array([0.0, 0.0, -20.0]), 0.1
    walls = [plane(n, apex) for n in ((-1, 0, s), (1, 0, s), (0, -1, s), (0, 1, s))]
    return union(*walls), Camera.look_at((0, 0, 0), tuple(apex), fov=70)


def _five_spheres() -> tuple[Node, Camera]:
    balls = [sphere(0.5).translate((-2.0 + i, 0.0, -0.6 * i)) for i in range(5)]
    return union(*balls), Camera.look_at((0, 0.3, 4), (0, 0, -1.2), fov=60)


def _product_union() -> tuple[Node, Camera]:
    s = product(sphere(0.6).translate((-0.5, 0, 0)), box(0.8).translate((0.6, 0, 0)))
    return s, OrbitCamera(distance=4, yaw=20, pitch=20)


def _thin_shell() -> tuple[Node, Camera]:
    shell = difference(sphere(1.0), sphere(0.999), box((2.2, 2.2, 2.2)).translate((0, 0, 1.3)))
    return shell, OrbitCamera(distance=3.5, yaw=35, pitch=25)


def _box_frame() -> tuple[Node, Camera]:
    return box_frame(2.0, 0.02), OrbitCamera(distance=4.5, yaw=30, pitch=25)


def _far(t: float) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        fov = float(np.degrees(2 * np.arctan(1.6 / t)))  # the unit sphere fills most of the frame
        return sphere(1.0), Camera.look_at((0.3, 0.2, t), (0, 0, 0), fov=fov)
    return build


def _large_world() -> tuple[Node, Camera]:
    c = np.array([1e5, 5e4, -1e5])
    scene = (box(1.5) - sphere(0.95)).translate(c)
    return scene, OrbitCamera(target=c, distance=4, yaw=30, pitch=25)


def _camera_inside() -> tuple[Node, Camera]:
    return sphere(1.0), Camera.look_at((0, 0, 0), (0, 0, -1), fov=60)


def _twist() -> tuple[Node, Camera]:
    return box((0.8, 2.0, 0.5)).twist(120), OrbitCamera(distance=4.5, yaw=20, pitch=20)


def _bend() -> tuple[Node, Camera]:
    return box((2.4, 0.3, 0.6)).bend(40), OrbitCamera(distance=4, yaw=10, pitch=30)


def _squash() -> tuple[Node, Camera]:
    return sphere(1.0).scale((2.0, 0.4, 1.0)), OrbitCamera(distance=5, yaw=30, pitch=30)


def _smooth(k: float) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        s = union(sphere(0.7).translate((-0.45, 0, 0)), box(0.9).translate((0.5, 0, 0)), k=k)
        return s, OrbitCamera(distance=4.5, yaw=20, pitch=20)
    return build


def _repeat_boundary() -> tuple[Node, Camera]:
    # spheres of radius 0.5 every 1.0: each touches its cell walls and its neighbours
    return sphere(0.5).repeat((1.0, 0.0, 1.0), count=(3, 0, 3)), OrbitCamera(distance=9, yaw=30, pitch=35)


def _normal_jumps() -> tuple[Node, Camera]:
    # two spheres touching at one point (the gradient jumps) and a box seen edge-on
    s = union(sphere(0.5).translate((-0.5, 0.6, 0)), sphere(0.5).translate((0.5, 0.6, 0)),
              box(1.0).rotate(45, (0, 1, 0)).translate((0, -0.6, 0)))
    return s, Camera.look_at((0, 0, 4), (0, 0, 0), fov=50)


def _grazing_face(deg: float) -> Callable[[], tuple[Node, Camera]]:
    # the top face of a long slab, every ray meeting it at deg/2 to 3 deg/2 degrees
    def build() -> tuple[Node, Camera]:
        slab = box((4.0, 1.0, 100.0)).translate((0, -0.5, -40))
        return slab, Camera.look_at((0, 10 * np.tan(np.radians(deg)), 10), (0, 0, 0), fov=deg)
    return build


def _small_beside_big(ratio: float) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        s = 200.0 / ratio  # a cube of this size on a floor 200 wide
        scene = box((200, 1, 200)).translate((0, -0.5, 0)) | box(s).translate((0.3 * s, s / 2, -0.2 * s))
        return scene, Camera.look_at((2.2 * s, 1.8 * s, 2.6 * s), (0.3 * s, s / 2, -0.2 * s), fov=40)
    return build


def _offset(r: float) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        c = r * np.array([0.8123456789, -0.4567891234, 0.3651234567])  # on no power-of-two grid
        scene = (box(1.5) - sphere(0.95)).translate(tuple(c))
        return scene, OrbitCamera(target=tuple(c), distance=4, yaw=30, pitch=25)
    return build


def _twist_720() -> tuple[Node, Camera]:
    return box((0.8, 2.0, 0.5)).twist(720), OrbitCamera(distance=4.5, yaw=20, pitch=20)


def _bend_120() -> tuple[Node, Camera]:
    return box((2.4, 0.3, 0.6)).bend(120), OrbitCamera(distance=4, yaw=10, pitch=30)


def _warp(node: Node, distance: float, yaw: float, pitch: float) -> Callable[[], tuple[Node, Camera]]:
    # more warps at other rates, sizes, positions and views: rays skim the warped faces
    return lambda: (node, OrbitCamera(distance=distance, yaw=yaw, pitch=pitch))


def _ghost_wall() -> tuple[Node, Camera]:
    # the side faces of both boxes coincide where z in (0, 0.5): f = 0 on a sheet, > 0 either side
    return box(1.0) - box(1.0).translate((0, 0, 0.5)), OrbitCamera(distance=4, yaw=30, pitch=20)


def _empty_difference() -> tuple[Node, Camera]:
    a = rounded_box(1.2, 0.2)
    return a - a, OrbitCamera(distance=4, yaw=30, pitch=20)


def _small_spheres() -> tuple[Node, Camera]:
    balls = [sphere(0.05).translate((x, y, 0.0)) for x in np.linspace(-1, 1, 7) for y in np.linspace(-0.7, 0.7, 5)]
    return union(*balls), Camera.look_at((0, 0, 4), (0, 0, 0), fov=40)


def _low_repeat() -> tuple[Node, Camera]:
    # a 61 x 61 field of spheres seen at a low angle: rays pass near one sphere on the way to another
    return (sphere(0.3).repeat((1.0, 0.0, 1.0), count=(30, 0, 30)),
            Camera.look_at((0.17, 0.55, 31.3), (0.0, 0.0, 0.0), fov=40))


def _telephoto() -> tuple[Node, Camera]:
    return sphere(1.0).translate((0.1, 0, 0)), Camera.look_at((0.3, 0.2, 1000), (0, 0, 0), fov=0.5)


def _big_sphere() -> tuple[Node, Camera]:
    return sphere(1e4), OrbitCamera(distance=3.2e4, yaw=30, pitch=20)


def _far_torus() -> tuple[Node, Camera]:
    return torus(1e4, 3e3), OrbitCamera(distance=4e4, yaw=20, pitch=30)


def _near_face() -> tuple[Node, Camera]:
    return box(100.0), Camera.look_at((0.3, 0.2, 50 + 1e-4), (0.3, 0.2, 0), fov=60)  # 1e-6 of the size away


def _on_surface() -> tuple[Node, Camera]:
    # the eye exactly on a face: rays into the solid hit at 0, rays leaving it go on
    return box(2.0).translate((0, 0, -1)) | sphere(0.5).translate((0, 0, 3)), Camera.look_at((0, 0, 0), (0, 0, 1), fov=120)


def _tilted_ground(r: float) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        n = np.array([0.12, 1.0, 0.07]) / np.linalg.norm([0.12, 1.0, 0.07])
        o = r * np.array([0.8123456789, 0.3651234567, -0.4567891234])  # on no power-of-two grid
        c = o + 0.018 * n
        scene = plane(tuple(n), tuple(o)) | box(0.02).translate(tuple(c))
        return scene, Camera.look_at(tuple(c + (0.026, 0.032, 0.04)), tuple(c - 0.006 * n), fov=60)
    return build


def _live_far() -> tuple[Node, Camera]:
    from ..params import param
    c = 1e6 * np.array([0.8123456789, -0.4567891234, 0.3651234567])
    where = param(tuple(c), "where")
    radius = param(0.45, "radius")
    scene = (box(0.8) | sphere(radius).translate((0.5, 0.3, 0.2))).translate(where)
    return scene, OrbitCamera(target=tuple(c), distance=3, yaw=30, pitch=25)


def _implicit(expr: str) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        from ..nodes.implicit import implicit
        # the rays start where f overflows float32 (|z| = 7); bounds keep the reference's fixed steps few
        scene = implicit(expr, bounds=((-8.0, -8.0, -8.0), (8.0, 8.0, 8.0)))
        return scene, Camera.look_at((4.4, 3.2, 6.8), (0.0, 0.0, 0.0), fov=24)
    return build


BASE_CASES: tuple[HardCase, ...] = (
    HardCase("grazing_sphere", "rays graze a sphere seen from just above its surface", _grazing_sphere),
    HardCase("horizon_plane", "a ground plane up to the horizon: ever shallower rays", _horizon_plane),
    HardCase("rounded_box", "Monzón González, Exp. 1: silhouette grazing on a rounded box", _rounded_box),
    HardCase("tunnel", "Monzón González, Exp. 2: four planes meeting ahead of the camera", _tunnel),
    HardCase("five_spheres", "Monzón González, Exp. 3: staggered spheres, rays pass near nearer ones", _five_spheres),
    HardCase("product_union", "Monzón González: a product of two SDFs, not a distance (Newton marching)",
             _product_union, settings={"method": "newton"},
             expect=Expect(outlier_frac=0.02, lost_frac=0.005)),
    HardCase("thin_shell", "a spherical shell 1e-3 thick, cut open", _thin_shell,
             expect=Expect(outlier_frac=0.02)),
    HardCase("box_frame", "thin bars (0.02) of a box frame", _box_frame,
             expect=Expect(normal_deg_p99=30.0)),  # bars 2 pixels wide: most pixels straddle an edge
    HardCase("far_1e3", "a unit sphere 1e3 away (narrow fov)", _far(1e3)),
    HardCase("far_1e4", "a unit sphere 1e4 away (narrow fov)", _far(1e4), max_dist=2e4),
    HardCase("large_world", "a scene 1e5 units from the origin", _large_world),
    HardCase("camera_inside", "the eye at the centre of a solid sphere (gradient 0 there)", _camera_inside),
    HardCase("twist", "twisted box: Lipschitz factor > 1", _twist),
    HardCase("bend", "bent bar: Lipschitz factor > 1", _bend),
    HardCase("nonuniform_scale", "sphere scaled (2, 0.4, 1): a bound, not exact", _squash),
    HardCase("smooth_k_tiny", "smooth union with k = 1e-6", _smooth(1e-6)),
    HardCase("smooth_k_large", "smooth union with k = 2", _smooth(2.0)),
    HardCase("repeat_boundary", "repeated spheres touching their cell walls", _repeat_boundary,
             expect=Expect(outlier_frac=0.05)),
    HardCase("normal_jumps", "gradient jumps: touching spheres and a box edge", _normal_jumps),
    *(HardCase(f"grazing_face_{deg:g}", f"a flat face seen at {deg / 2:g} to {1.5 * deg:g} degrees",
               _grazing_face(deg)) for deg in (0.5, 1.0, 2.0, 4.0)),
    HardCase("small_beside_big_1e3", "a 0.2 cube on a floor 200 wide (sizes 1:1e3)", _small_beside_big(1e3)),
    HardCase("small_beside_big_1e4", "a 0.02 cube on a floor 200 wide (sizes 1:1e4)", _small_beside_big(1e4)),
    *(HardCase(f"offset_{r:.0e}", f"a unit scene {r:.0e} from the origin, off any grid", _offset(r))
      for r in (1e5, 1e6, 1e7)),
    HardCase("twist_720", "twisted box at 720 degrees per unit", _twist_720,
             # 16 helical edges: about 1 % of hits at 128x96 lie within the normal step (1/50 of a
             # footprint) of an edge, where the normal is undefined
             expect=Expect(outlier_frac=0.005, normal_deg_p99=10.0)),
    HardCase("bend_120", "bent bar at 120 degrees per unit", _bend_120),
    HardCase("twist_360_low", "twisted box at 360 degrees per unit seen from below",
             _warp(box((0.8, 2.0, 0.5)).twist(360), 4.5, 50, -10)),
    HardCase("twist_1080", "thinner box twisted at 1080 degrees per unit",
             _warp(box((0.6, 2.0, 0.4)).twist(1080), 4.0, -30, 15), expect=Expect(normal_deg_p99=10.0)),  # edges
    HardCase("twist_720_off", "flat box twisted at 720 degrees per unit, off the view's centre",
             _warp(box((1.0, 2.0, 0.3)).twist(720).translate((0.3, 0.1, 0.0)), 5.0, 70, 35),
             expect=Expect(normal_deg_p99=10.0)),  # edges, as twist_720
    HardCase("bend_150", "bent bar at 150 degrees per unit, seen from the side",
             _warp(box((2.4, 0.3, 0.6)).bend(150), 4.0, -40, 10)),
    HardCase("bend_120_steep", "thin wide bar bent at 120 degrees per unit, seen steeply",
             _warp(box((2.0, 0.2, 0.8)).bend(120), 3.5, 80, 45)),
    HardCase("ghost_wall", "coinciding faces of a difference: f = 0 on a sheet outside the solid", _ghost_wall),
    HardCase("empty_difference", "a - a: an empty solid whose field touches 0 on a's surface",
             _empty_difference, expect=Expect(min_hits=0, max_hits=0)),
    HardCase("small_spheres", "35 spheres a few pixels wide: silhouettes everywhere", _small_spheres),
    HardCase("low_repeat", "61 x 61 repeated spheres seen at a low angle", _low_repeat),
    HardCase("telephoto_1000", "a unit sphere from 1000 away through a 0.5 degree lens (marched)", _telephoto,
             settings={"analytic": False}),
    HardCase("big_sphere_1e4", "a sphere of radius 1e4 (marched; beyond max_dist's default)", _big_sphere,
             settings={"analytic": False}),
    HardCase("far_torus", "torus(1e4, 3e3) seen from 4e4", _far_torus),
    HardCase("near_face_forward_newton", "forward Newton 1e-6 of the scene size from a face", _near_face,
             settings={"method": "forward_newton"},
             # the eye's own float32 rounding (8e-7 at 50) is 0.35 footprints at 64x48, 0.7 at 128x96
             expect=Expect(depth_px_median=1.0, depth_px_p99=1.0, surface_px_max=1.0)),
    HardCase("on_surface", "the eye exactly on a face: rays leaving the solid must go on", _on_surface),
    # the moving shader origin (unbounded and live scenes) and implicit fields that overflow float32
    *(HardCase(f"tilted_ground_{r:.0e}", f"a 0.02 cube on a tilted ground plane (unbounded) {r:.0e} out, off any grid",
               _tilted_ground(r)) for r in (1e7,)),
    HardCase("live_far_1e6", "live parameters (a translation, a radius) on a scene 1e6 out", _live_far),
    HardCase("implicit_x64", "implicit x^64 + y^64 + z^64 = 1: f overflows float32 beyond |x| = 4",
             _implicit("x**64 + y**64 + z**64 - 1"), settings={"method": "auto"}),  # auto: newton (implicit)
)
