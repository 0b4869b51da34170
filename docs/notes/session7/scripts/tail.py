"""Where the costly pixels of 1000 robots spend their calls: marching rounds near a surface,
marching rounds far, settle calls (separate renders with steps++ moved)."""
import dataclasses, sys, numpy as np, sdfgl as sg
import sdfgl.render
R = sys.modules["sdfgl.render"]
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
orig = R.generate
mode = {"m": None}
def patched(*a, **k):
    src = orig(*a, **k)
    t = src.text
    if mode["m"] == "settle":
        t = t.replace("        steps++;\n", "        if (settling != 0) steps++;\n", 1)
    elif mode["m"] == "near":
        t = t.replace("        steps++;\n", "        if (settling == 0 && r >= 0.0 && r < hitEpsilon(c)) steps++;\n", 1)
    elif mode["m"] == "probe3":
        t = t.replace("        steps++;\n", "        if (settling == 3) steps++;\n", 1)
    elif mode["m"] == "probe2":
        t = t.replace("        steps++;\n", "        if (settling == 2) steps++;\n", 1)
    elif mode["m"] == "backtrack":
        t = t.replace("        steps++;\n", "", 1)
        assert "t = tPrev + rPrev;  // back to where a plain step stands" in t
        t = t.replace("t = tPrev + rPrev;  // back to where a plain step stands", "steps++; t = tPrev + rPrev;", 1)
    elif mode["m"] == "proven":
        t = t.replace("        steps++;\n", "", 1)
        t = t.replace("        if (proven) next = free - hitEpsilon(t);", "        if (proven) { next = free - hitEpsilon(t); steps++; }", 1)
    return dataclasses.replace(src, text=t)
R.generate = patched
which = sys.argv[1] if len(sys.argv) > 1 else "robots"
s, c = (instances if which == "robots" else spheres_like)(1000)
out = {}
for m in (None, "settle", "near", "probe2", "backtrack", "proven"):
    mode["m"] = m
    out[m] = sg.Renderer().render(s, c, (320, 240), outputs=("color", "depth", "steps"), **NO_SHADING).steps.astype(float)
h = np.isfinite(sg.Renderer().render(s, c, (320, 240), outputs=("color", "depth"), **NO_SHADING).depth)
a = out[None]
for name, sel in (("all", a >= 0), ("tail >=30", a >= 30), ("tail>=50", a >= 50)):
    print(which, name, sel.sum(), "hits", h[sel].mean().round(2), " ".join(f"{m}:{out[m][sel].mean():.2f}" for m in out))
