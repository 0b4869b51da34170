"""More solids and operators: Platonic solids, a pyramid, a tube along a polyline and a
Bezier curve, a capped torus, a gyroid ball, a box morphing into a sphere, a sheared box,
a tapered, an eroded and a bent box, and a wavy sphere written in GLSL (sg.glsl) with its
numpy twin."""
import numpy as np

import sdfgl as sg

wavy = sg.glsl("return length(p) - 0.35 - 0.03 * sin(12.0 * p.x) * sin(12.0 * p.y);",
               twin=lambda p: np.linalg.norm(p, axis=-1) - 0.35 - 0.03 * np.sin(12 * p[:, 0]) * np.sin(12 * p[:, 1]),
               lipschitz=1.6, bounds=((-0.4, -0.4, -0.4), (0.4, 0.4, 0.4)))

scene = sg.union(
    sg.tetrahedron(0.25).translate((-2.4, 0.42, -0.8)).color("tomato"),
    sg.dodecahedron(0.35).translate((-1.6, 0.45, -0.8)).color("gold"),
    sg.icosahedron(0.35).translate((-0.8, 0.45, -0.8)).color("mediumseagreen"),
    sg.pyramid(0.9, 0.8).translate((0.1, 0.0, -0.8)).color("sandybrown"),
    sg.capped_torus(0.35, 0.08, 250).translate((1.0, 0.45, -0.8)).color("orchid"),
    (sg.gyroid(14.0, 0.05) & sg.sphere(0.45)).translate((2.0, 0.45, -0.8)).color("steelblue"),
    sg.tube([(-2.6, 0.1, 0.6), (-2.2, 0.7, 0.9), (-1.7, 0.2, 0.5), (-1.3, 0.8, 0.7)], 0.07).color("slategray"),
    sg.bezier_tube((-1.0, 0.1, 0.7), (-0.4, 1.6, 0.4), (0.2, 0.1, 0.8), 0.08).color("darkorange"),
    sg.morph(sg.box(0.7), sg.sphere(0.4), 0.5).translate((0.9, 0.38, 0.7)).color("cadetblue"),
    sg.box((0.4, 0.7, 0.4)).shear(0.5, "x", "y").translate((1.9, 0.35, 0.7)).color("indianred"),
    sg.box((0.5, 0.8, 0.5)).taper(-0.6, "y", -0.4).translate((-2.3, 0.4, 1.8)).color("khaki"),
    sg.rounded_box(0.7, 0.2).erode(0.1).translate((-1.2, 0.25, 1.8)).color("plum"),
    sg.box((1.2, 0.2, 0.2)).bend(50, "y").translate((0.0, 0.1, 1.8)).color("lightseagreen"),
    wavy.translate((1.3, 0.4, 1.8)).color("salmon"),
)
camera = sg.OrbitCamera(target=(-0.2, 0.4, 0.5), distance=6.6, yaw=10, pitch=32)
settings = {"ground": True}
