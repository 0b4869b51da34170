"""Interleaved frame times of marcher variants on one scene, in one process.

    python frame.py [--scene demo|CASE] [--size 400x300] [--rounds 30] DIR_OR_cur ...

Each variant is `cur` (this tree's shaders) or a folder holding replacement
march_relaxed / refine / march_newton / ray_derivative .glsl; the generated
shader's text of those files is swapped. Draws round-robin (A B C A B C ...),
prints per variant the median wall ms, median process-CPU ms, and the ratio to the
first variant. Demo settings are `sdfgl render --demo`'s (soft shadows, AO, ground).
"""
import argparse, dataclasses, statistics, sys, time
from pathlib import Path

from sdfgl import shaderlib
from sdfgl.bench import FrameTimer, Variant
from sdfgl.render import Renderer


def swapper(folder):
    if folder == "cur":
        return None
    pairs = []
    for name in ("refine", "march_relaxed", "march_newton", "ray_derivative"):
        f = Path(folder) / f"{name}.glsl"
        if f.is_file():
            pairs.append((shaderlib.read(name), f.read_text()))

    def fn(src):
        text = src.text
        for a, b in pairs:
            if a in text:
                text = text.replace(a, b)
        return dataclasses.replace(src, text=text)
    return fn


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scene", default="demo")
    ap.add_argument("--size", default="400x300")
    ap.add_argument("--rounds", type=int, default=30)
    ap.add_argument("--method", default=None)
    ap.add_argument("variants", nargs="+")
    a = ap.parse_args()
    size = tuple(int(x) for x in a.size.split("x"))
    if a.scene == "demo":
        from sdfgl.demo import demo_camera, demo_scene
        node, cam = demo_scene(), demo_camera()
        settings = dict(shadows="soft", ao=True, ground=True)
    else:
        from sdfgl import hardcases
        c = {c.name: c for c in hardcases.CASES}[a.scene]
        node, cam = c.build()
        settings = dict(shadows=False, ao=False, max_dist=c.max_dist, **c.settings)
    if a.method:
        settings["method"] = a.method
    r = Renderer()
    timer = FrameTimer(r, size)
    vs = [Variant(a.scene, v, settings, node, cam, source=swapper(v)) for v in a.variants]
    for v in vs:
        timer.prepare(v)
        v.result["cpu"] = []
    for rnd in range(3 + a.rounds):
        for v in vs:
            c0 = time.process_time()
            dt = timer.draw(v)
            c1 = time.process_time()
            if rnd >= 3:
                v.times.append(dt)
                v.result["cpu"].append(c1 - c0)
    w0 = statistics.median(vs[0].times)
    c0 = statistics.median(vs[0].result["cpu"])
    for v in vs:
        w = statistics.median(v.times)
        c = statistics.median(v.result["cpu"])
        print(f"{v.label:>24}: wall {1000 * w:7.2f} ms ({w / w0:5.3f}x)  cpu {1000 * c:7.2f} ms ({c / c0:5.3f}x)")


if __name__ == "__main__":
    main()
