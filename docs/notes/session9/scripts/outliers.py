"""Depth outliers (|depth - reference| > 0.5 fp) of one hard case for the sdfgl on PYTHONPATH, with
how deep the float64 field dips at the reference's hit. Usage: outliers.py CASE WxH"""
import sys, numpy as np
from sdfgl.hardcases import CASES
from sdfgl.reference import trace
from sdfgl.render import render
c = next(x for x in CASES if x.name == sys.argv[1]); W, H = map(int, sys.argv[2].split("x"))
s, cam = c.build()
ref = trace(s, cam, (W, H), max_dist=c.max_dist)
res = render(s, cam, (W, H), outputs=("color", "depth"), shadows=False, ao=False, max_dist=c.max_dist, **c.settings)
o, d = cam.rays(W, H)
fp = ref.pixel_angle * ref.t
both = np.isfinite(res.depth) & ref.hit & ~ref.undecided
err = np.where(both, np.abs(res.depth - np.where(ref.hit, ref.t, 0)) / np.where(both, fp, 1), 0)
for y, x in zip(*np.nonzero(err > 0.5)):
    t0 = ref.t[y, x]; ts = np.linspace(t0, t0 + 2 * fp[y, x], 2001)
    f = s.distance(o[y, x] + d[y, x] * ts[:, None])
    print(f"({x},{y}) ref {t0:.5f} render {res.depth[y, x]:.5f} off {err[y, x]:.1f} fp; dip {f.min() / fp[y, x]:.2e} fp, inside {(f < 0).mean() * 2:.3f} fp")
