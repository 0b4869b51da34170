"""Code vs grid for n scattered spheres, boxes and tori (bench_model.scattered), 320x240, no shadows/AO."""
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_model import scattered
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
vs = []
for n in (16, 24, 32, 48, 64):
    s, c = scattered(n)
    for grid in (False, True):
        vs.append(Variant(f"n{n}", "grid" if grid else "code", dict(shadows=False, ao=False, grid=grid, grid_min=8), s, c))
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for i in range(0, len(vs), 2):
    a, b = vs[i], vs[i + 1]
    print(a.scene, f"code {a.result['frame_ms_median']:.2f} ms, grid {b.result['frame_ms_median']:.2f} ms, grid/code {b.result['frame_ms_median'] / a.result['frame_ms_median']:.2f}", flush=True)
