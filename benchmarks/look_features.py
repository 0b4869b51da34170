"""The benchmark's feature rows without AA (base, shadows, AO, lights, materials, alpha, fog)
on the demo scene at 400x300, interleaved: `python benchmarks/look_features.py`."""
import os
os.environ.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
from sdfgl.bench import FrameTimer, Progress, feature_table, feature_variants, time_interleaved
from sdfgl.render import Renderer
fv = [v for v in feature_variants() if not v.label.startswith(("aa", "all ("))]
time_interleaved(FrameTimer(Renderer(), (400, 300)), fv, 15, 2, Progress(0, False))
print(feature_table(fv))
