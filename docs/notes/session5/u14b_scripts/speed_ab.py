"""In-process A/B of the crease handling's cost: sharp mesh of fogleman's CSG example at 2^22
samples with the old refine (05fa8e3's, passed as OLD_DC=path/to/old/extract_dc.py: plain
gradients, no crease planes) against the new one, interleaved, 7 rounds; CPU and wall medians."""
import importlib.util, os, time
import numpy as np
import sdfgl as sg
from sdfgl.mesh import extract_dc as X

spec = importlib.util.spec_from_file_location("sdfgl.mesh.old_dc", os.environ.get("OLD_DC", "/tmp/u14b_base/sdfgl/mesh/extract_dc.py"))
old = importlib.util.module_from_spec(spec)
spec.loader.exec_module(old)
new_refine = X.refine


def old_refine(field, lat, low, axis, t, inside):
    t, g = old.refine(field, lat, low, axis, t, inside)
    return t, g, np.zeros(len(t))  # no bend: no crease planes


c = sg.cylinder(0.5, 4)
part = (sg.sphere(1) & sg.box(1.5)) - (c.orient(sg.X) | c | c.orient(sg.Z))
sg.mesh(part, samples=2 ** 20, mode="sharp", colors=False)
res = {"old": [], "new": []}
for r in range(7):
    for name in ("old", "new"):
        X.refine = old_refine if name == "old" else new_refine
        t0, w0 = time.process_time(), time.perf_counter()
        sg.mesh(part, samples=2 ** 22, mode="sharp", colors=False)
        res[name].append((time.process_time() - t0, time.perf_counter() - w0))
for k, v in res.items():
    print(k, "median cpu %.3f wall %.3f" % (np.median([a for a, _ in v]), np.median([b for _, b in v])))
print("ratio cpu %.3f" % (np.median([a for a, _ in res["new"]]) / np.median([a for a, _ in res["old"]])))
