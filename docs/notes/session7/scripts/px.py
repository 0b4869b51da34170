import sys, numpy as np
from sdfgl.bench_big import instances
s, c = instances(1000, 0)
o, d = c.rays(320, 240); o = o.reshape(-1, 3); d = d.reshape(-1, 3)
k = int(sys.argv[1]); t0 = float(sys.argv[2]); w = float(sys.argv[3])
ts = np.linspace(t0 - w, t0 + w, 20001)
f = s.distance(o[k] + d[k] * ts[:, None])
fp = 2 * np.tan(np.radians(c.fov / 2)) / 240 * t0
i = f.argmin()
print("min f", f.min(), "at", ts[i], "in fp", f.min() / fp, "fp", fp)
neg = ts[f < 0]
print("first t with f<0", neg[:1], "count", (f < 0).sum())
