"""Held-out check: random scenes (tests/nodes_zoo.random_scene) meshed with default settings:
closed, and volume against the twin (levels 2). Usage: python random_vol.py SEED COUNT [mode]"""
import sys, time, numpy as np, sdfgl as sg
sys.path.insert(0, ".")
from tests.nodes_zoo import random_scene
from tests.test_mesh import closed
from sdfgl.mesh.geometry import volume
from sdfgl.mesh.report import Twin
rng = np.random.default_rng(int(sys.argv[1])); n = int(sys.argv[2]); mode = sys.argv[3] if len(sys.argv) > 3 else "mc"
for k in range(n):
    s = random_scene(rng)
    lo, hi = s.bounds
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
        print(k, "unbounded"); continue
    t = time.time(); m = sg.mesh(s, colors=False, mode=mode); tm = time.time() - t
    if len(m.faces) == 0:
        print(k, "empty"); continue
    ref = Twin(s, m.lattice.box).integrate(48, levels=2)
    e = 100 * (volume(m.vertices, m.faces) - ref) / ref
    print(k, f"{e:+.3f} %", closed(m), "refined %.2fx" % (m.default_step / m.step) if m.default_step else "", f"{tm:.2f} s", flush=True)
