import sys, dataclasses
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
def rw(old, new):
    def f(src):
        assert old in src.text, old
        return dataclasses.replace(src, text=src.text.replace(old, new))
    return f
s16, c16 = growth(16, 0)
s, c = growth(1024, 0)
exps = {
 "base": None,
 "no-list-fetch": rw("vec4 d0 = dataFetch(e + 0);", "vec4 d0 = vec4(float(e & 7), float(e & 3), 0.0, 0.15);"),
 "no-cell-fetch": rw("vec4 s0 = dataFetch(g0_CELLS + cell + 0);", "vec4 s0 = vec4(float(cell & 1023), 3.0, 0.0, 0.0);"),
 "double-list-fetch": rw("vec4 d0 = dataFetch(e + 0);", "vec4 d0 = dataFetch(e + 0) + 1e-30 * dataFetch(e + 1);"),
}
vs = [Variant("g16", "base", dict(NO_SHADING), s16, c16)]
for k, f in exps.items():
    vs.append(Variant("g1024", k, dict(NO_SHADING), s, c, source=f))
time_interleaved(timer, vs, 7, 2, Progress(0, False))
base = vs[0].result['frame_ms_median']
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.2f} ms  ratio {v.result['frame_ms_median']/base:.2f}", flush=True)
