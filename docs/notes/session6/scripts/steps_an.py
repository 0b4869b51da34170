import numpy as np, sdfgl as sg
from sdfgl.bench_big import growth, NO_SHADING
size=(320,240)
for n in (16,1024):
    s, c = growth(n, 0)
    for m in ("enhanced","sphere"):
        a = sg.render(s, c, size, outputs=("color","depth","steps"), method=m, **NO_SHADING)
        hit=np.isfinite(a.depth)
        print(n, m, "all", a.steps.mean().round(2), "hits", hit.sum(), a.steps[hit].mean().round(2), np.percentile(a.steps[hit],[10,50,90]), "miss", a.steps[~hit].mean().round(2), "miss>0 frac", (a.steps[~hit]>0).mean().round(3), "mean", a.steps[(~hit)&(a.steps>0)].mean().round(2))
