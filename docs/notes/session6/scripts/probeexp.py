import dataclasses, numpy as np
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
s16, c16 = growth(16, 0); s, c = growth(1024, 0)
OLD = "bool shallow = !inside && !near && s > 1e-3 && s < 0.5 && ++sinceProbe >= 4;"
def rw(new):
    def f(src):
        assert OLD in src.text
        return dataclasses.replace(src, text=src.text.replace(OLD, new))
    return f
vs = [Variant("g16", "-", dict(NO_SHADING), s16, c16), Variant("g1024", "probe4", dict(NO_SHADING), s, c),
      Variant("g1024", "noprobe", dict(NO_SHADING), s, c, source=rw("bool shallow = false;")),
      Variant("g1024", "probe8", dict(NO_SHADING), s, c, source=rw(OLD.replace(">= 4", ">= 8")))]
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.2f} ms ratio {v.result['frame_ms_median']/vs[0].result['frame_ms_median']:.2f}")
