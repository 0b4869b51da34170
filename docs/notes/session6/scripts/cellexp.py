import dataclasses, numpy as np
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
s16, c16 = growth(16, 0); s, c = growth(1024, 0)
OLD = "    cap = max(g0_MARGIN - length(outside), boxDist);"
def rw(old, new):
    def f(src):
        assert old in src.text
        return dataclasses.replace(src, text=src.text.replace(old, new))
    return f
vs = [Variant("g16", "-", dict(NO_SHADING), s16, c16), Variant("g1024", "base", dict(NO_SHADING), s, c),
      Variant("g1024", "capconst", dict(NO_SHADING), s, c, source=rw(OLD, "    cap = g0_MARGIN;")),
      Variant("g1024", "no-sphere-alu", dict(NO_SHADING), s, c, source=rw("float v0 = sdSphere(q, d0.w);", "float v0 = q.x - d0.w;")),
      ]
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.2f} ms ratio {v.result['frame_ms_median']/vs[0].result['frame_ms_median']:.2f}")
