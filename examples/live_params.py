"""The CSG part with live parameters: in `sdfgl html` / `sg.widget` each gets a slider."""
import sdfgl as sg

radius = sg.param(1.0, "radius", range=(0.75, 1.25))
hole = sg.param(0.45, "hole", range=(0.2, 0.65))
blend = sg.param(0.08, "blend", range=(0.01, 0.3))

ball = (sg.sphere(radius) & sg.box(1.5)).color(0.85, 0.3, 0.2)
drill = sg.cylinder(hole, 4).orient(sg.X) | sg.cylinder(hole, 4) | sg.cylinder(hole, 4).orient(sg.Z)
scene = sg.difference(ball, drill.color(0.95, 0.8, 0.3), k=blend)
camera = sg.OrbitCamera(distance=4.6, yaw=30, pitch=25)
settings = {"ground": True}
