"""Calls a pixel spent settling (steps counted only in settle rounds), hits and misses."""
import dataclasses, sys, numpy as np, sdfgl as sg
import sdfgl.render
R = sys.modules["sdfgl.render"]
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
orig = R.generate
mode = {"m": None}
def patched(*a, **k):
    src = orig(*a, **k)
    t = src.text
    if mode["m"] == "settle":
        assert "        steps++;\n" in t
        t = t.replace("        steps++;\n", "        if (settling != 0) steps++;\n", 1)
    return dataclasses.replace(src, text=t)
R.generate = patched
for f in (spheres_like, instances):
    s, c = f(1000)
    out = {}
    for m in (None, "settle"):
        mode["m"] = m
        out[m] = sg.Renderer().render(s, c, (320, 240), outputs=("color", "depth", "steps"), **NO_SHADING)
    h = np.isfinite(out[None].depth)
    a, b = out[None].steps, out["settle"].steps
    print(f.__name__, "all calls hit/miss", a[h].mean().round(2), a[~h].mean().round(2), " settle calls hit/miss", b[h].mean().round(2), b[~h].mean().round(2))
