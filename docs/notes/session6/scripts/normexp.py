import dataclasses
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
s16, c16 = growth(16, 0); s, c = growth(1024, 0)
OLD = """    for (int i = uZero; i < 6; i++) {
        float s = (i & 1) == 0 ? 1.0 : -1.0;
        vec3 e = vec3(0.0);
        e[i >> 1] = s * h;
        g[i >> 1] += s * NORMAL_FIELD(pos + e);
    }"""
NEW = """    for (int i = uZero; i < 4; i++) {
        vec3 e = 0.5773 * (2.0 * vec3((((i + 3) >> 1) & 1), ((i >> 1) & 1), (i & 1)) - 1.0);
        g += e * NORMAL_FIELD(pos + e * h);
    }"""
NONE = "    g = vec3(0.0, 1.0, 0.0);"
def rw(new):
    def f(src):
        assert OLD in src.text
        return dataclasses.replace(src, text=src.text.replace(OLD, new))
    return f
vs = [Variant("g16", "-", dict(NO_SHADING), s16, c16), Variant("g1024", "central6", dict(NO_SHADING), s, c),
      Variant("g1024", "tetra4", dict(NO_SHADING), s, c, source=rw(NEW)), Variant("g1024", "none", dict(NO_SHADING), s, c, source=rw(NONE))]
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.2f} ms ratio {v.result['frame_ms_median']/vs[0].result['frame_ms_median']:.2f}")
