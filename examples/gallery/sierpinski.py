"""A Sierpinski tetrahedron (after Monzón González's Zaragoza thesis): 4^6 copies at the cost of six mirror folds."""
import sdfgl as sg

scene = sg.sierpinski(6, 1.0).color(0.85, 0.8, 0.7).rotate(-45, sg.Y).translate((0, 1.0, 0))
camera = sg.OrbitCamera(target=(0, 0.9, 0), distance=4.2, yaw=30, pitch=15)
settings = {"ground": True}
