"""1000 robots ('turned': each turned about a random axis): the free way (the nearest subtree by its
parts) against free_way=False and the float64 reference (every pixel; cached in /tmp); then the frame
against 1000 spheres, strictly alternating. Usage: entry_check.py [turned] [notime]"""
import os, sys
import numpy as np
from sdfgl.bench import FrameTimer, Variant
from pair import alternate
from sdfgl.bench_big import instances, spheres_like, turned_instances, NO_SHADING
from sdfgl.reference import trace_rays
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
which = "turned" if "turned" in sys.argv else "robots"
sp, ro = spheres_like(1000), (turned_instances if which == "turned" else instances)(1000)
cam = ro[1]
o, d = cam.rays(*size); o = o.reshape(-1, 3); d = d.reshape(-1, 3)
cache = f"/tmp/ref_{which}_1000_0.npz"  # robots: the same file as session 7's rcmp.py (9 minutes to make)
if not os.path.exists(cache):
    t, und = trace_rays(ro[0], o, d)
    np.savez(cache, t=t, und=und)
z = np.load(cache); t, und = z["t"], z["und"]
fp = 2 * np.tan(np.radians(cam.fov / 2)) / size[1]
for fw in (False, True):
    res = r.render(ro[0], cam, size, outputs=("color", "depth", "steps"), **NO_SHADING, free_way=fw)
    st = res.steps.astype(float); bm = st.reshape(60, 4, 80, 4).max(axis=(1, 3)).mean()
    dep = res.depth.ravel(); hit = np.isfinite(dep); ref = np.isfinite(t) & ~und; both = hit & ref
    err = np.abs(dep[both] - t[both]) / (fp * t[both])
    pts = o[hit] + d[hit] * dep[hit][:, None]
    f = np.abs(ro[0].distance(pts)) / (fp * dep[hit])
    print(f"free_way={fw}: calls {st.mean():.2f} blockmax {bm:.2f} hits {hit.sum()} false {(hit & ~np.isfinite(t) & ~und).sum()} "
          f"lost {(~hit & ref).sum()} off>0.5fp {(err > 0.5).sum()} p99 {np.percentile(err, 99):.4f} |f|>0.1fp {(f > 0.1).sum()}", flush=True)
if "notime" in sys.argv:
    sys.exit()
vs = [Variant("spheres", "1000", dict(NO_SHADING), *sp), Variant("robots", "1000", dict(NO_SHADING), *ro)]
ms = alternate(timer, vs, 32)
print(f"spheres {ms['spheres']:.2f} ms robots {ms['robots']:.2f} ms ratio {ms['robots'] / ms['spheres']:.3f}")
