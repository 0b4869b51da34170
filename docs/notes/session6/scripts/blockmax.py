import numpy as np, sdfgl as sg
from sdfgl.bench_big import growth, NO_SHADING
size=(320,240)
for n in (16,1024):
    s, c = growth(n, 0)
    for m in ("enhanced","sphere","relaxed"):
        a = sg.render(s, c, size, outputs=("color","depth","steps"), method=m, **NO_SHADING)
        st = a.steps.reshape(60,4,80,4).transpose(0,2,1,3).reshape(60,80,16)
        hit = np.isfinite(a.depth)
        print(n, m, "mean", a.steps.mean().round(2), "block-max mean", st.max(-1).mean().round(2), "2x2-max", a.steps.reshape(120,2,160,2).max(axis=(1,3)).mean().round(2), "8-lane rows max", a.steps.reshape(240,40,8).max(-1).mean().round(2))
