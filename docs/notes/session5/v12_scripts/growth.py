"""Growth ratio 1024/16 (and steps/px, link + first frame at 1024) for the tree on sys.path.

Usage: python growth.py SEEDS [KIND]   e.g. `python growth.py 0,1,2,3,4`, KIND = growth | dense
(dense: radius 0.1 spheres in 6x2x6, a different density/size than the benchmark's kind).
Prints one line per (seed, n): wall and CPU ms per frame (median of 7 after 2 warm-ups),
steps/px, link and first-frame ms. Run A/B by alternating PYTHONPATH between trees.
"""
import statistics, sys, time
import numpy as np
import sdfgl
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.nodes import booleans, primitives
from sdfgl.camera import OrbitCamera
from sdfgl.render import Renderer

def dense(n, seed):
    rng = np.random.default_rng(seed)
    pts = rng.uniform((-3, -1, -3), (3, 1, 3), (n, 3))
    s = booleans.union(*[primitives.sphere(0.1).translate(p) for p in pts]) if n > 1 else primitives.sphere(0.1).translate(pts[0])
    return s, OrbitCamera(target=(0, 0, 0), distance=8, yaw=70, pitch=20, fov=50)

kind = sys.argv[2] if len(sys.argv) > 2 else "growth"
make = growth if kind == "growth" else dense
size = (320, 240)
r = Renderer()
r.render(sdfgl.sphere(1), size=(8, 8))
for seed in [int(x) for x in sys.argv[1].split(",")]:
    row = {}
    for n in (16, 1024):
        s, c = make(n, seed)
        t0 = time.perf_counter()
        r.render(s, c, size, **NO_SHADING)  # link + first frame (a new scene compiles)
        t2 = time.perf_counter()
        res = r.render(s, c, size, outputs=("color", "steps"), **NO_SHADING)
        walls, cpus = [], []
        for i in range(9):
            w, p = time.perf_counter(), time.process_time()
            r.render(s, c, size, **NO_SHADING)
            if i >= 2:
                walls.append(time.perf_counter() - w); cpus.append(time.process_time() - p)
        row[n] = (statistics.median(walls) * 1e3, statistics.median(cpus) * 1e3)
        print(f"{kind} seed {seed} n {n}: wall {row[n][0]:.1f} ms cpu {row[n][1]:.1f} ms steps/px {float(res.steps.mean()):.2f} "
              f"link+first {1e3*(t2-t0):.0f} ms", flush=True)
    print(f"{kind} seed {seed} ratio wall {row[1024][0]/row[16][0]:.2f} cpu {row[1024][1]/row[16][1]:.2f}", flush=True)
