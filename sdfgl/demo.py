"""The built-in showcase scene (`sdfgl render --demo`): every primitive family on a ground plane."""
from __future__ import annotations

from .camera import OrbitCamera
from .nodes import (box, capsule, cone, cylinder, ellipsoid, hex_prism, octahedron, rounded_box, sphere,
                    torus, union)
from .nodes.base import Node
from .nodes.booleans import difference
from .render import RenderResult, render


def demo_scene() -> Node:
    """A small gallery: CSG in the middle, primitives and a smooth blend around it."""
    drill = cylinder(0.5, 4).orient((1, 0, 0)) | cylinder(0.5, 4) | cylinder(0.5, 4).orient((0, 0, 1))
    csg = difference((sphere(1) & box(1.5)).color(0.85, 0.3, 0.2), drill.color(0.95, 0.8, 0.3))
    blob = union(sphere(0.45).translate((-0.25, 0, 0)), sphere(0.35).translate((0.3, 0.15, 0)),
                 k=0.3).color(0.3, 0.6, 0.9)
    parts = [
        csg.translate((0, 0.75, 0)),
        torus(0.5, 0.15).color(0.9, 0.75, 0.2).rotate(20, (1, 0, 0)).translate((2.2, 0.65, 0)),
        capsule((-0.4, 0, 0), (0.4, 0.5, 0), 0.2).color(0.4, 0.8, 0.4).translate((-2.2, 0.2, 0)),
        rounded_box((0.8, 0.8, 0.8), 0.15).color(0.6, 0.4, 0.8).translate((0, 0.4, -2.2)),
        cone(1.0, 0.45, 0.1).color(0.9, 0.5, 0.2).translate((2.0, 0.5, -1.8)),
        ellipsoid((0.6, 0.3, 0.4)).color(0.8, 0.8, 0.85).translate((-2.0, 0.3, -1.8)),
        octahedron(0.5).color(0.2, 0.7, 0.7).translate((2.0, 0.5, 1.9)),
        hex_prism(0.4, 0.8).color(0.75, 0.3, 0.5).translate((-2.0, 0.4, 1.9)),
        blob.translate((0, 0.45, 2.1)),
    ]
    return union(*parts)


def demo_camera() -> OrbitCamera:
    return OrbitCamera(target=(0, 0.4, 0), distance=7.5, yaw=35, pitch=28, fov=45)


def render_demo(size: tuple[int, int] = (800, 600), aa: int = 2) -> RenderResult:
    """Render the showcase with soft shadows, AO and the ground plane."""
    return render(demo_scene(), demo_camera(), size, aa=aa, shadows="soft", ao=True, ground=True)
