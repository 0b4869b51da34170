"""2D shapes made solid: an extruded star and rounded plate, a revolved vase and ring."""
import math

import sdfgl as sg

star = sg.polygon([((0.5 if i % 2 else 1.0) * math.cos(a), (0.5 if i % 2 else 1.0) * math.sin(a))
                   for i, a in enumerate(math.pi / 2 + 2 * math.pi * k / 10 for k in range(10))])
vase = sg.polygon([(0.0, 0.0), (0.45, 0.0), (0.55, 0.4), (0.3, 0.9), (0.4, 1.3), (0.0, 1.3)])
scene = sg.union(
    sg.extrude(star, 0.3).color(0.9, 0.75, 0.2).translate((-1.8, 1.0, 0)),
    sg.extrude(sg.rectangle((1.2, 0.8), 0.2), 0.2).rotate(90, sg.X).color(0.4, 0.5, 0.8).translate((0, 0.1, 0)),
    sg.revolve(vase).color(0.8, 0.4, 0.3).translate((0, 0.2, 0)),
    sg.revolve(sg.circle(0.12), 0.5).color(0.3, 0.7, 0.5).translate((1.8, 0.12, 0)),
)
camera = sg.OrbitCamera(target=(0, 0.6, 0), distance=5.5, yaw=20, pitch=25)
settings = {"ground": True}
