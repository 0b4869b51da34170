import dataclasses, sys, numpy as np, sdfgl as sg
import sdfgl.render
R = sys.modules["sdfgl.render"]
from sdfgl.bench_big import growth, mixed, NO_SHADING
orig = R.generate
state = {"off": False}
def patched(*a, **k):
    src = orig(*a, **k)
    if state["off"]:
        return dataclasses.replace(src, text=src.text.replace("#define RAY_FREE\n", ""))
    return src
R.generate = patched
for name, (s, c) in [("growth1024 s0", growth(1024, 0)), ("growth1024 s2", growth(1024, 2)), ("growth256", growth(256, 1)),
                     ("spheres_like", __import__("sdfgl.bench_big", fromlist=["x"]).spheres_like(1000, 0)), ("mixed", mixed(5000, 0))]:
    out = {}
    for off in (False, True):
        state["off"] = off
        r = sg.Renderer()
        res = r.render(s, c, (320, 240), outputs=("color", "depth", "normal", "steps"), **NO_SHADING)
        out[off] = res
    a, b = out[True], out[False]   # a: without, b: with
    ha, hb = np.isfinite(a.depth), np.isfinite(b.depth)
    both = ha & hb
    dd = np.abs(a.depth[both] - b.depth[both])
    fp = 2 * np.tan(np.radians(c.fov / 2)) / 240 * a.depth[both]
    print(name, "RAY_FREE in src:", "RAY_FREE" in b.source.text, "hits", ha.sum(), hb.sum(), "flips", (ha != hb).sum(),
          "max |dt| fp", (dd / fp).max().round(4) if both.any() else 0, "steps", a.steps.mean().round(2), "->", b.steps.mean().round(2),
          "colour diff px", (np.abs(a.color.astype(int) - b.color.astype(int)).max(-1) > 2).sum())

from sdfgl.reference import trace_rays
print("--- against the float64 reference on the pixels that differ by > 0.5 fp")
for name, (s, c) in [("growth1024 s2", growth(1024, 2)), ("spheres_like", __import__("sdfgl.bench_big", fromlist=["x"]).spheres_like(1000, 0)), ("mixed", mixed(5000, 0))]:
    out = {}
    for off in (False, True):
        state["off"] = off
        out[off] = sg.Renderer().render(s, c, (320, 240), outputs=("color", "depth"), **NO_SHADING)
    a, b = out[True], out[False]
    o, d = c.rays(320, 240)
    fp = 2 * np.tan(np.radians(c.fov / 2)) / 240
    both = np.isfinite(a.depth) & np.isfinite(b.depth)
    diff = both & (np.abs(a.depth - b.depth) > 0.5 * fp * np.where(both, a.depth, 0))
    idx = np.flatnonzero(diff.ravel())
    t, und = trace_rays(s, o.reshape(-1, 3)[idx], d.reshape(-1, 3)[idx])
    ea = np.abs(a.depth.ravel()[idx] - t) / (fp * t); eb = np.abs(b.depth.ravel()[idx] - t) / (fp * t)
    print(name, len(idx), "pixels; error in fp without RAY_FREE: max", ea.max().round(3) if len(idx) else 0, " with:", eb.max().round(3) if len(idx) else 0, "undecided", und.sum())
    for k in range(len(idx)):
        print("   px", idx[k], "ref t", round(float(t[k]), 4), "without", round(float(a.depth.ravel()[idx[k]]), 4), "with", round(float(b.depth.ravel()[idx[k]]), 4))
