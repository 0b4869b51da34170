"""A sparse kind: n spheres (radius 0.1) on a shell of radius 4 plus two clusters; frame CPU ms and steps/px.
Usage: python shell.py N"""
import sys, time, statistics
import numpy as np
import sdfgl
from sdfgl.bench_big import NO_SHADING
from sdfgl.camera import OrbitCamera
from sdfgl.nodes import booleans, primitives
n = int(sys.argv[1]); rng = np.random.default_rng(0)
v = rng.normal(size=(n, 3)); v /= np.linalg.norm(v, axis=1)[:, None]; pts = 4 * v
pts[: n // 4] = rng.normal(size=(n // 4, 3)) * 0.4 + (1.5, 0, 0)
s = booleans.union(*[primitives.sphere(0.1).translate(p) for p in pts])
cam = OrbitCamera(target=(0, 0, 0), distance=12, yaw=20, pitch=15, fov=50)
r = sdfgl.render(s, cam, size=(320, 240), outputs=("color", "steps"), **NO_SHADING)
ts = []
for i in range(7):
    p = time.process_time(); sdfgl.render(s, cam, size=(320, 240), **NO_SHADING); ts.append(time.process_time() - p)
print(f"shell n {n}: steps/px {r.steps.mean():.2f} cpu {1e3*statistics.median(ts[2:]):.1f} ms")
