import sys
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING, mixed
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
seed = int(sys.argv[1])
s16, c16 = growth(16, seed)
vs = [Variant("g16", "-", dict(NO_SHADING), s16, c16)]
for label in ("box", "ball"):
    s, c = (growth(1024, seed) if len(sys.argv) < 3 else mixed(5000, seed))
    g = s.grid
    if label == "box":
        g._ball_at = None
    vs.append(Variant("g1024", label, dict(NO_SHADING), s, c))
time_interleaved(timer, vs, 9, 2, Progress(0, False))
for v in vs:
    print(seed, v.scene, v.label, f"{v.result['frame_ms_median']:.2f} ms ratio {v.result['frame_ms_median']/vs[0].result['frame_ms_median']:.2f}", flush=True)
