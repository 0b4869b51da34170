"""Deformations with honest Lipschitz factors: twist, bend, non-uniform scale, noise displacement."""
import sdfgl as sg

scene = sg.union(
    sg.box((0.6, 2.0, 0.6)).twist(90).color(0.85, 0.4, 0.2).translate((-2.2, 1.0, 0)),
    sg.box((2.0, 0.25, 0.5)).bend(35).color(0.3, 0.6, 0.85).translate((-0.4, 0.6, 0)),
    sg.sphere(0.6).scale((1.6, 0.6, 1.0)).color(0.5, 0.75, 0.4).translate((1.4, 0.36, 0)),
    sg.sphere(0.55).displace(0.08, 4.0, 4).color(0.8, 0.7, 0.6).translate((3.0, 0.62, 0)),
)
camera = sg.OrbitCamera(target=(0.4, 0.6, 0), distance=6.8, yaw=5, pitch=20)
settings = {"ground": True}
