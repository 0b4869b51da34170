"""Calls a pixel with the free way on/off for grid scenes on a floor."""
import numpy as np, sdfgl as sg
from sdfgl.bench_big import growth, instances, NO_SHADING
for name, (s, c) in (("growth 1024 on a plane", growth(1024)), ("1000 robots on a box floor", instances(1000))):
    s = s | (sg.plane((0, 1, 0), (0, -1.2, 0)) if "plane" in name else sg.box((25, 0.2, 25)).translate((0, -11, 0)))
    out = {}
    for off in (True, False):
        out[off] = sg.Renderer().render(s, c, (320, 240), outputs=("color", "depth", "steps"), **NO_SHADING, free_way=not off)
    a, b = out[True], out[False]
    ha, hb = np.isfinite(a.depth), np.isfinite(b.depth)
    print(name, "RAY_FREE", "#define RAY_FREE" in b.source.text, "calls", a.steps.mean().round(2), "->", b.steps.mean().round(2), "hit flips", (ha != hb).sum())
