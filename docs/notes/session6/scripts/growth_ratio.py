import sys
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
import sdfgl as sg
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
vs = []
seed = int(sys.argv[1]) if len(sys.argv) > 1 else 0
for n in (16, 1024):
    s, c = growth(n, seed)
    for pp in ("x",):
        vs.append(Variant(f"g{n}", str(pp), dict(NO_SHADING), s, c))
time_interleaved(timer, vs, 7, 2, Progress(0, False))
base = vs[0].result['frame_ms_median']
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.1f} ms  ratio to g16 {v.result['frame_ms_median']/base:.2f}", flush=True)
