"""Benchmarks of "model only what a scene needs": generated against hand-written and
data-driven shaders, growth with scene size, live against baked values, closed-form
shortcuts. Frame times interleaved in one run (see sdfgl.bench); ratios are what count.
"""
from __future__ import annotations

import sys
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

from . import shaderlib
from .bench import FrameTimer, Progress, Variant, time_interleaved
from .camera import Camera, OrbitCamera
from .compiler.source import ShaderSource
from .gl.cache import CacheBudget
from .demo import demo_camera, demo_scene
from .nodes import box, cylinder, plane, rounded_box, sphere, torus, union
from .nodes.base import Node
from .compiler.data.instances import build
from .params import param
from .render import Renderer

NO_SHADING = {"shadows": False, "ao": False}
BASELINES = Path(__file__).resolve().parents[1] / "benchmarks" / "baselines"
"""The hand-written shaders the generated ones are timed against: in a source checkout only."""
MISSING_BASELINES = (f"hand-written rows skipped: their shaders ({BASELINES}) are in a source checkout of sdfgl, "
                     "not in the installed package")


def csg_scene(live: bool = False) -> Node:
    """examples/csg.py; with ``live`` every number that can be is a parameter."""
    v = (lambda x: param(x)) if live else (lambda x: x)
    ball = (sphere(v(1.0)) & box(v(1.5))).color(0.85, 0.3, 0.2)
    drill = (cylinder(v(0.5), v(4.0)).orient((1, 0, 0)) | cylinder(v(0.5), v(4.0))
             | cylinder(v(0.5), v(4.0)).orient((0, 0, 1)))
    return ball - drill.color(0.95, 0.8, 0.3)


def blobs_scene() -> Node:
    """The scene of benchmarks/baselines/blobs.glsl."""
    blob = union(sphere(0.5).translate((-0.6, 0, 0)), sphere(0.45).translate((0.1, 0.3, 0.2)),
                 sphere(0.4).translate((0.7, -0.1, -0.1)), sphere(0.35).translate((0.0, 0.6, -0.3)), k=0.3)
    slab = rounded_box((2.4, 0.3, 1.2), 0.1).color(0.6, 0.5, 0.4).rotate(30, (0, 1, 0)).translate((0, -0.9, 0))
    ring = torus(1.2, 0.08).color(0.9, 0.75, 0.2).translate((0, 0.2, 0))
    return union(blob.color(0.3, 0.6, 0.9), slab, ring)


HANDWRITTEN: dict[str, tuple[Callable[[], Node], Callable[[], Camera]]] = {
    "csg": (csg_scene, lambda: OrbitCamera(distance=5, yaw=30, pitch=20)),
    "blobs": (blobs_scene, lambda: OrbitCamera(distance=5, yaw=20, pitch=25)),
    "demo": (demo_scene, demo_camera),
}


def handwritten(name: str) -> Callable[[ShaderSource], ShaderSource]:
    """Swap the generated map() and mapColor() for benchmarks/baselines/<name>.glsl."""
    code = (BASELINES / f"{name}.glsl").read_text(encoding="utf-8")

    def rewrite(src: ShaderSource) -> ShaderSource:
        start = src.text.index("float map(vec3 p) {")
        end = src.text.index(shaderlib.read("stages/refine").split("\n")[0])
        text = src.text[:start] + code + "\n" + src.text[end:]
        return ShaderSource(text, ("(hand-written)",) * (text.count("\n") + 1), src.params, src.live_bounds,
                            src.data, coarse_tile=src.coarse_tile)  # the same coarse pass before it
    return rewrite


WHOLE_SHADERS = {"csg": csg_scene}
"""Scenes with a whole fragment shader written by hand (benchmarks/baselines/whole/<name>.glsl)."""


def whole_handwritten(name: str) -> Callable[[ShaderSource], ShaderSource]:
    """Replace the generated shader by the whole one written by hand for scene ``name``."""
    whole = (BASELINES / "whole" / f"{name}.glsl").read_text(encoding="utf-8")
    own_map = (BASELINES / f"{name}.glsl").read_text(encoding="utf-8")  # the map() both baselines share
    text = "#version 330 core\n" + whole.replace(f'#include "../{name}.glsl"', own_map)
    return lambda src: ShaderSource(text, ("(hand-written)",) * (text.count("\n") + 1))


def run_whole(size: tuple[int, int], frames: int, warmup: int) -> str:
    """Generated shaders against whole shaders written by hand for the same scene, lights and
    look, default settings (soft shadows and AO): a frame with its read-back, interleaved; and
    how many pixels differ. Return the markdown table (empty without the baselines)."""
    if not (BASELINES / "whole").is_dir():
        return ""
    renderer = Renderer(budget=CacheBudget(programs=None))
    timer = FrameTimer(renderer, size, read_back=True)
    groups = []
    for name, make in WHOLE_SHADERS.items():
        cam = HANDWRITTEN[name][1]()
        groups.append([Variant(name, "generated", {}, make(), cam),
                       Variant(name, "generated, no coarse pass", {"coarse": False}, make(), cam),
                       Variant(name, "whole shader written by hand", {}, make(), cam, source=whole_handwritten(name))])
    rows = ["| scene | variant | frame ms incl. read-back (median / p95) | ratio to the hand-written | "
            "pixels > 8/255 from the generated image |", "|---|---|---|---|---|"]
    for vs in groups:
        time_interleaved(timer, vs, frames, warmup, Progress(0, False))
        images = [np.frombuffer(v.result["_image"], np.uint8).astype(int) for v in vs]
        hand = vs[-1].result["frame_ms_median"]
        for v, img in zip(vs, images):
            differ = float(np.mean(np.abs(img - images[0]).reshape(-1, 3).max(axis=1) > 8))
            rows.append(f"| {v.scene} | {v.label} | {v.result['frame_ms_median']:.1f} / {v.result['frame_ms_p95']:.1f} | "
                        f"{v.result['frame_ms_median'] / hand:.2f} | {100 * differ:.2f} % |")
    return (f"Whole shaders, {size[0]}x{size[1]}, default settings (soft shadows and AO), {frames} timed frames "
            f"after {warmup} warm-up, interleaved: each frame drawn and read back. The hand-written shader "
            "(benchmarks/baselines/whole/) marches a fixed 128 steps with the same lights and look; the generated "
            "one adds its coarse pass and draws the tiles it proves empty without the march.\n\n" + "\n".join(rows))


def scattered(n: int, seed: int = 0) -> tuple[Node, Camera]:
    """n spheres, boxes and tori scattered in a cube whose volume grows with n."""
    rng = np.random.default_rng(seed)
    ext = 2.0 * n ** (1 / 3)
    kinds = (lambda: sphere(0.4), lambda: box(0.6), lambda: torus(0.35, 0.1))
    parts = [kinds[i % 3]().translate(tuple(rng.uniform(-ext, ext, 3))) for i in range(n)]
    return union(*parts), OrbitCamera(distance=3.2 * ext, yaw=30, pitch=25)


def with_grid(scene: Node, single_cell: bool) -> Node:
    """The same union kept as data: a real grid, or one cell listing everything (an uber-shader)."""
    scene.__dict__["_grid"] = build(list(scene.children), 2, single_cell=single_cell)
    return scene


def variants(sizes: Sequence[int]) -> list[tuple[str, list[Variant]]]:
    groups: list[tuple[str, list[Variant]]] = []
    hand = []
    for name, (make, cam) in HANDWRITTEN.items():
        hand.append(Variant(name, "generated", dict(NO_SHADING), make(), cam()))
        if BASELINES.is_dir():
            hand.append(Variant(name, "hand-written", dict(NO_SHADING), make(), cam(), source=handwritten(name)))
    groups.append(("generated vs hand-written (same template and settings)", hand))
    for n in sizes:
        vs = []
        kinds = [("code (no bounds)", "off"), ("uber-shader (one list)", "single"), ("grid (bounds)", "grid")]
        for label, grid in kinds if n <= 256 else kinds[::2]:  # the uber-shader takes ~20 s a frame at 1024
            node, cam = scattered(n)
            if grid != "off":
                node = with_grid(node, single_cell=grid == "single")
            vs.append(Variant(f"{n} primitives", label, {**NO_SHADING, "grid": grid != "off"}, node, cam))
        groups.append((f"{n} primitives", vs))
    live = [Variant("csg", "baked constants", dict(NO_SHADING), csg_scene(), HANDWRITTEN["csg"][1]()),
            Variant("csg", "live parameters (uniforms)", dict(NO_SHADING), csg_scene(live=True), HANDWRITTEN["csg"][1]())]
    groups.append(("baked vs live parameters", live))
    lone = OrbitCamera(distance=4, yaw=30, pitch=20)
    shortcuts = [Variant("lone sphere", "closed form", dict(NO_SHADING), sphere(1), lone),
                 Variant("lone sphere", "marched", {**NO_SHADING, "analytic": False}, sphere(1), lone),
                 Variant("demo + ground", "analytic ground", {**NO_SHADING, "ground": True}, demo_scene(), demo_camera()),
                 Variant("demo + ground", "marched ground plane", dict(NO_SHADING),
                         union(demo_scene(), plane((0, 1, 0), (0, demo_scene().bounds[0][1], 0))), demo_camera())]
    groups.append(("closed-form shortcuts", shortcuts))
    return groups


def run_model(size: tuple[int, int], frames: int, warmup: int, sizes: Sequence[int], progress: bool) -> str:
    """Run every group (interleaved within a group); return the markdown section."""
    renderer = Renderer(budget=CacheBudget(programs=None))  # timings hold every variant's program
    timer = FrameTimer(renderer, size)
    groups = variants(sizes)
    note = "" if BASELINES.is_dir() else f" ({MISSING_BASELINES})"
    if note:
        print(f"bench: {MISSING_BASELINES}", file=sys.stderr)
    bar = Progress(sum(len(g) + warmup + frames for _, g in groups), progress)
    rows = ["| scene | variant | frame ms (median / p95) | ratio to the scene's first row | link ms | first frame ms | "
            "steps/px |", "|---|---|---|---|---|---|---|"]
    for title, vs in groups:
        time_interleaved(timer, vs, frames, warmup, bar)
        for v in vs:
            r = v.result
            base = next(b for b in vs if b.scene == v.scene).result["frame_ms_median"]
            res = renderer.render(v.node, v.camera, size, outputs=("color", "steps"), **v.settings) if v.source is None \
                else None
            steps = f"{float(res.steps.mean()):.2f}" if res is not None else "-"
            rows.append(f"| {v.scene} | {v.label} | {r['frame_ms_median']:.2f} / {r['frame_ms_p95']:.2f} | "
                        f"{r['frame_ms_median'] / base:.2f} | {1000 * r['compile_s']:.0f} | "
                        f"{1000 * r['first_frame_s']:.0f} | {steps} |")
    return (f"Size {size[0]}x{size[1]}, shadows and AO off (marching, normals and refinement only), "
            f"{frames} timed frames after {warmup} warm-up, interleaved within each comparison. "
            "'link' is the driver's compile and link; 'first frame' adds llvmpipe's code generation"
            f"{note}.\n\n"
            + "\n".join(rows))
