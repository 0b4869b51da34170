"""Hard cases for numerical stability: each a named scene, camera and expected behaviour.

The tests hold the default renderer to each case's bounds against the float64
reference; the benchmark reuses the same cases to put speed beside error.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Callable

import numpy as np

from .camera import Camera, OrbitCamera
from .nodes import box, box_frame, difference, plane, product, rounded_box, sphere, union
from .nodes.base import Node
from .reference import ErrorReport

if TYPE_CHECKING:  # pragma: no cover
    from .render import RenderResult


@dataclass(frozen=True)
class Expect:
    """Bounds a render must meet against the reference (fractions are of all pixels)."""

    mismatch_frac: float = 0.04     # silhouette mismatch / pixels (near misses count as hits)
    lost_frac: float = 0.001        # reference hits the render missed / pixels
    outlier_frac: float = 0.01      # depth outliers (> 2 footprints apart) / pixels
    depth_px_median: float = 0.02   # median |t - t*| in pixel footprints
    normal_deg_median: float = 0.1
    min_hits: int = 1               # the case must actually show geometry

    def violations(self, e: ErrorReport) -> list[str]:
        """Human-readable list of the bounds ``e`` breaks (empty when it passes)."""
        out = []
        checks = [("silhouette mismatch share", e.silhouette_mismatch / e.pixels, self.mismatch_frac),
                  ("lost-hit share", e.lost_hits / e.pixels, self.lost_frac),
                  ("depth-outlier share", e.depth_outliers / e.pixels, self.outlier_frac),
                  ("depth median (px)", e.depth_px_median, self.depth_px_median),
                  ("normal median (deg)", e.normal_deg_median, self.normal_deg_median)]
        out += [f"{name} {val:.4g} > {lim:.4g}" for name, val, lim in checks if val > lim]
        if e.nan_count:
            out.append(f"{e.nan_count} NaN/Inf values")
        if e.hits < self.min_hits:
            out.append(f"only {e.hits} reference hits (< {self.min_hits})")
        return out


@dataclass(frozen=True)
class HardCase:
    name: str
    what: str                       # the difficulty, in a sentence
    build: Callable[[], tuple[Node, Camera]]
    settings: dict = field(default_factory=dict)
    expect: Expect = Expect()
    max_dist: float = 1000.0


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


CASES: tuple[HardCase, ...] = (
    HardCase("grazing_sphere", "rays graze a sphere seen from just above its surface", _grazing_sphere),
    HardCase("horizon_plane", "a ground plane up to the horizon: ever shallower rays", _horizon_plane),
    HardCase("rounded_box", "seed Exp. 1: silhouette grazing on a rounded box", _rounded_box),
    HardCase("tunnel", "seed Exp. 2: four planes meeting ahead of the camera", _tunnel),
    HardCase("five_spheres", "seed Exp. 3: staggered spheres, rays pass near nearer ones", _five_spheres),
    HardCase("product_union", "seed: a product of two SDFs, not a distance (Newton marching)",
             _product_union, settings={"method": "newton"},
             expect=Expect(mismatch_frac=0.05, outlier_frac=0.02, lost_frac=0.005)),
    HardCase("thin_shell", "a spherical shell 1e-3 thick, cut open", _thin_shell,
             expect=Expect(outlier_frac=0.02)),
    HardCase("box_frame", "thin bars (0.02) of a box frame", _box_frame, expect=Expect(mismatch_frac=0.07)),
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
)


def case(name: str) -> HardCase:
    """The hard case called ``name``."""
    for c in CASES:
        if c.name == name:
            return c
    raise KeyError(f"no hard case '{name}'; known: {', '.join(c.name for c in CASES)}")


def run_case(c: HardCase, size: tuple[int, int] = (64, 48), **settings: object) -> tuple[ErrorReport, "RenderResult"]:
    """Render ``c`` (shadows and AO off: only primary rays matter) and compare with the reference."""
    from .reference import compare, trace
    from .render import render
    scene, cam = c.build()
    opts = {"shadows": False, "ao": False, "max_dist": c.max_dist, **c.settings, **settings}
    res = render(scene, cam, size, outputs=("color", "depth", "normal", "steps"), **opts)
    return compare(res, trace(scene, cam, size, max_dist=c.max_dist)), res


def table(size: tuple[int, int] = (128, 96), **settings: object) -> str:
    """A markdown table of every hard case's errors for the given settings."""
    rows = ["| case | hits | silhouette mismatch (false/lost) | depth outliers | depth med / p99 (px) "
            "| normal med / p99 (deg) | NaN | mean steps | bounds met |",
            "|---|---|---|---|---|---|---|---|---|"]
    for c in CASES:
        e, res = run_case(c, size, **settings)
        bad = c.expect.violations(e)
        rows.append(f"| {c.name} | {e.hits} | {e.silhouette_mismatch} ({e.false_hits}/{e.lost_hits}) | "
                    f"{e.depth_outliers} | {e.depth_px_median:.2g} / {e.depth_px_p99:.2g} | "
                    f"{e.normal_deg_median:.2g} / {e.normal_deg_p99:.2g} | {e.nan_count} | "
                    f"{float(res.steps.mean()):.1f} | {'yes' if not bad else '; '.join(bad)} |")
    return "\n".join(rows)


if __name__ == "__main__":  # python -m sdfgl.hardcases [WxH]
    import sys
    w, h = (int(x) for x in (sys.argv[1] if len(sys.argv) > 1 else "128x96").split("x"))
    print(table((w, h)))
