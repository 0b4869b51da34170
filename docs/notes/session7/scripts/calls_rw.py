"""Calls a pixel for the earlyout.py rewrites (generate patched)."""
import sys, numpy as np, sdfgl as sg
import sdfgl.render
R = sys.modules["sdfgl.render"]
sys.argv, kinds = sys.argv[:1], sys.argv[1:]
import importlib.util
spec = importlib.util.spec_from_file_location("eo", __file__.replace("calls_rw.py", "earlyout.py")); eo = importlib.util.module_from_spec(spec); spec.loader.exec_module(eo)
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
orig = R.generate
cur = {"k": None}
def patched(*a, **k):
    src = orig(*a, **k)
    return eo.rewrite(cur["k"])(src) if cur["k"] not in (None, 'spheres') else src
R.generate = patched
for k in [None, 'spheres'] + kinds:
    s, c = spheres_like(1000) if k == 'spheres' else instances(1000)
    cur["k"] = k
    res = sg.Renderer().render(s, c, (320, 240), outputs=("color", "depth", "steps"), **NO_SHADING)
    h = np.isfinite(res.depth)
    st = res.steps.reshape(60, 4, 80, 4).transpose(0, 2, 1, 3).reshape(60, 80, 16)
    print(k, "block4x4 max", st.max(-1).mean().round(2), "calls", res.steps.mean().round(2), "hits", h.sum(), "hit/miss", res.steps[h].mean().round(2), res.steps[~h].mean().round(2))
