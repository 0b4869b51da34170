"""Domain operators: mirror symmetry, polar and finite repetition, elongate, round, shell.
The shell thickness, the rounding radius and the ring's colour are live (sliders and a colour picker)."""
import sdfgl as sg

thickness = sg.param(0.06, "shell thickness", range=(0.02, 0.15))
radius = sg.param(0.12, "rounding", range=(0.02, 0.25))
gold = sg.param((0.9, 0.7, 0.2), "ring colour")

ring = sg.capsule((-0.15, 0, 0), (0.15, 0, 0), 0.12).translate((1.0, 0, 0)).repeat_polar(10).color(gold)
arch = sg.box((0.3, 0.9, 0.3)).translate((0.6, 0.45, 0)).symmetric("x").color(0.6, 0.6, 0.65) | \
    sg.box((1.5, 0.2, 0.3)).translate((0, 1.0, 0)).color(0.6, 0.6, 0.65)
pills = sg.sphere(0.25).elongate((0.4, 0, 0)).repeat((0, 0, 0.7), count=(0, 0, 2)).color(0.3, 0.7, 0.5)
shelled = (sg.sphere(0.55).shell(thickness) - sg.box(1.2).translate((0, 0.6, 0))).color(0.85, 0.35, 0.3)
rounded = sg.box(0.6).round(radius).color(0.4, 0.5, 0.9)
scene = sg.union(ring.translate((-2.3, 0.15, 0)), arch.translate((0, 0, 0)), pills.translate((2.3, 0.25, 0)),
                 shelled.translate((-0.9, 0.55, 1.6)), rounded.translate((0.9, 0.72, 1.6)))
camera = sg.OrbitCamera(target=(0, 0.4, 0.5), distance=6.5, yaw=15, pitch=35)
settings = {"ground": True}
