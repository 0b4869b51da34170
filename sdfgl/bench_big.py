"""Benchmarks of big scenes: growth with the number of objects, mixed primitive types,
instanced subtrees, 10^5-deep chains, shared subtrees (DAGs) and big polygons.

Each row says what was built and how long building, compiling (link and first frame)
and drawing took, beside the steps per ray; frame times are medians of interleaved draws
(see sdfgl.bench). ``scenes`` are also what the tests and the closing figures use.
"""
from __future__ import annotations

import importlib.util
import math
import statistics
import time
from typing import TYPE_CHECKING, Callable

import numpy as np

from .camera import Camera, OrbitCamera
from .gl.cache import CacheBudget
from .nodes import booleans, primitives, shapes2d
from .nodes.base import Node

if TYPE_CHECKING:  # pragma: no cover
    from .render import Renderer

NO_SHADING = {"shadows": False, "ao": False}


def growth(n: int, seed: int = 0) -> tuple[Node, Camera]:
    """The growth scene kind: n spheres of radius 0.15 scattered in a 12 x 2 x 12 box."""
    rng = np.random.default_rng(seed)
    pts = rng.uniform((-6, -1, -6), (6, 1, 6), (n, 3))
    scene = booleans.union(*[primitives.sphere(0.15).translate(p) for p in pts]) if n > 1 else \
        primitives.sphere(0.15).translate(pts[0])
    return scene, OrbitCamera(target=(0, 0, 0), distance=14, yaw=30, pitch=35, fov=50)


def blend_slab(n: int, k: float = 0.1, seed: int = 0) -> tuple[Node, Camera]:
    """n spheres of radius 0.05-0.12 random in a slab 0.3 n^(1/2) wide and 1 thick, blended
    with radius ``k`` (0: the hard union of the same spheres)."""
    rng = np.random.default_rng(seed)
    half = 0.15 * n ** 0.5
    pts = rng.uniform((-half, -0.5, -half), (half, 0.5, half), (n, 3))
    radii = rng.uniform(0.05, 0.12, n)
    scene = booleans.union(*[primitives.sphere(float(r)).translate(p) for r, p in zip(radii, pts)], k=k)
    return scene, OrbitCamera(target=(0, 0, 0), distance=1.9 * half, yaw=30, pitch=35, fov=50)


ATOMS = {"C": (0.17, (0.35, 0.35, 0.35)), "N": (0.155, (0.2, 0.3, 0.9)), "O": (0.152, (0.9, 0.15, 0.1)),
         "S": (0.18, (0.9, 0.8, 0.2)), "H": (0.11, (0.95, 0.95, 0.95))}


def molecule(n: int = 1001, k: float = 0.04, seed: int = 0) -> tuple[Node, Camera]:
    """A molecule of n atoms, spheres smooth-blended with radius ``k`` (the molecule scene kind
    of the Lipschitz-pruning paper, Barbier et al. 2025): a folded chain, atoms 0.15 apart
    along it and kept within a globule, each an element's radius and colour."""
    rng = np.random.default_rng(seed)
    names = rng.choice(list(ATOMS), n, p=[0.35, 0.1, 0.1, 0.05, 0.4])
    at = np.zeros((n, 3))
    step = np.array([1.0, 0.0, 0.0])
    globule = 0.3 * n ** (1 / 3)  # about the radius of n packed atoms
    for i in range(1, n):  # a persistent random walk, turned back into a globule
        out = float(np.linalg.norm(at[i - 1]))
        step = step + 0.8 * rng.normal(size=3) - (at[i - 1] / out if out > globule else 0.0)
        step /= np.linalg.norm(step)
        at[i] = at[i - 1] + 0.15 * step
    parts = [primitives.sphere(ATOMS[e][0]).color(*ATOMS[e][1]).translate(tuple(p)) for e, p in zip(names, at)]
    lo, hi = at.min(axis=0), at.max(axis=0)
    centre = tuple((lo + hi) / 2)
    return booleans.union(*parts, k=k), OrbitCamera(target=centre, distance=1.6 * float(np.max(hi - lo)) + 1,
                                                     yaw=30, pitch=25)


def trees(n_trees: int = 62, k: float = 0.05, seed: int = 0) -> tuple[Node, Camera]:
    """A forest of 3 n_trees boxes (186 by default; the trees scene kind of the Lipschitz-
    pruning paper): each tree a trunk smooth-blended (radius ``k``) into a crown that is
    the hard union of two turned boxes, four kinds of tree moved and turned about y."""
    rng = np.random.default_rng(seed)
    kinds = []
    for _ in range(4):
        h = float(rng.uniform(0.6, 1.0))
        trunk = primitives.box((0.08, h / 2, 0.08)).translate((0, h / 2, 0)).color(0.45, 0.3, 0.15)
        crown = booleans.union(
            primitives.box(tuple(rng.uniform(0.2, 0.35, 3))).rotate(float(rng.uniform(0, 90)), (0, 1, 0)),
            primitives.box(tuple(rng.uniform(0.15, 0.3, 3))).rotate(45, (1, 0, 1)).translate((0, 0.25, 0)))
        kinds.append(booleans.union(trunk, crown.translate((0, h + 0.15, 0)).color(0.2, 0.55, 0.2), k=k))
    side = int(np.ceil(n_trees ** 0.5))
    parts = []
    for i in range(n_trees):
        x, z = (i % side - side / 2) * 1.1, (i // side - side / 2) * 1.1
        parts.append(kinds[i % 4].rotate(float(rng.uniform(0, 360)), (0, 1, 0))
                     .translate((x + float(rng.uniform(-0.3, 0.3)), 0, z + float(rng.uniform(-0.3, 0.3)))))
    return booleans.union(*parts), OrbitCamera(target=(0, 0.6, 0), distance=1.5 * side, yaw=30, pitch=30)


def _random_rotation(rng: np.random.Generator) -> tuple[float, tuple[float, float, float]]:
    axis = rng.normal(size=3)
    return float(rng.uniform(0, 360)), tuple(axis / np.linalg.norm(axis))


def mixed(n: int, seed: int = 0) -> tuple[Node, Camera]:
    """n capsules, cones, tori, boxes and spheres, each rotated, in a cube growing with n."""
    rng = np.random.default_rng(seed)
    ext = 1.2 * n ** (1 / 3)
    kinds: list[Callable[[], Node]] = [
        lambda: primitives.capsule((0, -0.3, 0), (0, 0.3, 0), float(rng.uniform(0.1, 0.2))),
        lambda: primitives.cone(float(rng.uniform(0.4, 0.7)), float(rng.uniform(0.2, 0.35)), 0.05),
        lambda: primitives.torus(float(rng.uniform(0.2, 0.35)), 0.08),
        lambda: primitives.box(tuple(rng.uniform(0.2, 0.5, 3))),
        lambda: primitives.sphere(float(rng.uniform(0.15, 0.3))),
    ]
    parts = []
    for i in range(n):
        angle, axis = _random_rotation(rng)
        parts.append(kinds[i % 5]().rotate(angle, axis).translate(tuple(rng.uniform(-ext, ext, 3))))
    return booleans.union(*parts), OrbitCamera(distance=3.2 * ext, yaw=30, pitch=25)


def twenty_nodes() -> Node:
    """A 20-node subtree: a little robot of primitives, booleans and moves."""
    p = primitives
    body = p.rounded_box((0.4, 0.5, 0.3), 0.05)
    head = p.sphere(0.18).translate((0, 0.38, 0))
    eyes = booleans.union(p.sphere(0.04).translate((-0.07, 0.42, 0.15)), p.sphere(0.04).translate((0.07, 0.42, 0.15)))
    arms = p.capsule((-0.3, 0.15, 0), (0.3, 0.15, 0), 0.05)
    legs = booleans.union(p.cylinder(0.06, 0.3).translate((-0.1, -0.35, 0)),
                          p.cylinder(0.06, 0.3).translate((0.1, -0.35, 0)))
    return booleans.difference(booleans.union(body, head, arms, legs), eyes).color(0.8, 0.5, 0.2)


def instances(n: int, seed: int = 0, subtree: Node | None = None) -> tuple[Node, Camera]:
    """n translated copies of one subtree (the 20-node robot) in a cube growing with n."""
    rng = np.random.default_rng(seed)
    ext = 1.0 * n ** (1 / 3)
    sub = subtree if subtree is not None else twenty_nodes()
    parts = [sub.translate(tuple(rng.uniform(-ext, ext, 3))) for _ in range(n)]
    return booleans.union(*parts), OrbitCamera(distance=3.2 * ext, yaw=30, pitch=25)


def turned_instances(n: int, seed: int = 0) -> tuple[Node, Camera]:
    """n copies of the 20-node robot, each turned about a random axis, where instances(n) puts them."""
    rng = np.random.default_rng(seed)
    ext = 1.0 * n ** (1 / 3)
    sub = twenty_nodes()
    parts = [sub.rotate(*_random_rotation(rng)).translate(tuple(rng.uniform(-ext, ext, 3))) for _ in range(n)]
    return booleans.union(*parts), OrbitCamera(distance=3.2 * ext, yaw=30, pitch=25)


def spheres_like(n: int, seed: int = 0) -> tuple[Node, Camera]:
    """n spheres where instances(n) puts its copies (the frame-time yardstick)."""
    return instances(n, seed, primitives.sphere(0.35))


def on_floor(scene: Node, camera: Camera) -> tuple[Node, Camera]:
    """``scene`` on a plane just below its bounds: the free way along the ray beside other geometry."""
    lo, hi = scene.bounds
    below = float(lo[1]) - 0.05 * float(max(hi - lo))
    return booleans.union(scene, primitives.plane((0, 1, 0), (0, below, 0))), camera


def chain(kind: str, n: int) -> tuple[Node, Camera]:
    """A chain of n operations as a loop writes it: ``s = s | x``, ``s = s.translate(...)``."""
    s: Node = primitives.sphere(0.5)
    if kind == "union":
        for i in range(n):
            s = s | primitives.sphere(0.02).translate((math.cos(i * 0.01) * 2, (i / n) * 2 - 1, math.sin(i * 0.01) * 2))
    elif kind == "union_right":  # s = x | s: joins the same n-ary node from the front
        for i in range(n):
            s = primitives.sphere(0.02).translate((math.cos(i * 0.01) * 2, (i / n) * 2 - 1, math.sin(i * 0.01) * 2)) | s
    elif kind == "translate":
        for _ in range(n):
            s = s.translate((1e-5, 0, 0))
    elif kind == "rotate":
        s = primitives.box((1, 0.5, 0.25))
        for _ in range(n):
            s = s.rotate(0.01, (0, 1, 0))
    elif kind == "mixed":  # union, then move: nothing to fold, the graph is n deep
        for i in range(n):
            s = (s | primitives.sphere(0.02).translate((0, 1, 0))).translate((1e-5, 0, 0))
    else:
        raise ValueError(kind)
    return s, OrbitCamera(distance=6, yaw=30, pitch=20)


def dag(levels: int) -> tuple[Node, Camera]:
    """One node object used as both operands of a smooth union, ``levels`` deep (2^levels paths)."""
    s: Node = primitives.sphere(0.5).union(primitives.box(0.6).translate((0.5, 0, 0)))
    for _ in range(levels):
        s = booleans.union(s, s, k=0.01)
    return s, OrbitCamera(distance=4, yaw=30, pitch=20)


def polygon(n: int) -> tuple[Node, Camera]:
    """An extruded star polygon of n vertices."""
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + 0.3 * np.cos(12 * a)
    pts = np.stack([r * np.cos(a), r * np.sin(a)], axis=1)
    return shapes2d.extrude(shapes2d.polygon(pts), 0.5), OrbitCamera(distance=4, yaw=30, pitch=40)


def text_page(glyphs: int) -> tuple[Node, Camera]:
    """Extruded text of ``glyphs`` letters and digits (40 a line), seen face on, filling the view."""
    from .nodes.text import text
    rng = np.random.default_rng(glyphs)
    chars = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
    picks = rng.integers(len(chars), size=glyphs)
    lines = ["".join(chars[i] for i in picks[j:j + 40]) for j in range(0, glyphs, 40)]
    scene = shapes2d.extrude(text("\n".join(lines), size=0.1, align="center"), 0.02)
    lo, hi = scene.bounds
    centre, ext = (lo + hi) / 2, float(np.max(hi - lo))
    return scene, Camera.look_at(tuple(centre + (0.0, 0.0, 1.2 * ext)), tuple(centre), fov=45)


def engraved_plate(engraved: bool) -> tuple[Node, Camera]:
    """A rounded plate, with "sdfgl" engraved in it or not (the modelling guide's example)."""
    from .nodes.text import text
    plate = primitives.rounded_box((1.2, 0.5, 0.1), 0.02)
    if engraved:
        plate = booleans.difference(plate, shapes2d.extrude(text("sdfgl", size=0.3, align="center"), 0.05)
                                    .translate((0, -0.1, 0.05)))
    return plate, OrbitCamera(distance=2.2, yaw=20, pitch=25)


FRESH_CHAIN = 10 ** 6
"""The union chain the full run's phases table builds in a fresh process of its own."""


def run_phases(quick: bool, size: tuple[int, int] = (320, 240), fresh: int | None = None) -> str:
    """Where the time of a 10^5-deep chain (and of a ``fresh``-step union chain in a fresh
    process, :func:`main`; by default :data:`FRESH_CHAIN` steps in the full run, none in the
    quick one) goes, phase by phase, each in wall and process CPU seconds (CPU is what a loaded
    machine disturbs least): the Python loop that builds it, bounds, code generation (with the
    grid build), the driver's compile and link, and the first frame (llvmpipe's code
    generation); return the markdown table."""
    from .render import Renderer
    n = 2000 if quick else 10 ** 5
    cases: list[tuple[str, Callable[[], tuple[Node, Camera]]]] = [
        (f"chain of {n} unions, left-deep (s = s OR x)", lambda: chain("union", n)),
        (f"chain of {n} unions, right-deep (s = x OR s)", lambda: chain("union_right", n)),
        (f"chain of {n} translates", lambda: chain("translate", n)),
        (f"chain of {n} rotates", lambda: chain("rotate", n)),
        ("one node as both operands, 30 levels (2^30 paths)", lambda: dag(30))]
    rows = ["| scene | build s (CPU) | bounds s (CPU) | codegen s | link s | first frame s | render CPU s | "
            "total s (CPU) | frame ms |", "|---|---|---|---|---|---|---|---|---|"]
    renderer = Renderer(budget=CacheBudget(programs=None))  # timings hold every variant's programs
    renderer.render(primitives.sphere(1), size=(8, 8))  # the context, outside the figures
    rows += [phases_row(renderer, name, make, size)[0] for name, make in cases]
    fresh = FRESH_CHAIN if fresh is None and not quick else fresh
    whole = "" if fresh is None else _fresh_chain(fresh, size, rows)
    return (f"Build and compile phases of deep chains, {size[0]}x{size[1]}, shadows and AO off, one run each "
            "in a fresh scene: wall seconds, process CPU seconds in brackets ('render CPU' covers codegen, "
            f"link and first frame; llvmpipe's threads count).{whole}\n\n" + "\n".join(rows))


def phases_row(renderer: "Renderer", name: str, make: Callable[[], tuple[Node, Camera]],
               size: tuple[int, int]) -> tuple[str, float]:
    """One row of the phases table, for the scene ``make()`` builds, drawn by ``renderer``: (the
    markdown row, the wall seconds from the build to the first frame's end)."""
    import gc
    gc.collect()
    w0, c0 = time.perf_counter(), time.process_time()
    scene, cam = make()
    w1, c1 = time.perf_counter(), time.process_time()
    scene.bounds  # noqa: B018 - the phase being timed
    w2, c2 = time.perf_counter(), time.process_time()
    res = renderer.render(scene, cam, size, **NO_SHADING)
    w3, c3 = time.perf_counter(), time.process_time()
    t = res.timings
    frame = renderer.render(scene, cam, size, **NO_SHADING).timings["draw_s"]
    return (f"| {name} | {w1 - w0:.2f} ({c1 - c0:.2f}) | {w2 - w1:.2f} ({c2 - c1:.2f}) | "
            f"{t['codegen_s']:.2f} | {t['compile_s']:.2f} | {t['draw_s']:.2f} | {c3 - c2:.2f} | "
            f"{w3 - w0:.2f} ({c3 - c0:.2f}) | {1000 * frame:.1f} |"), w3 - w0


def _fresh_chain(n: int, size: tuple[int, int], rows: list[str]) -> str:
    """Add the phases row of an n-step union chain built in a fresh process (``python -m
    sdfgl.bench_big N W H``) to ``rows``; return the sentence on that process's whole run."""
    from .bench_process import fresh_process, last_json, python_module
    got = fresh_process(python_module("sdfgl.bench_big", n, *size))
    if isinstance(got, str):
        return f" The chain of {n} unions in a fresh process {got}."
    wall, stdout = got
    out = last_json(stdout)
    rows.append(out["row"])
    return (f" The last row ran in a fresh process of its own: from its start to its exit it took {wall:.2f} s, "
            f"{wall - out['total_s']:.2f} s of them outside the row (start-up, imports and the GL context before "
            "the build; after the frame, the interpreter's exit freeing the graph).")


def main() -> None:
    """``python -m sdfgl.bench_big N W H``: the phases row of a chain of N unions, built and drawn
    at W x H in this process; prints {"row": the markdown row, "total_s": its wall seconds} as JSON."""
    import json
    import sys

    from .render import Renderer
    n, w, h = (int(x) for x in sys.argv[1:4])
    renderer = Renderer(budget=CacheBudget(programs=None))
    renderer.render(primitives.sphere(1), size=(8, 8))  # the context, outside the row
    row, total = phases_row(renderer, f"chain of {n} unions, left-deep (s = s OR x), in a fresh process",
                            lambda: chain("union", n), (w, h))
    print(json.dumps({"row": row, "total_s": total}))


def _timed(fn: Callable[[], object]) -> tuple[object, float]:
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def run_big(quick: bool, size: tuple[int, int] = (320, 240)) -> str:
    """Every big-scene row at ``size`` (--quick: smaller scenes); return the markdown section."""
    from .bench import FrameTimer, Progress, Variant, time_interleaved
    from .render import Renderer
    renderer = Renderer(budget=CacheBudget(programs=None))  # timings hold every variant's programs
    timer = FrameTimer(renderer, size)
    frames, warmup = (3, 1) if quick else (5, 2)
    rows = ["| scene | objects | build s | link ms | first frame ms | frame ms (median) | ratio | steps/px | "
            "code chars | how |", "|---|---|---|---|---|---|---|---|---|---|"]

    def measure(group: list[tuple[str, int, Callable[[], tuple[Node, Camera]]]], base: int = 0,
                extra: tuple[dict, ...] = ()) -> None:
        """Time ``group`` interleaved; ``extra`` settings per row (after NO_SHADING)."""
        vs = []
        for i, (name, n, make) in enumerate(group):
            (scene, cam), build = _timed(make)  # type: ignore[misc]
            settings = {**NO_SHADING, **(extra[i] if i < len(extra) else {})}
            vs.append(Variant(name, str(n), settings, scene, cam, result={"build_s": build}))
        time_interleaved(timer, vs, frames, warmup, Progress(0, False))
        ref = vs[base].result["frame_ms_median"]
        for v in vs:
            res = renderer.render(v.node, v.camera, size, outputs=("color", "steps"), **v.settings)
            r = v.result
            src = r["_source"]
            rows.append(f"| {v.scene} | {v.label} | {r['build_s']:.2f} | {1000 * r['compile_s']:.0f} | "
                        f"{1000 * r['first_frame_s']:.0f} | {r['frame_ms_median']:.1f} | "
                        f"{r['frame_ms_median'] / ref:.2f} | {float(res.steps.mean()):.2f} | {src.code_size} | "
                        f"{src.choice}; {src.data_unions} union(s) as data, grid_min {src.grid_min} |")

    sizes = (16, 128) if quick else (16, 256, 1024)
    measure([("growth: spheres r 0.15 in 12x2x12", n, lambda n=n: growth(n)) for n in sizes])
    n_inst = 64 if quick else 1000
    # the yardstick pair alone: a third, slower variant in the round-robin moved the pair's
    # ratio from 2.1-2.2 (pairs) to 1.8, so the free-way rows are groups of their own
    measure([(f"{n_inst} spheres (yardstick)", n_inst, lambda: spheres_like(n_inst)),
             (f"{n_inst} moved copies of a 20-node subtree", n_inst, lambda: instances(n_inst))])
    for name, n, make in ((f"{n_inst} moved copies of a 20-node subtree", n_inst, lambda: instances(n_inst)),
                          (f"{n_inst} turned copies of a 20-node subtree", n_inst, lambda: turned_instances(n_inst)),
                          (f"{n_inst} moved copies on a plane", n_inst, lambda: on_floor(*instances(n_inst))),
                          ("growth: 1024 spheres on a plane", 1024, lambda: on_floor(*growth(1024)))):
        measure([(f"{name}, free way", n, make), (f"{name}, plain steps (free_way=False)", n, make)],
                extra=({}, {"free_way": False}))
    n_blend = 1000 if quick else 10 ** 4
    measure([(f"hard union of {n_blend} spheres in a slab (yardstick)", n_blend, lambda: blend_slab(n_blend, 0.0)),
             (f"smooth union (k 0.1) of the same {n_blend} spheres", n_blend, lambda: blend_slab(n_blend, 0.1))])
    measure([("molecule: 1001 atoms smooth-blended (k 0.04)", 1001, lambda: molecule(1001)),
             ("trees: 186 boxes, 62 trees of smooth and hard CSG", 186, lambda: trees(62))])
    n_mixed = 100 if quick else 5000
    measure([("mixed rotated capsules, cones, tori, boxes, spheres", n_mixed, lambda: mixed(n_mixed))])
    depth = 2000 if quick else 10 ** 5
    measure([(f"chain of {depth} {kind}s", depth, lambda kind=kind: chain(kind, depth))
             for kind in ("union", "translate", "rotate")])
    measure([("one node as both operands, 30 levels (2^30 paths)", 30, lambda: dag(30))])
    measure([(f"extruded polygon of {n} vertices", n, lambda n=n: polygon(n)) for n in ((500,) if quick else (2000, 10000))])
    if importlib.util.find_spec("fontTools") is not None:  # the text extra
        measure([(f"extruded text of {n} glyphs, fitted to the view", n, lambda n=n: text_page(n))
                 for n in ((1, 200) if quick else (1, 1000))])
        look = {"shadows": "soft", "ao": True}  # the default look: every shadow and AO sample meets the text too
        measure([("a plate, soft shadows and AO", 1, lambda: engraved_plate(False)),
                 ("the plate with 'sdfgl' engraved, soft shadows and AO", 2, lambda: engraved_plate(True))],
                extra=(look, look))
    return (f"Size {size[0]}x{size[1]}, shadows and AO off, frames interleaved within each group; 'build' is the Python "
            "that makes the scene, 'link' generating the source plus the driver's compile and link, 'first "
            "frame' adds llvmpipe's code generation; 'ratio' is to the group's first row; 'how' is the "
            "code/data choice in the shader source (grid_min: the fewest instances a union kept as data had "
            "to have).\n\n" + "\n".join(rows) + "\n\n" + run_structures(quick, size))


def run_structures(quick: bool, size: tuple[int, int] = (320, 240), seeds: tuple[int, ...] = (0, 1, 2)) -> str:
    """The acceleration structure table: the uniform grid (the default) against the
    bounding volume hierarchy (setting grid="bvh") on the growth scene kind over
    ``seeds`` and on the mixed scene, frames interleaved; wall and process CPU time per
    frame (llvmpipe draws on worker threads of this process; CPU time is the figure that
    a loaded machine disturbs least); return the markdown section."""
    from .bench import FrameTimer, Variant
    from .render import Renderer
    renderer = Renderer(budget=CacheBudget(programs=None))  # timings hold every variant's programs
    timer = FrameTimer(renderer, size)
    frames, warmup = (2, 1) if quick else (5, 2)
    sizes = (16, 64) if quick else (16, 256, 1024, 4096)
    scenes = [("growth", n, seed, lambda n=n, seed=seed: growth(n, seed)) for seed in seeds[:1 if quick else None]
              for n in sizes] + ([] if quick else [("mixed", 5000, 0, lambda: mixed(5000))])
    found: dict[tuple, dict] = {}
    vs = []
    for structure in ("grid", "bvh"):
        for kind, n, seed, make in scenes:
            scene, cam = make()
            v = Variant(kind, f"{n}", {**NO_SHADING, "grid": True if structure == "grid" else "bvh"}, scene, cam)
            link, first = timer.prepare(v)
            v.result.update(key=(kind, n, seed, structure), link=link, first=first, wall=[], cpu=[])
            vs.append(v)
    for rnd in range(warmup + frames):
        for v in vs:
            c0 = time.process_time()
            dt = timer.draw(v)
            if rnd >= warmup:
                v.result["wall"].append(1000 * dt)
                v.result["cpu"].append(1000 * (time.process_time() - c0))
    for v in vs:
        res = renderer.render(v.node, v.camera, size, outputs=("color", "steps"), **v.settings)
        found[v.result["key"]] = dict(wall=statistics.median(v.result["wall"]), cpu=statistics.median(v.result["cpu"]),
                                      steps=float(res.steps.mean()), link=v.result["link"], first=v.result["first"])
    rows = ["| scene | objects | structure | frame ms (wall) | CPU ms / frame | ratio to 16 (CPU) | steps/px | "
            "link ms | first frame ms |", "|---|---|---|---|---|---|---|---|---|"]
    for structure in ("grid", "bvh"):
        for kind, n, seed, _ in scenes:
            f = found[(kind, n, seed, structure)]
            base = found.get((kind, sizes[0], seed, structure)) if kind == "growth" else None
            ratio = f"{f['cpu'] / base['cpu']:.2f}" if base else "-"
            name = f"growth seed {seed}" if kind == "growth" else "mixed rotated primitives"
            rows.append(f"| {name} | {n} | {structure} | {f['wall']:.1f} | {f['cpu']:.1f} | {ratio} | {f['steps']:.2f} | "
                        f"{1000 * f['link']:.0f} | {1000 * f['first']:.0f} |")
    return (f"Acceleration structures, {size[0]}x{size[1]}, shadows and AO off; frames of every "
            "row interleaved; medians. The growth scenes of 16 objects are code under both (fewer than "
            "grid_min). 'CPU' is the process's CPU time per frame (all llvmpipe threads).\n\n" + "\n".join(rows))


if __name__ == "__main__":
    main()
