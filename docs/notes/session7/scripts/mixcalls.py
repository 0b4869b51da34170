import sys, numpy as np, sdfgl as sg
from sdfgl.bench_big import mixed, NO_SHADING
for n in (int(x) for x in sys.argv[1:]):
    s, c = mixed(n)
    out = {}
    for off in (True, False):
        out[off] = sg.Renderer().render(s, c, (320, 240), outputs=("color", "depth", "steps"), **NO_SHADING, free_way=not off)
    a, b = out[True], out[False]
    ha, hb = np.isfinite(a.depth), np.isfinite(b.depth)
    st = lambda r: r.steps.reshape(60, 4, 80, 4).transpose(0, 2, 1, 3).reshape(60, 80, 16).max(-1).mean().round(2)
    print("mixed", n, "RAY_FREE", "#define RAY_FREE" in b.source.text, "calls", a.steps.mean().round(2), "->", b.steps.mean().round(2), "block max", st(a), "->", st(b), "hit flips", (ha != hb).sum())
