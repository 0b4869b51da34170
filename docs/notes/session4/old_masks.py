"""Depths (inf: miss) of the pre-issue-10 renderer on every current hard case. Run with PYTHONPATH=<checkout of 18c68e5> (hardcases.py of main copied in as hardcases_new.py):"""
import sys, numpy as np
import sdfgl.hardcases_new as H
from sdfgl.render import render
W, Hh = map(int, sys.argv[1].split('x')); out = {}
for c in H.CASES:
    try:
        s, cam = c.build()
        opts = {"shadows": False, "ao": False, "max_dist": c.max_dist, **c.settings}
        res = render(s, cam, (W, Hh), outputs=("color", "depth"), **opts)
        out[c.name] = np.where(np.isfinite(res.depth) & (res.depth >= 0), res.depth, np.inf)
    except Exception as e:
        print("old renderer fails", c.name, repr(e)[:100], file=sys.stderr)
np.savez_compressed(sys.argv[2], **out)
