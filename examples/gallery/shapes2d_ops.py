"""2D modelling: a gear from 2D booleans, a twisted star, a tapered rounded hexagon, an arc
handle, and a slice of a torus knot-like blend made solid again."""
import sdfgl as sg

teeth = sg.union(*[sg.rectangle((0.22, 0.3)).translate((0, 0.72)).rotate(360 * i / 12) for i in range(12)])
gear = (sg.circle(0.72) | teeth) - sg.regular_polygon(6, 0.25, 0.05)
blob = sg.slice(sg.union(sg.sphere(0.5).translate((-0.3, 0, 0)), sg.box(0.7).rotate(45, sg.Y).translate((0.3, 0, 0)),
                         k=0.3))
scene = sg.union(
    sg.extrude(gear, 0.25).rotate(-90, sg.X).translate((-1.9, 0.125, 0)).color("#c08040"),
    sg.extrude(sg.star(5, 0.6, sharpness=3.2), 1.4, twist=120).rotate(-90, sg.X).translate((-0.4, 0.7, 0.2)).color("crimson"),
    sg.extrude(sg.regular_polygon(6, 0.55, 0.12), 1.2, taper=0.55).rotate(-90, sg.X).translate((1.0, 0.6, -0.2))
    .color("steelblue"),
    sg.extrude(sg.arc(0.45, 220, 0.1) | sg.capsule2((-0.5, -0.1), (0.5, -0.1), 0.08), 0.2).translate((2.2, 0.55, 0.3))
    .color("seagreen"),
    sg.extrude(blob, 0.2).rotate(-90, sg.X).translate((0.4, 0.1, 1.3)).color("#e0c040"),
)
camera = sg.OrbitCamera(target=(0.2, 0.5, 0.2), distance=6.0, yaw=15, pitch=30)
settings = {"ground": True}
