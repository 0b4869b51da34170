"""Switch penalty? Robots/spheres pair: strict alternation vs blocks of consecutive draws."""
import statistics, sys
from sdfgl.bench import FrameTimer, Variant
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
vs = [Variant("spheres", "1000", dict(NO_SHADING), *spheres_like(1000)), Variant("robots", "1000", dict(NO_SHADING), *instances(1000))]
for v in vs: timer.prepare(v)
alt = {v.scene: [] for v in vs}; blk = {v.scene: [] for v in vs}; blk_first = {v.scene: [] for v in vs}
for rnd in range(int(sys.argv[1]) if len(sys.argv) > 1 else 6):
    for _ in range(5):
        for v in vs: alt[v.scene].append(timer.draw(v))
    for v in vs:
        ts = [timer.draw(v) for _ in range(6)]
        blk_first[v.scene].append(ts[0]); blk[v.scene].extend(ts[1:])
m = lambda x: 1000 * statistics.median(x)
print("alternating:", {k: round(m(x), 2) for k, x in alt.items()}, "ratio", round(m(alt['robots']) / m(alt['spheres']), 3))
print("blocks     :", {k: round(m(x), 2) for k, x in blk.items()}, "ratio", round(m(blk['robots']) / m(blk['spheres']), 3))
print("block first:", {k: round(m(x), 2) for k, x in blk_first.items()})
