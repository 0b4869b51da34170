"""Every bounded zoo kind meshed with default settings (auto refinement): volume error vs the twin
(levels 2), step refinement, time. Usage (repo root): python zoo_default.py MODE [kinds...]"""
import sys, time, numpy as np, sdfgl as sg
sys.path.insert(0, ".")
from tests.nodes_zoo import all_nodes
from tests.test_mesh import volume, closed, _zoo
from sdfgl.mesh.report import Twin
mode = sys.argv[1]
nodes = all_nodes()
kinds = sys.argv[2:] or [p.id for p in _zoo()]
bad = []
for k in kinds:
    node = nodes[k]
    t = time.time()
    m = sg.mesh(node, colors=False, mode=mode)
    tm = time.time() - t
    ref = Twin(node, m.lattice.box).integrate(48, levels=int(__import__("os").environ.get("LEVELS", "2")))
    e = 100 * (volume(m.vertices, m.faces) - ref) / ref
    if abs(e) > 1: bad.append(k)
    ref_s = "" if m.default_step is None else f"refined {m.default_step / m.step:.2f}x"
    print(f"{k:24s} {mode:5s} {e:+8.3f} %  closed {closed(m)}  cell {m.step:.4f} {ref_s:14s} {tm:.2f} s", flush=True)
print("over 1 %:", bad)
