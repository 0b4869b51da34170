"""Session 8's turned-robots reference (/tmp/ref_turned_1000_0.npz, made by
docs/notes/session8/scripts/entry_check.py turned) with the new graze rule applied to its hits,
then the free way's figures against it. Usage: turned_regraze.py"""
import numpy as np
from sdfgl.bench_big import turned_instances, NO_SHADING
from sdfgl.codegen import scene_frame
from sdfgl import reference as R
from sdfgl.render import Renderer
size = (320, 240)
scene, cam = turned_instances(1000)
o, d = cam.rays(*size); o = o.reshape(-1, 3); d = d.reshape(-1, 3)
z = np.load("/tmp/ref_turned_1000_0.npz"); t, und = z["t"], z["und"]
lo, hi, scale = scene_frame(scene)
reach = np.linalg.norm(o - 0.5 * (lo + hi), axis=-1)
lip = scene.lipschitz
und2 = und | R._shallow(scene, o, d, t, R.ROUNDING * max(lip, 1.0) * (reach + t), lip, 1e-7 * scale)
print("undecided", int(und.sum()), "->", int(und2.sum()), flush=True)
fp = 2 * np.tan(np.radians(cam.fov / 2)) / size[1]
r = Renderer()
for fw in (False, True):
    res = r.render(scene, cam, size, outputs=("color", "depth", "steps"), **NO_SHADING, free_way=fw)
    dep = res.depth.ravel(); hit = np.isfinite(dep); ref = np.isfinite(t) & ~und2; both = hit & ref
    err = np.abs(dep[both] - t[both]) / (fp * t[both])
    print(f"free_way={fw}: hits {hit.sum()} false {(hit & ~np.isfinite(t) & ~und2).sum()} lost {(~hit & ref).sum()} "
          f"off>0.5fp {(err > 0.5).sum()} p99 {np.percentile(err, 99):.4f}", flush=True)
