"""Free way on/off on a scene: calls, and every decided pixel against the float64 reference."""
import sys, time, numpy as np, sdfgl as sg
from sdfgl.bench_big import instances, spheres_like, growth, mixed, NO_SHADING
from sdfgl.reference import trace_rays
which = sys.argv[1] if len(sys.argv) > 1 else "robots"
n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 0
W, H = 320, 240
s, c = {"robots": instances, "spheres": spheres_like, "growth": growth, "mixed": mixed}[which](n, seed)
out = {}
for off in (False, True):
    out[off] = sg.Renderer().render(s, c, (W, H), outputs=("color", "depth", "steps"), **NO_SHADING, free_way=not off)
a, b = out[True], out[False]
print(which, n, seed, "RAY_FREE", "#define RAY_FREE" in b.source.text, "steps", a.steps.mean().round(2), "->", b.steps.mean().round(2))
o, d = c.rays(W, H)
o = o.reshape(-1, 3); d = d.reshape(-1, 3)
import os
cache = f"/tmp/ref_{which}_{n}_{seed}.npz"
t0 = time.time()
if os.path.exists(cache):
    z = np.load(cache); t, und = z["t"], z["und"]
else:
    t, und = trace_rays(s, o, d)
    np.savez(cache, t=t, und=und)
print("reference", round(time.time() - t0, 1), "s; undecided", und.sum())
fp = 2 * np.tan(np.radians(c.fov / 2)) / H
for name, r in (("plain", a), ("free", b)):
    dep = r.depth.ravel()
    hit = np.isfinite(dep); ref = np.isfinite(t) & ~und
    dec = ~und
    both = hit & ref
    err = np.abs(dep[both] - t[both]) / (fp * t[both])
    false_hit = hit & ~np.isfinite(t) & dec
    lost = ~hit & ref
    # a hit whose point is off the surface in float64
    pts = o[hit] + d[hit] * dep[hit][:, None]
    f = np.abs(s.distance(pts)) / (fp * dep[hit])
    print(f"{name}: hits {hit.sum()} false {false_hit.sum()} lost {lost.sum()} off>0.5fp {(err > 0.5).sum()} "
          f"p99 {np.percentile(err, 99):.4f} max {err.max():.2f}  |f|>0.1fp {(f > 0.1).sum()}")
    bad = np.flatnonzero(both)[err > 0.5]
    for k in bad[:8]:
        print("   px", k, "ref", round(float(t[k]), 3), "got", round(float(dep[k]), 3))
    for k in np.flatnonzero(false_hit)[:5]:
        print("   false px", k, "got", round(float(dep[k]), 3))
