import sys, itertools
import sdfgl.nodes.grid as G
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
import sdfgl as sg
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
seed = int(sys.argv[1])
combos = [(0.5, 0.5), (0.4, 0.5), (0.45, 0.5), (0.4, 0.6)]
vs = []
s16, c16 = growth(16, seed)
vs.append(Variant("g16", "-", dict(NO_SHADING), s16, c16))
for cf, mg in combos:
    G.CELL_FACTOR, G.MARGIN = cf, mg
    s, c = growth(1024, seed)
    sg.compile(s, **NO_SHADING)  # builds the grid with these constants
    v = Variant("g1024", f"cf{cf} m{mg}", dict(NO_SHADING), s, c)
    timer.prepare(v)  # compile now, under these constants
    vs.append(v)
    res = sg.render(s, c, size, outputs=("color", "steps"), **NO_SHADING)
    v.result["steps"] = float(res.steps.mean())
    v.result["dims"] = tuple(s.grid.dims)
time_interleaved(timer, vs, 7, 2, Progress(0, False))
b = vs[0].result['frame_ms_median']
for v in vs:
    print(v.label, f"{v.result['frame_ms_median']:.2f} ms ratio {v.result['frame_ms_median']/b:.2f} steps {v.result.get('steps', 0):.2f} dims {v.result.get('dims')}", flush=True)
