"""Sharp-mode corner/edge error (cells) over seeded random boxes and box-minus-box CSG corners.

usage: corners.py [N_BOXES=60] [RES=32] [SEED=0]   -> one line per failing case, summary line."""
import sys, time
import numpy as np
import sdfgl as sg
from sdfgl.mesh.geometry import distance_to_mesh
from sdfgl.mesh.topology import edge_use

SIGNS = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T


def features(half):
    c = SIGNS * half
    t = np.linspace(0, 1, 9)[1:-1, None]
    e = np.concatenate([c[a] + t * (c[b] - c[a]) for a in range(8) for b in range(a + 1, 8)
                        if np.sum(SIGNS[a] != SIGNS[b]) == 1])
    return c, e


def random_box(rng):
    half = np.array([0.5, 0.4, 0.3]) * rng.uniform(0.8, 1.2, 3)
    ang, ax, off = rng.uniform(0, 90), rng.normal(size=3), rng.uniform(-0.05, 0.05, 3)
    s = sg.box(tuple(2 * half)).rotate(ang, tuple(ax)).translate(tuple(off))
    R = s.children[0].m
    c, e = features(half)
    w = lambda p: p @ R.T + off  # noqa: E731
    return s, w(c), w(e)


def csg_case(rng):
    """Box minus a smaller box that sticks out of one corner: the concave corner where three cut
    faces meet, and the cut edges inside the big box (both boxes share a random rotation)."""
    big = np.array([0.5, 0.4, 0.3])
    cut_c = big * rng.uniform(0.3, 0.7, 3)            # concave corner inside the big box (local)
    cut_half = big                                    # extends past the big box's + corner
    centre = cut_c + cut_half
    ang, ax, off = rng.uniform(0, 90), rng.normal(size=3), rng.uniform(-0.05, 0.05, 3)
    s = (sg.box(tuple(2 * big)) - sg.box(tuple(2 * cut_half)).translate(tuple(centre))).rotate(ang, tuple(ax)).translate(tuple(off))
    R = s.children[0].m
    t = np.linspace(0, 1, 9)[1:-1, None]
    ends = [np.array([big[0], cut_c[1], cut_c[2]]), np.array([cut_c[0], big[1], cut_c[2]]), np.array([cut_c[0], cut_c[1], big[2]])]
    e = np.concatenate([cut_c + t * (q - cut_c) for q in ends])
    w = lambda p: p @ R.T + off  # noqa: E731
    return s, w(cut_c[None]), w(e)


def measure(s, c, e, res):
    m = sg.mesh(s, resolution=res, mode="sharp", colors=False)
    dc = distance_to_mesh(c, m.vertices, m.faces) / m.step
    de = distance_to_mesh(e, m.vertices, m.faces) / m.step
    cnt, tw = edge_use(m.faces)
    return dc.max(), de.max(), bool(np.all(cnt == 2) and tw == 0)


if __name__ == "__main__":
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 60
    res = int(sys.argv[2]) if len(sys.argv) > 2 else 32
    rng = np.random.default_rng(int(sys.argv[3]) if len(sys.argv) > 3 else 0)
    t0 = time.process_time()
    rows = []
    for k in range(n + 6):
        kind = "box" if k < n else "csg"
        s, c, e = random_box(rng) if k < n else csg_case(rng)
        dc, de, ok = measure(s, c, e, res)
        rows.append((kind, k, dc, de, ok))
        if dc > 0.1 or de > 0.1 or not ok:
            print(f"FAIL {kind} {k}: corner {dc:.3f} edge {de:.3f} closed {ok}", flush=True)
    b = [r for r in rows if r[0] == "box"]
    x = [r for r in rows if r[0] == "csg"]
    for name, rr in (("boxes", b), ("csg", x)):
        print(f"{name} {len(rr)}: corner max {max(r[2] for r in rr):.3f} (>0.1: {sum(r[2] > 0.1 for r in rr)}) "
              f"edge max {max(r[3] for r in rr):.3f} (>0.1: {sum(r[3] > 0.1 for r in rr)}) "
              f"not closed {sum(not r[4] for r in rr)}")
    print(f"cpu {time.process_time() - t0:.1f} s")
