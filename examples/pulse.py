"""An animated scene file: blobs that merge and part, a ring that turns, a keyframed colour.

    sdfgl animate examples/pulse.py -o pulse.mp4 --seconds 4 --turntable --ground
"""
import sdfgl as sg

t = sg.time()
swing = 0.55 * sg.sin(t * 3.14159265 / 2)                    # one swing per 4 s
blobs = sg.union(sg.sphere(0.45).translate(sg.mix((-0.9, 0.5, 0), (0.9, 0.5, 0), 0.5 + swing)),
                 sg.sphere(0.4).translate(sg.mix((0.9, 0.45, 0), (-0.9, 0.45, 0), 0.5 + swing)),
                 k=0.35).color(sg.keyframes({0: (0.9, 0.35, 0.25), 2: (0.25, 0.55, 0.95), 4: (0.9, 0.35, 0.25)},
                                            ease="smooth", time=t))
ring = sg.torus(0.9, 0.08).rotate(90, (1, 0, 0)).rotate(t * 90, (0, 1, 0)).translate((0, 0.5, 0)).color(0.95, 0.8, 0.3)
base = sg.rounded_box((2.6, 0.2, 1.4), 0.08).translate((0, -0.15, 0)).color(0.6, 0.6, 0.65)
scene = blobs | ring | base
camera = sg.OrbitCamera(target=(0, 0.35, 0), distance=4.2, yaw=20, pitch=22)
