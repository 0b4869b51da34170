"""Robots/spheres pair per grid constant combo (CF,MARGIN), each pair alone, strictly alternating."""
import statistics, sys
import sdfgl.nodes.grid as G
from sdfgl.bench import FrameTimer, Variant
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
m = lambda x: 1000 * statistics.median(x)
for arg in sys.argv[1:]:
    cf, mg = map(float, arg.split(","))
    G.CELL_FACTOR, G.MARGIN = cf, mg
    vs = [Variant("spheres", arg, dict(NO_SHADING), *spheres_like(1000)), Variant("robots", arg, dict(NO_SHADING), *instances(1000))]
    calls = {}
    for v in vs:
        timer.prepare(v)
        calls[v.scene] = float(r.render(v.node, v.camera, size, outputs=("steps",), **NO_SHADING).steps.mean())
    ts = {v.scene: [] for v in vs}
    for rnd in range(32):
        for v in vs:
            dt = timer.draw(v)
            if rnd >= 2: ts[v.scene].append(dt)
    s, b = m(ts["spheres"]), m(ts["robots"])
    print(f"{arg}: spheres {s:.2f} ms {calls['spheres']:.2f} calls; robots {b:.2f} ms {calls['robots']:.2f} calls; ratio {b/s:.3f}", flush=True)
