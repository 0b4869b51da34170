"""Frame with and without the free way (free_way=False), interleaved: mixed 5000 rotated, robots, growth."""
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import mixed, instances, growth, NO_SHADING
from sdfgl.render import Renderer
r = Renderer(); timer = FrameTimer(r, (320, 240))
vs = []
for name, (s, c) in (("mixed5000", mixed(5000)), ("robots1000", instances(1000)), ("growth1024", growth(1024))):
    vs += [Variant(name, "free", dict(NO_SHADING), s, c), Variant(name, "plain", {**NO_SHADING, "free_way": False}, s, c)]
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for v in vs:
    print(v.scene, v.label, f"{v.result['frame_ms_median']:.1f} ms")
