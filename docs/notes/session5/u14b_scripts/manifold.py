# s14b manifold check (notes/s3/s14b_scripts/manifold.py) with MODES=mc,sharp env; run from the repo root
import sys, numpy as np, sdfgl as sg
sys.path.insert(0, ".")
from tests.nodes_zoo import all_nodes
from sdfgl.mesh.topology import edge_use
def vertex_manifold(F, nv):
    # each vertex's faces form one fan: count connected components of the link via shared edges
    import collections
    bad = 0
    # link edges: for face (a,b,c), at vertex a the link edge is (b,c)
    links = np.concatenate([F[:, [0, 1, 2]], F[:, [1, 2, 0]], F[:, [2, 0, 1]]])
    order = np.argsort(links[:, 0], kind="stable")
    links = links[order]
    starts = np.searchsorted(links[:, 0], np.arange(nv + 1))
    for v in range(nv):
        L = links[starts[v]:starts[v + 1], 1:]
        if len(L) == 0: continue
        nxt = dict(zip(L[:, 0], L[:, 1]))
        if len(nxt) != len(L): bad += 1; continue
        x = L[0, 0]; n = 0
        while True:
            x = nxt.get(x); n += 1
            if x is None or x == L[0, 0] or n > len(L): break
        if n != len(L) or x != L[0, 0]: bad += 1
    return bad
names = sys.argv[2:] or list(all_nodes())
res = int(sys.argv[1]); import os; MODES = os.environ.get("MODES", "mc,sharp").split(",")
zoo = all_nodes()
for name in names:
    node = zoo[name]
    lo, hi = node.bounds
    if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))): continue
    for mode in MODES:
        m = sg.mesh(node, resolution=res, mode=mode, colors=False)
        cnt, tw = edge_use(m.faces)
        nm = int(np.sum(cnt != 2))
        vb = vertex_manifold(m.faces, len(m.vertices))
        if nm or tw or vb:
            print(f"{name} {mode} res {res}: edges!=2 {nm} of {len(cnt)}, twice-directed {tw}, nonmanifold verts {vb}", flush=True)
print("done")
