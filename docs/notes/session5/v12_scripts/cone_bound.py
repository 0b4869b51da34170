"""Upper bound on what a conservative cone pre-pass could save on the growth scene.

Plain sphere tracing with the float64 twin along the centre ray of each BxB block (B = 4, 8);
a cone of the block's angular radius can advance while d >= cone radius (t * angle) and must
stop at the first sample where d < cone radius. The steps before that point are the most
the full-resolution ray could skip; steps after it it still takes.
Usage: python cone_bound.py N SEED B"""
import sys
import numpy as np
from sdfgl.bench_big import growth
n, seed, B = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
s, cam = growth(n, seed)
W, H = 320 // B, 240 // B
ro, rd = cam.rays(W, H)
ro = np.broadcast_to(ro, rd.shape).reshape(-1, 3); rd = rd.reshape(-1, 3)
ang = cam.pixel_angle(240) * B * 0.5 * np.sqrt(2)   # the block's angular radius
t = np.zeros(len(rd)); alive = np.ones(len(rd), bool); coned = np.ones(len(rd), bool)
before = np.zeros(len(rd)); total = np.zeros(len(rd))
for i in range(200):
    idx = np.nonzero(alive)[0]
    if not len(idx): break
    d = s.distance(ro[idx] + rd[idx] * t[idx, None])
    total[idx] += 1
    coned[idx] &= d >= t[idx] * ang
    before[idx[coned[idx]]] += 1
    t[idx] += d
    alive[idx] = (d > 1e-4 * np.maximum(t[idx], 1)) & (t[idx] < 40)
print(f"n {n} seed {seed} B {B}: plain steps/ray {total.mean():.2f}, of which before the cone stops {before.mean():.2f} "
      f"({before.sum() / total.sum():.0%}); rays in the grid box only: "
      f"{before[total > 3].mean():.2f} of {total[total > 3].mean():.2f}")
