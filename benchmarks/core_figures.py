"""Figures of the core pipeline: unit-sphere depth and silhouette against the closed form, and the
end-to-end time of an 800x600 AA 2 render, cold (with compile; Mesa shader cache off) and warm.

    python benchmarks/core_figures.py
"""
import os, time, numpy as np
os.environ["MESA_SHADER_CACHE_DISABLE"] = "true"
import sdfgl as sg
cam = sg.OrbitCamera(distance=4, yaw=0, pitch=0, fov=40)
for analytic in (False, True):
    r = sg.render(sg.sphere(1), cam, (65, 65), outputs=("color","depth","normal"), shadows=False, ao=False, analytic=analytic)
    o, d = cam.rays(65, 65)
    closest = np.linalg.norm(np.cross(d, -o), axis=-1)
    mis = (closest < 1) != np.isfinite(r.depth)
    print(f"analytic={analytic}: centre depth error {abs(float(r.depth[32,32]) - 3.0):.2e}; silhouette mismatch {mis.sum()} px of "
          f"{(closest<1).sum()} hit px; worst offset {np.abs(closest[mis]-1).max()/(3*cam.pixel_angle(65)) if mis.any() else 0:.3f} footprints")
s = (sg.sphere(1) & sg.box(1.5)) - (sg.cylinder(0.5, 4).orient(sg.X) | sg.cylinder(0.5, 4) | sg.cylinder(0.5, 4).orient(sg.Z))
c = sg.OrbitCamera(distance=5, yaw=30, pitch=20)
t0 = time.perf_counter(); r = sg.render(s, c, (800, 600), aa=2); t1 = time.perf_counter()
print(f"800x600 aa2 csg, cold (shader compile, Mesa cache off, includes EGL context): {t1-t0:.3f} s  timings {r.timings}")
ts = []
for _ in range(5):
    t0 = time.perf_counter(); r = sg.render(s, c, (800, 600), aa=2); ts.append(time.perf_counter() - t0)
print(f"800x600 aa2 csg, warm: median {np.median(ts):.3f} s (min {min(ts):.3f})")
