"""Growth ratio 1024/16 per seed (320x240, no shading), interleaved; steps per pixel."""
import sys
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
import sdfgl as sg
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
r.render(sg.sphere(1), size=(8, 8))
vs = []
seeds = [int(x) for x in sys.argv[1:]] or [0, 1, 2]
for seed in seeds:
    for n in (16, 1024):
        s, c = growth(n, seed)
        vs.append(Variant(f"growth s{seed}", str(n), dict(NO_SHADING), s, c))
time_interleaved(timer, vs, 5, 2, Progress(0, False))
for i in range(0, len(vs), 2):
    a, b = vs[i], vs[i + 1]
    st = [float(r.render(v.node, v.camera, size, outputs=("color", "steps"), **v.settings).steps.mean()) for v in (a, b)]
    fa, fb = a.result['frame_ms_median'], b.result['frame_ms_median']
    print(f"{a.scene}: 16 {fa:.1f} ms, 1024 {fb:.1f} ms, ratio {fb/fa:.2f}; steps/px {st[0]:.2f} -> {st[1]:.2f}; link+first 1024 {1000*(b.result['compile_s']+b.result['first_frame_s']):.0f} ms", flush=True)
