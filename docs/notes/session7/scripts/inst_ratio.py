"""Frame of 1000 robot copies against 1000 spheres (the bench's group), interleaved."""
import sys
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
from sdfgl.render import Renderer
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
n = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
vs = [Variant("spheres", str(n), dict(NO_SHADING), *spheres_like(n)), Variant("robots", str(n), dict(NO_SHADING), *instances(n))]
time_interleaved(timer, vs, 9, 2, Progress(0, False))
base = vs[0].result['frame_ms_median']
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.1f} ms  ratio {v.result['frame_ms_median']/base:.2f}", flush=True)
