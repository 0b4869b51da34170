"""The classic CSG example: a sphere-box intersection drilled by three cylinders."""
import sdfgl as sg

ball = (sg.sphere(1) & sg.box(1.5)).color(0.85, 0.3, 0.2)
drill = sg.cylinder(0.5, 4).orient(sg.X) | sg.cylinder(0.5, 4) | sg.cylinder(0.5, 4).orient(sg.Z)
scene = ball - drill.color(0.95, 0.8, 0.3)
camera = sg.OrbitCamera(distance=5, yaw=30, pitch=20)
