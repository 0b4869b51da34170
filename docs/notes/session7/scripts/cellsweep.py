"""Robots and spheres (1000) against CELL_FACTOR and MARGIN: frame (interleaved) and calls."""
import sys
import sdfgl.nodes.grid as G
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
combos = [tuple(map(float, a.split(","))) for a in sys.argv[1:]] or [(0.5, 0.5), (0.7, 0.5), (0.35, 0.5), (0.5, 0.35)]
vs = []
for cf, mg in combos:
    G.CELL_FACTOR, G.MARGIN = cf, mg
    for name, f in (("spheres", spheres_like), ("robots", instances)):
        s, c = f(1000)
        v = Variant(name, f"{cf},{mg}", dict(NO_SHADING), s, c)
        res = r.render(s, c, size, outputs=("color", "steps"), **NO_SHADING)
        v.result["calls"] = float(res.steps.mean())
        timer.prepare(v)  # compiles with this grid (the grid is built with the node)
        vs.append(v)
# time_interleaved prepares again: the grids are cached on the nodes, so the same programs
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for i in range(0, len(vs), 2):
    a, b = vs[i], vs[i + 1]
    print(a.label, f"spheres {a.result['frame_ms_median']:.1f} ms {a.result['calls']:.2f} calls; robots {b.result['frame_ms_median']:.1f} ms "
          f"{b.result['calls']:.2f} calls; ratio {b.result['frame_ms_median'] / a.result['frame_ms_median']:.2f}", flush=True)
