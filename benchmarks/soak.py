"""Soak test: resident memory while rendering many distinct scenes and a baked-angle turntable.

    python benchmarks/soak.py                       # the full figures: 2000 scenes, 1000 frames
    python benchmarks/soak.py --scenes 300 --frames 300 --size 32x24 --json   # the CI size

Every scene and every turntable frame has its own shader source (the angle is baked into
the scene as a constant), so without bounded caches each one would keep a compiled program
(about 1 to 3 MB of llvmpipe machine code) for ever. Prints RSS at the start (after a
warm-up render), every so often, and at the end, plus the cache sizes.
"""
from __future__ import annotations

import argparse
import json
import resource
import time

import sdfgl as sg
from sdfgl.render import default_renderer


def rss_mb() -> float:
    """Current resident set size in MB (from /proc; falls back to the peak)."""
    try:
        with open("/proc/self/statm") as f:
            pages = int(f.read().split()[1])
        return pages * resource.getpagesize() / 2**20
    except OSError:
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def distinct_scene(i: int) -> sg.Node:
    """Scene i: a different source for every i (sizes, blend radius and colour baked in)."""
    a = sg.rounded_box((1.0 + 0.001 * i, 0.8, 0.9), 0.1)
    b = sg.sphere(0.6 + 0.0005 * i).translate((0.5, 0.3, 0.0))
    return sg.union(a, b, k=0.05 + 0.0001 * i).color(0.8, 0.2 + 0.0003 * (i % 2000), 0.3)


def turntable_frame(i: int, frames: int) -> sg.Node:
    """Frame i of a turntable whose angle is baked into the scene (a new source each frame)."""
    base = sg.difference(sg.box(1.4), sg.sphere(0.9)) | sg.torus(1.0, 0.15).translate((0, -0.7, 0))
    return base.rotate(360.0 * i / frames, (0, 1, 0))


def run(scenes: int, frames: int, size: tuple[int, int], every: int = 250, progress: bool = False) -> dict:
    r = default_renderer()
    cam = sg.OrbitCamera(distance=5, yaw=30, pitch=20)
    sg.render(sg.sphere(1), cam, size)  # warm-up: context, first program
    out: dict = {"size": list(size), "budget": vars(sg.cache_budget()), "start_rss_mb": rss_mb(), "trace": []}
    if progress:
        print(f"start: RSS {out['start_rss_mb']:.1f} MB", flush=True)
    t0 = time.perf_counter()
    for i in range(scenes):
        sg.render(distinct_scene(i), cam, size, shadows=False, ao=False)
        if (i + 1) % every == 0:
            out["trace"].append(("scenes", i + 1, round(rss_mb(), 1)))
            if progress:
                print(f"scenes {i + 1:5d}: RSS {rss_mb():.1f} MB ({time.perf_counter() - t0:.0f} s)", flush=True)
    out["after_scenes_rss_mb"] = rss_mb()
    for i in range(frames):
        sg.render(turntable_frame(i, frames), cam, size, shadows=False, ao=False)
        if (i + 1) % every == 0:
            out["trace"].append(("frames", i + 1, round(rss_mb(), 1)))
            if progress:
                print(f"frames {i + 1:5d}: RSS {rss_mb():.1f} MB ({time.perf_counter() - t0:.0f} s)", flush=True)
    out["end_rss_mb"] = rss_mb()
    out["growth_mb"] = out["end_rss_mb"] - out["start_rss_mb"]
    out["seconds"] = time.perf_counter() - t0
    out["compiles"] = r.programs.compiles
    out["cached_programs"] = len(r.programs)
    out["evicted_programs"] = r.programs.evictions
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scenes", type=int, default=2000)
    p.add_argument("--frames", type=int, default=1000)
    p.add_argument("--size", default="64x48")
    p.add_argument("--json", action="store_true", help="print one JSON object only")
    a = p.parse_args()
    size = tuple(int(x) for x in a.size.split("x"))
    res = run(a.scenes, a.frames, size, every=100, progress=not a.json)  # type: ignore[arg-type]
    if a.json:
        print(json.dumps(res))
        return
    print(f"start RSS {res['start_rss_mb']:.1f} MB, after {a.scenes} scenes {res['after_scenes_rss_mb']:.1f} MB, "
          f"after {a.frames} turntable frames {res['end_rss_mb']:.1f} MB: growth {res['growth_mb']:.1f} MB "
          f"({res['compiles']} compiles, {res['cached_programs']} cached, {res['evicted_programs']} evicted, "
          f"{res['seconds']:.0f} s, budget {res['budget']})")


if __name__ == "__main__":
    main()
