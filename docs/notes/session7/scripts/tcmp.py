"""The test scene (translated robots, boxes, capsules, spheres) at 96x72: free vs plain vs reference."""
import sys, time, numpy as np, sdfgl as sg
from sdfgl.bench_big import twenty_nodes
from sdfgl.reference import trace_rays
def translated(n, seed):
    rng = np.random.default_rng(seed)
    robot = twenty_nodes()
    kinds = (lambda: robot, lambda: sg.box(tuple(rng.uniform(0.02, 0.5, 3))),
             lambda: sg.capsule((-0.2, 0, 0), (0.2, 0.1, 0), float(rng.uniform(0.01, 0.06))), lambda: sg.sphere(float(rng.choice([0.01, 0.1, 0.3]))))
    return sg.union(*[kinds[i % 4]().translate(tuple(rng.uniform((-2, -0.6, -2), (2, 0.6, 2)))) for i in range(n)])
n, seed = int(sys.argv[1]), int(sys.argv[2])
W, H = (int(x) for x in (sys.argv[3] if len(sys.argv) > 3 else "96x72").split("x"))
scene = translated(n, seed)
cam = sg.OrbitCamera(distance=5.5, yaw=80, pitch=30, fov=45)
out = {}
for off in (False, True):
    out[off] = sg.Renderer().render(scene, cam, (W, H), shadows=False, ao=False, outputs=("color", "depth", "steps"), free_way=not off)
print("RAY_FREE", "#define RAY_FREE" in out[False].source.text, "steps", out[True].steps.mean().round(2), "->", out[False].steps.mean().round(2))
o, d = cam.rays(W, H)
t0 = time.time()
t, und = trace_rays(scene, o.reshape(-1, 3), d.reshape(-1, 3))
print("ref s", round(time.time() - t0, 1), "undecided", und.sum())
t, und = t.reshape(H, W), und.reshape(H, W)
fp = cam.pixel_angle(H) * np.where(np.isfinite(t), t, 1.0)
for name, r in (("plain", out[True]), ("free", out[False])):
    hit = np.isfinite(r.depth); ref = np.isfinite(t); sure = ~und
    both = hit & ref & sure
    err = np.abs(r.depth[both] - t[both]) / fp[both]
    flips = np.flatnonzero((hit != ref) & sure)
    print(f"{name}: hits {hit.sum()} flips {len(flips)} off>0.5 {(err > 0.5).sum()} p99 {np.percentile(err, 99):.4f} max {err.max():.2f}")
    for k in flips[:5]:
        print("   flip", np.unravel_index(k, (H, W)), "ref", t.ravel()[k], "got", r.depth.ravel()[k])
