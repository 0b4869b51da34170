"""Other 20-node subtrees as 1000 translated copies against 1000 spheres (pairs timed alone)."""
import statistics, sys
import numpy as np
import sdfgl as sg
from sdfgl.bench import FrameTimer, Variant
from sdfgl.bench_big import instances, spheres_like, NO_SHADING, twenty_nodes
from sdfgl.render import Renderer

def chair():
    seat = sg.box((0.5, 0.06, 0.5)).translate((0, 0, 0))
    back = sg.rounded_box((0.5, 0.5, 0.06), 0.02).translate((0, 0.28, -0.22))
    legs = sg.union(*[sg.cylinder(0.03, 0.4).translate((x, -0.2, z)) for x in (-0.21, 0.21) for z in (-0.21, 0.21)])
    holes = sg.union(*[sg.cylinder(0.05, 0.2).rotate(90, (1, 0, 0)).translate((x, 0.3, -0.22)) for x in (-0.12, 0.12)])
    return sg.difference(sg.union(seat, back, legs), holes)

def csg():
    c = sg.cylinder(0.15, 0.8)
    body = sg.intersection(sg.sphere(0.35), sg.box(0.52))
    return body - sg.union(c, c.rotate(90, (1, 0, 0)), c.rotate(90, (0, 0, 1)))

def lamp():  # smooth: one box
    return sg.union(sg.sphere(0.2).translate((0, 0.25, 0)), sg.capsule((0, -0.3, 0), (0, 0.2, 0), 0.04),
                    sg.cylinder(0.15, 0.04).translate((0, -0.32, 0)), k=0.05)

def tower():  # turned parts
    parts = [sg.box((0.3, 0.1, 0.3)).rotate(15 * i, (0, 1, 0)).translate((0, -0.4 + 0.2 * i, 0)) for i in range(5)]
    return sg.union(*parts) | sg.sphere(0.1).translate((0, 0.6, 0))

kinds = {"robot": twenty_nodes, "chair": chair, "csg": csg, "lamp": lamp, "tower": tower}
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
m = lambda x: 1000 * statistics.median(x)
sp = spheres_like(1000)
for name in sys.argv[1:] or kinds:
    sub = kinds[name]()
    from sdfgl.nodes.traverse import postorder
    nodes = len({id(n) for n in postorder(sub)})
    ro = instances(1000, 0, sub)
    vs = [Variant("spheres", "1000", dict(NO_SHADING), *sp), Variant(name, "1000", dict(NO_SHADING), *ro)]
    calls = {}
    for v in vs:
        timer.prepare(v)
        calls[v.scene] = float(r.render(v.node, v.camera, size, outputs=("steps",), **NO_SHADING).steps.mean())
    refined = "enterNear" in vs[1].result["_prog"][2].text
    ts = {v.scene: [] for v in vs}
    for rnd in range(27):
        for v in vs:
            dt = timer.draw(v)
            if rnd >= 2: ts[v.scene].append(dt)
    a, b = m(ts["spheres"]), m(ts[name])
    print(f"{name} ({nodes} nodes, refined {refined}): spheres {a:.2f} ms {calls['spheres']:.2f} calls; {b:.2f} ms {calls[name]:.2f} calls; ratio {b/a:.3f}", flush=True)
