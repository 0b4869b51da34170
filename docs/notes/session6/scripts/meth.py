from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
s16, c16 = growth(16, 0); s, c = growth(1024, 0)
vs = [Variant("g16", "-", dict(NO_SHADING), s16, c16)]
for m in ("enhanced", "sphere", "relaxed"):
    vs.append(Variant("g1024", m, dict(NO_SHADING, method=m), s, c))
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.2f} ms ratio {v.result['frame_ms_median']/vs[0].result['frame_ms_median']:.2f}")
