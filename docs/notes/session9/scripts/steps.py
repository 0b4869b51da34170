"""Mean map() calls a pixel and depths for every hard case of the sdfgl on PYTHONPATH.
Usage: steps.py WxH out.npz   (defaults, no shadows/AO, each case's own max_dist and settings)"""
import sys, numpy as np
from sdfgl.hardcases import CASES
from sdfgl.render import render
W, H = map(int, sys.argv[1].split("x")); out = {}
for c in CASES:
    try:
        s, cam = c.build()
        res = render(s, cam, (W, H), outputs=("color", "depth", "steps"), shadows=False, ao=False,
                     max_dist=c.max_dist, **c.settings)
    except Exception as e:
        print("fails", c.name, repr(e)[:100], file=sys.stderr); continue
    out[c.name + ".steps"] = res.steps
    out[c.name + ".depth"] = np.where(np.isfinite(res.depth) & (res.depth >= 0), res.depth, np.inf)
    print(f"{c.name:22s} {res.steps.mean():8.3f}", flush=True)
np.savez_compressed(sys.argv[2], **out)
