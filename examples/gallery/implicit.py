"""Implicit surfaces from expressions (f / |grad f|, gradient by sympy) and a rational
parametric surface implicitized with a Groebner basis; rendered by Newton marching."""
import sdfgl as sg

tangle = sg.implicit("x**4 - 5*x**2 + y**4 - 5*y**2 + z**4 - 5*z**2 + 11.8",
                     bounds=((-2.8, -2.8, -2.8), (2.8, 2.8, 2.8))).color(0.85, 0.5, 0.3)
saddle = sg.parametric("s", "t", "(s**2 - t**2)/2", bounds=((-1.2, -1, -1.2), (1.2, 1, 1.2))).color(0.3, 0.6, 0.9)
scene = sg.union(tangle.scale(0.6).translate((-1.7, 0, 0)), saddle.translate((1.8, 0, 0)))
camera = sg.OrbitCamera(target=(0, 0, 0), distance=7, yaw=25, pitch=25)
settings = {"method": "newton", "ao": False}
