"""What flattening the robot into its parts would give: 1000 robots written as 5000 instances
(body, arms, two legs, head minus eyes), against the robots and 1000 spheres, interleaved."""
import numpy as np
import sdfgl as sg
from sdfgl.bench import FrameTimer, Progress, Variant, time_interleaved
from sdfgl.bench_big import instances, spheres_like, NO_SHADING
from sdfgl.nodes import booleans, primitives as p
from sdfgl.render import Renderer


def flat(n: int = 1000, seed: int = 0):
    rng = np.random.default_rng(seed)
    ext = 1.0 * n ** (1 / 3)
    body = p.rounded_box((0.4, 0.5, 0.3), 0.05)
    head = booleans.difference(p.sphere(0.18).translate((0, 0.38, 0)),
                               booleans.union(p.sphere(0.04).translate((-0.07, 0.42, 0.15)), p.sphere(0.04).translate((0.07, 0.42, 0.15))))
    arms = p.capsule((-0.3, 0.15, 0), (0.3, 0.15, 0), 0.05)
    legs = [p.cylinder(0.06, 0.3).translate((-0.1, -0.35, 0)), p.cylinder(0.06, 0.3).translate((0.1, -0.35, 0))]
    parts = []
    for _ in range(n):
        t = tuple(rng.uniform(-ext, ext, 3))
        parts += [x.translate(t).color(0.8, 0.5, 0.2) for x in (body, head, arms, *legs)]
    return booleans.union(*parts), instances(n, seed)[1]


if __name__ == "__main__":
    r = Renderer(); timer = FrameTimer(r, (320, 240))
    vs = [Variant("spheres", "1000", dict(NO_SHADING), *spheres_like(1000)),
          Variant("robots", "1000", dict(NO_SHADING), *instances(1000)),
          Variant("robots flattened", "5000 parts", dict(NO_SHADING), *flat())]
    for v in vs:
        res = r.render(v.node, v.camera, (320, 240), outputs=("color", "depth", "steps"), **NO_SHADING)
        v.result["calls"] = float(res.steps.mean())
        v.result["depth"] = res.depth
    print("same image:", np.array_equal(np.isfinite(vs[1].result["depth"]), np.isfinite(vs[2].result["depth"])),
          "max depth diff", float(np.nanmax(np.abs(vs[1].result["depth"] - vs[2].result["depth"]))))
    time_interleaved(timer, vs, 9, 2, Progress(0, False))
    base = vs[0].result["frame_ms_median"]
    for v in vs:
        print(v.scene, v.label, f"{v.result['frame_ms_median']:.1f} ms ratio {v.result['frame_ms_median'] / base:.2f} calls {v.result['calls']:.2f}")
