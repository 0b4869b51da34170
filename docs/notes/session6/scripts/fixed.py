from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import growth, NO_SHADING
from sdfgl.render import Renderer
import sdfgl as sg
size = (320, 240)
r = Renderer(); timer = FrameTimer(r, size)
s16, c16 = growth(16, 0)
s1024, c = growth(1024, 0)
far = (sg.sphere(0.1).translate((0, 100, 0)) | sg.sphere(0.1).translate((1,101,0)))
vs = [Variant("g16", "-", dict(NO_SHADING), s16, c16), Variant("far", "-", dict(NO_SHADING), far, c16),
      Variant("g1024", "-", dict(NO_SHADING), s1024, c)]
time_interleaved(timer, vs, 7, 2, Progress(0, False))
for v in vs:
    print(v.scene, f"{v.result['frame_ms_median']:.2f} ms")
