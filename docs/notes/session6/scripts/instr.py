import dataclasses, sys, numpy as np, sdfgl as sg
import sdfgl.render
R = sys.modules["sdfgl.render"]
from sdfgl.bench_big import growth, NO_SHADING
orig = R.generate
OLD = """            if (over && abs(r) + rPrev < t - tPrev) {
                t = tPrev + rPrev;"""
def patched(*a, **k):
    src = orig(*a, **k)
    assert OLD in src.text
    return dataclasses.replace(src, text=src.text.replace(OLD, OLD.replace("t = tPrev + rPrev;", "t = tPrev + rPrev; steps += 1000;")))
R.generate = patched
for n in (16, 1024):
    s, c = growth(n, 0)
    res = sg.render(s, c, (320, 240), outputs=("color", "depth", "steps"), **NO_SHADING)
    st = res.steps
    back = st // 1000; calls = st % 1000
    print(n, "calls/px", calls.mean().round(2), "backtracks/px", back.mean().round(3), "frac of calls", (back.sum() / calls.sum()).round(3))
