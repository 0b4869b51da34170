"""1000 robots turned about random axes ('y': about Y only) and translated like the bench's copies:
calls and 4x4 block maxima with the free way and without, hits against free_way=False, then the
frame against 1000 spheres (the pair timed alone, strictly alternating). Usage: turned.py [y] [notime]"""
import sys
import numpy as np
import sdfgl as sg
from sdfgl.bench import FrameTimer, Variant
from pair import alternate
from sdfgl.bench_big import spheres_like, twenty_nodes, NO_SHADING
from sdfgl.camera import OrbitCamera
from sdfgl.render import Renderer
n = 1000
rng = np.random.default_rng(0)
ext = 1.0 * n ** (1 / 3)
robot = twenty_nodes()
axis = (lambda: (0.0, 1.0, 0.0)) if "y" in sys.argv else (lambda: tuple(rng.normal(size=3)))
scene = sg.union(*[robot.rotate(float(rng.uniform(0, 360)), axis()).translate(tuple(rng.uniform(-ext, ext, 3)))
                   for _ in range(n)])
cam = OrbitCamera(distance=3.2 * ext, yaw=30, pitch=25)
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
out = {}
for fw in (False, True):
    res = r.render(scene, cam, size, outputs=("color", "depth", "steps"), **NO_SHADING, free_way=fw)
    st = res.steps.astype(float)
    out[fw] = res
    print(f"free_way={fw}: calls {st.mean():.2f} blockmax {st.reshape(60, 4, 80, 4).max(axis=(1, 3)).mean():.2f} "
          f"hits {np.isfinite(res.depth).sum()} refined {'enterNear' in res.source.text}", flush=True)
a, b = out[False].depth, out[True].depth
both = np.isfinite(a) & np.isfinite(b)
print("hit mismatch", int((np.isfinite(a) != np.isfinite(b)).sum()), "depth diff p99", float(np.percentile(np.abs(a[both] - b[both]), 99)),
      "pixels off > 0.01", int((np.abs(a[both] - b[both]) > 0.01).sum()))
if "notime" in sys.argv:
    sys.exit()
vs = [Variant("spheres", "1000", dict(NO_SHADING), *spheres_like(n)), Variant("turned", "1000", dict(NO_SHADING), scene, cam)]
ms = alternate(timer, vs, 27)
print(f"spheres {ms['spheres']:.2f} ms turned {ms['turned']:.2f} ms ratio {ms['turned'] / ms['spheres']:.3f}")
