import numpy as np, sdfgl as sg
from sdfgl.bench_big import growth, NO_SHADING
for n in (16, 1024):
    s, c = growth(n, 0)
    for om in (0.3, 0.5, 0.7, 0.9, 1.0):
        res = sg.render(s, c, (320, 240), outputs=("color", "depth", "steps"), method="enhanced", omega=om, **NO_SHADING)
        st = res.steps
        print(n, om, "calls/px", st.mean().round(2), "8-lane max", st.reshape(240, 40, 8).max(-1).mean().round(2), "hits", np.isfinite(res.depth).sum())
