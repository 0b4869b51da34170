"""Steps per ray on the growth scene: mean for hits and misses, and how many rays enter the grid box.
Usage: python steps.py N SEED"""
import sys
import numpy as np
import sdfgl
from sdfgl.bench_big import growth, NO_SHADING
n, seed = int(sys.argv[1]), int(sys.argv[2])
r = sdfgl.render(*growth(n, seed), size=(320, 240), outputs=("color", "steps", "depth"), **NO_SHADING)
st, d = r.steps.astype(float), r.depth
hit = np.isfinite(d) & (d > 0) & (d < 1e5)
print(f"n {n} seed {seed}: steps/px {st.mean():.2f} hit {hit.mean():.3f} hits {st[hit].mean():.1f} (median {np.median(st[hit]):.0f}) "
      f"misses {st[~hit].mean():.2f}; pct of misses with steps>=4: {(st[~hit] >= 4).mean():.3f}")
for k in (1, 2, 3, 4, 6, 8, 12, 16, 24, 32):
    print(k, f"{(st[~hit] <= k).mean():.3f} {(st[hit] <= k).mean():.3f}", end=" | ")
print()
