"""Hard cases of bounds and signs: polygons kept as an edge grid on round coordinates, n-ary
smooth unions with large blend radii, offsets of stretched fields."""
from __future__ import annotations

from typing import Callable

import numpy as np

from ..camera import Camera, OrbitCamera
from ..nodes import box, ellipsoid, extrude, polygon, sphere, union
from ..nodes.base import Node
from .spec import Expect, HardCase


def _comb_outline(teeth: int, height: float) -> np.ndarray:
    """A comb on round coordinates (a base strip 1 high, teeth half a unit wide), 1/4 scale."""
    width = teeth + 1.0
    pts = [(0.0, 0.0), (width, 0.0), (width, 1.0)]
    for j in range(teeth, 0, -1):
        pts += [(j + 0.5, 1.0), (j + 0.5, height), (j, height), (j, 1.0)]
    return (np.array(pts + [(0.0, 1.0)]) - width / 2) / 4.0


def _comb(height: float, yaw: float, pitch: float) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        # 64 vertices over 16 x 16 units: the edge grid's cells are exactly 2 units, so their
        # centres lie on the teeth's sides at odd x
        return (extrude(polygon(_comb_outline(15, height)), 0.3).rotate(-90, (1, 0, 0)),
                OrbitCamera(distance=6.0, yaw=yaw, pitch=pitch))
    return build


def _floor_plan() -> tuple[Node, Camera]:
    rng = np.random.default_rng(5)
    steps = rng.integers(1, 4, size=(31, 2))
    pts = [(0, 0)]
    for x, y in np.cumsum(steps, axis=0):
        pts += [(int(x), pts[-1][1]), (int(x), int(y))]
    pts += [(pts[-1][0], pts[-1][1] + 3), (0, pts[-1][1] + 3)]
    v = np.array(pts, dtype=float)
    v = (v - v.mean(axis=0)) / float(np.ptp(v, axis=0).max()) * 3.0
    return extrude(polygon(v), 0.2).rotate(-90, (1, 0, 0)), OrbitCamera(distance=5.0, yaw=25, pitch=60)


def _metaballs(k: float, blend: str, n: int, spread: float) -> Callable[[], tuple[Node, Camera]]:
    def build() -> tuple[Node, Camera]:
        rng = np.random.default_rng(n)
        balls = [sphere(float(r)).translate(tuple(c))
                 for r, c in zip(rng.uniform(0.15, 0.3, n), rng.uniform(-spread, spread, (n, 3)))]
        return union(*balls, k=k, blend=blend), OrbitCamera(distance=6.5, yaw=30, pitch=20)
    return build


def _rounded_stretch() -> tuple[Node, Camera]:
    # rounding a stretched sphere and an ellipsoid: their fields rise slower than the
    # distance outside their boxes, so the offset's reach is the child's stretch times r
    s = union(sphere(0.4).scale((3.0, 0.6, 1.0)).round(0.3), ellipsoid((0.9, 0.2, 0.3)).translate((0, 0.9, 0)).round(0.25),
              box((0.4, 0.4, 0.4)).translate((0, -0.9, 0)))
    return s, OrbitCamera(distance=6.0, yaw=15, pitch=25)


BOUNDS_CASES: tuple[HardCase, ...] = (
    HardCase("polygon_grid_comb", "a 64-vertex comb whose edge-grid cell centres lie on its edges",
             _comb(16.0, 10, 70)),
    HardCase("polygon_grid_comb_low", "the comb, shorter teeth, seen low along its teeth", _comb(10.0, 80, 25),
             expect=Expect(normal_deg_p99=30.0)),  # teeth a third of a pixel wide: most hits straddle an edge
    HardCase("polygon_grid_floor_plan", "a staircase floor plan on the integer grid (66 vertices)", _floor_plan),
    HardCase("metaballs_k1", "three spheres blended with k = 1 (each fold reaches k/4 further)",
             _metaballs(1.0, "quadratic", 3, 0.2)),
    HardCase("metaballs_k2_12", "twelve spheres blended with k = 2", _metaballs(2.0, "quadratic", 12, 0.6)),
    HardCase("metaballs_circular", "five spheres, circular blend with k = 0.6", _metaballs(0.6, "circular", 5, 0.5)),
    HardCase("metaballs_chamfer", "five spheres, chamfer blend with k = 1", _metaballs(1.0, "chamfer", 5, 0.5)),
    HardCase("rounded_stretch", "offsets of a stretched sphere and an ellipsoid", _rounded_stretch),
)
