"""Hits the current renderer loses that the pre-issue-10 renderer (18c68e5) found (within 2 footprints
of the reference depth: an early stop at a near miss is no found hit), per hard case,
against the float64 reference (its undecided rays left out). Usage: lost_vs_old.py WxH old.npz [case,case,...]"""
import sys, numpy as np
from sdfgl.hardcases import CASES
from sdfgl.reference import trace
from sdfgl.render import render
W, Hh = map(int, sys.argv[1].split('x')); old = np.load(sys.argv[2])
only = sys.argv[3].split(",") if len(sys.argv) > 3 else None
tot = 0
for c in CASES:
    if only and c.name not in only:
        continue
    s, cam = c.build()
    ref = trace(s, cam, (W, Hh), max_dist=c.max_dist)
    res = render(s, cam, (W, Hh), outputs=("color", "depth", "steps"), shadows=False, ao=False,
                 max_dist=c.max_dist, **c.settings)
    dec = ~ref.undecided; g = ref.hit & dec; new = np.isfinite(res.depth) & dec
    lost = g & ~new
    o = None
    if c.name in old.files:  # the old renderer found the hit: within 2 footprints of the reference's
        od = old[c.name]
        o = np.isfinite(od) & (np.abs(od - np.where(ref.hit, ref.t, 0)) <= 2 * ref.pixel_angle * np.where(ref.hit, ref.t, 0) + 2 * ref.pixel_size)
    lvo = int((lost & o).sum()) if o is not None else -1
    tot += max(lvo, 0)
    print(f"{c.name}: hits {int(g.sum())} lost {int(lost.sum())} lost-that-old-found {lvo} "
          f"old-lost {int((g & ~o).sum()) if o is not None else -1} false {int((new & ~ref.hit & dec).sum())} "
          f"undecided {int(ref.undecided.sum())} max steps {int(res.steps.max())}", flush=True)
print("total lost that the old renderer found:", tot)
