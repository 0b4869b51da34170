"""Sharp-mode cost on fogleman's CSG example at 2^22 samples: one timed mesh per process.

usage: speed.py            -> prints 'cpu wall point_samples' for the sdfgl on sys.path
A/B: alternate PYTHONPATH=<old checkout> and the new tree, 5 rounds each, compare medians."""
import time
import sdfgl as sg

c = sg.cylinder(0.5, 4)
part = (sg.sphere(1) & sg.box(1.5)) - (c.orient(sg.X) | c | c.orient(sg.Z))
sg.mesh(part, samples=2 ** 20, mode="sharp", colors=False)  # compile shaders, warm caches
t0, w0 = time.process_time(), time.perf_counter()
m = sg.mesh(part, samples=2 ** 22, mode="sharp", colors=False)
print(f"{time.process_time() - t0:.3f} {time.perf_counter() - w0:.3f} {len(m.vertices)}")
