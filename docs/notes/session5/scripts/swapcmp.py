"""Depth/steps of hard cases under shader variants, against the first variant (same tree).

    PYTHONPATH=<tree> python swapcmp.py WxH case,case VARIANT VARIANT ...
VARIANT: `cur` or a folder of replacement .glsl files (any name under shaders/). Prints per
case the differing pixels, depth change, hit/miss flips, steps sums, 4x4 block-max steps.
"""
import sys, numpy as np
from pathlib import Path
from sdfgl import shaderlib
from sdfgl.hardcases import CASES
from sdfgl.render import render
orig = shaderlib.read.__wrapped__
def use(folder):
    def rd(name):
        f = Path(folder) / f"{name}.glsl" if folder != "cur" else None
        return f.read_text() if f is not None and f.is_file() else orig(name)
    shaderlib.read = rd
W, H = map(int, sys.argv[1].split('x'))
names = sys.argv[2].split(',')
outs = {}
for v in sys.argv[3:]:
    use(v)
    for c in CASES:
        if c.name not in names: continue
        scene, cam = c.build()
        res = render(scene, cam, (W, H), outputs=("color", "depth", "steps"), shadows=False, ao=False, max_dist=c.max_dist, **c.settings)
        outs[v, c.name] = (res.depth, res.steps)
for n in names:
    d0, s0 = outs[sys.argv[3], n]
    for v in sys.argv[4:]:
        d1, s1 = outs[v, n]
        diff = ~((d0 == d1) | (np.isnan(d0) & np.isnan(d1))) | (s0 != s1)
        print(n, v, int(diff.sum()), [(int(x), int(y), int(s0[y, x]), int(s1[y, x])) for y, x in zip(*np.nonzero(diff))][:6])
        fin = np.isfinite(d0) & np.isfinite(d1)
        dd = np.abs(d0 - d1)[fin & diff]
        print('   depth diff max', float(dd.max()) if dd.size else 0, 'rel', float((dd / d0[fin & diff]).max()) if dd.size else 0,
              'hit/miss flips', int((np.isfinite(d0) != np.isfinite(d1)).sum()), 'steps sum', int(s0.sum()), int(s1.sum()))
        def bm(s, B=4):
            h, w = s.shape
            return s[:h - h % B, :w - w % B].reshape(h // B, B, w // B, B).max(axis=(1, 3)).sum() * B * B / s.size
        print(f'   block-max4 {bm(s0):.3f} -> {bm(s1):.3f}   p99.9 {np.percentile(s0, 99.9):.0f} -> {np.percentile(s1, 99.9):.0f} max {s0.max()} -> {s1.max()}')
