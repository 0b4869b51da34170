"""Sharp-mode corner and edge errors (cells) of seeded random rotated boxes at 32 cells.
Usage, from the repository root: python docs/notes/session4/sharp_corners.py SEED COUNT"""
import sys, numpy as np, sdfgl as sg
sys.path.insert(0, ".")  # run from the repository root
from tests.test_mesh import distance_to_mesh, closed
rng = np.random.default_rng(int(sys.argv[1]) if len(sys.argv) > 1 else 0)
N = int(sys.argv[2]) if len(sys.argv) > 2 else 24
worst = []
for k in range(N):
    half = rng.uniform(0.25, 0.55, 3); ang = rng.uniform(0, 180); ax = rng.normal(size=3); off = rng.uniform(-0.05, 0.05, 3)
    box = sg.box(tuple(2 * half)).rotate(float(ang), tuple(ax / np.linalg.norm(ax))).translate(tuple(off))
    m = sg.mesh(box, resolution=32, mode="sharp", colors=False)
    rot = box.children[0]
    signs = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T
    corners = signs * half
    t = np.linspace(0, 1, 7)[1:-1, None]
    edges = np.concatenate([corners[a] + t * (corners[b] - corners[a]) for a in range(8) for b in range(a + 1, 8) if np.sum(signs[a] != signs[b]) == 1])
    W = lambda p: p @ rot.m.T + off
    dc = distance_to_mesh(W(corners), m.vertices, m.faces) / m.step
    de = distance_to_mesh(W(edges), m.vertices, m.faces) / m.step
    worst.append((dc.max(), de.max()))
    print(k, 'corner max %.3f edge max %.3f closed %s' % (dc.max(), de.max(), closed(m)), flush=True)
w = np.array(worst); print('over 0.1: corners', (w[:, 0] > 0.1).sum(), 'edges', (w[:, 1] > 0.1).sum(), 'of', len(w), 'max', w.max(0))
