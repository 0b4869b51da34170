"""Zoo volume error (%) per kind, mode and resolution against the twin's integral (levels=3).
Usage (repo root): python zoo_vol.py MODE RES [kinds...]"""
import sys, time, numpy as np, sdfgl as sg
sys.path.insert(0, ".")
from tests.nodes_zoo import all_nodes
from tests.test_mesh import volume, closed, MC_OVER_1PC
from sdfgl.mesh.report import Twin
mode, res = sys.argv[1], (int(sys.argv[2]) if sys.argv[2] != 'default' else None)
kinds = sys.argv[3:] or sorted(MC_OVER_1PC)
nodes = all_nodes()
for k in kinds:
    node = nodes[k]
    t = time.time()
    m = sg.mesh(node, resolution=res, colors=False, mode=mode)  # res None: the default 2^22 samples
    tm = time.time() - t
    ref = Twin(node, m.lattice.box).integrate(48, levels=3)
    v = volume(m.vertices, m.faces)
    print(f"{k:24s} {mode:5s} {str(res):>7s} {100*(v-ref)/ref:+8.3f} %  closed {closed(m)}  cell {m.step:.4f}  {tm:.1f} s", flush=True)
