"""Mesh volume error estimated from the field at face centroids (area x f) against the twin's volume.
Usage (repo root): python deficit.py MODE RES|default kinds..."""
import sys, time, numpy as np, sdfgl as sg
sys.path.insert(0, ".")
from tests.nodes_zoo import all_nodes
from tests.test_mesh import volume
from sdfgl.mesh.sample import GPUField
from sdfgl.mesh.report import Twin
nodes = all_nodes()
mode, res = sys.argv[1], (None if sys.argv[2] == "default" else int(sys.argv[2]))
for k in sys.argv[3:]:
    node = nodes[k]
    m = sg.mesh(node, resolution=res, colors=False, mode=mode)
    h = m.step
    field = GPUField(node, *m.lattice.box)
    v = m.vertices[m.faces]
    c = v.mean(1)
    a = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    f, g, _ = field.gradient_bend(c, 0.05 * h); f = f / np.maximum(np.linalg.norm(g, axis=1), 1e-30)
    # mid-edge samples: exact mean of a quadratic over the triangle
    mids = np.concatenate([(v[:, 0] + v[:, 1]) / 2, (v[:, 1] + v[:, 2]) / 2, (v[:, 2] + v[:, 0]) / 2])
    fm, gm, _ = field.gradient_bend(mids, 0.05 * h); fm = fm / np.maximum(np.linalg.norm(gm, axis=1), 1e-30)
    fm = fm.reshape(3, -1).mean(0)
    vol = volume(m.vertices, m.faces)
    ref = Twin(node, m.lattice.box).integrate(48, levels=3)
    print(f"{k:22s} {mode} {res} actual {100*(vol-ref)/ref:+7.3f} %  est(centroid) {100*np.sum(a*f)/vol:+7.3f} %  est(mid-edges) {100*np.sum(a*fm)/vol:+7.3f} %  abs {100*np.sum(a*np.abs(fm))/vol:7.3f} %", flush=True)
