"""Median demo (or hard-case) frame of the sdfgl on sys.path: for A/B runs across trees.

    python tree.py [demo|CASE] [WxH] [frames]  -> prints "wall_ms cpu_ms" (medians)

Run it alternately for two trees (tree_ab.sh does A B A B ...); cwd must not hold
another sdfgl (run from /tmp). Demo settings are `sdfgl render --demo`'s.
"""
import statistics, sys, time
from sdfgl.bench import FrameTimer, Variant
from sdfgl.render import Renderer

scene = sys.argv[1] if len(sys.argv) > 1 else "demo"
size = tuple(int(x) for x in (sys.argv[2] if len(sys.argv) > 2 else "400x300").split("x"))
frames = int(sys.argv[3]) if len(sys.argv) > 3 else 15
if scene == "demo":
    from sdfgl.demo import demo_camera, demo_scene
    node, cam, st = demo_scene(), demo_camera(), dict(shadows="soft", ao=True, ground=True)
else:
    from sdfgl import hardcases
    c = {c.name: c for c in hardcases.CASES}[scene]
    node, cam = c.build()
    st = dict(shadows=False, ao=False, max_dist=c.max_dist, **c.settings)
timer = FrameTimer(Renderer(), size)
v = Variant(scene, "x", st, node, cam)
timer.prepare(v)
w, c = [], []
for i in range(3 + frames):
    c0 = time.process_time()
    dt = timer.draw(v)
    c1 = time.process_time()
    if i >= 3:
        w.append(dt)
        c.append(c1 - c0)
print(f"{1000 * statistics.median(w):.2f} {1000 * statistics.median(c):.2f}")
