"""The frametime benchmark: speed beside error for every marching method and setting.

Frame times are wall-clock draws closed by ctx.finish() (GL timer queries are not
trusted on llvmpipe), variants interleaved round by round so drift cancels, reported
as medians, p95 and ratios. Errors come from the same shader against the float64
reference (sdfgl.reference). The full run adds a mesh as a field against libigl and
rasterisation (:mod:`sdfgl.bench_mesh_field`). Run it as ``sdfgl bench`` or
``python benchmarks/bench.py``.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

from .errors import ParameterError, SdfglError
from . import hardcases
from .camera import Camera
from .compiler.generate import generate
from .compiler.source import ShaderSource
from .compiler.analysis import max_steps_of, scene_frame
from .gl.cache import CacheBudget
from .gl.context import describe
from .nodes.base import IMPLICIT, Node
from .reference import Reference, compare, trace
from .render import Renderer, bind_image, coarse_source, draw_image, image_draws, shader_origin
from .settings import DISTANCE_METHODS, Settings


@dataclass
class Variant:
    """One shader to time: a scene with one set of settings."""

    scene: str
    label: str
    settings: dict
    node: Node
    camera: Camera
    times: list[float] = field(default_factory=list)
    result: dict = field(default_factory=dict)
    source: Callable[[ShaderSource], ShaderSource] | None = None  # rewrites the generated shader


class Progress:
    """A one-line progress bar on stderr (silent when stderr is not a terminal and quiet)."""

    def __init__(self, total: int, enabled: bool = True) -> None:
        self.total, self.done, self.enabled = max(total, 1), 0, enabled
        self.t0 = time.perf_counter()

    def step(self, what: str) -> None:
        self.done += 1
        if not self.enabled:
            return
        frac = self.done / self.total
        bar = "#" * int(30 * frac) + "-" * (30 - int(30 * frac))
        eta = (time.perf_counter() - self.t0) / frac * (1 - frac)
        sys.stderr.write(f"\r[{bar}] {self.done}/{self.total} eta {eta:4.0f}s {what[:40]:<40}")
        if self.done == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


class FrameTimer:
    """Times single draws of prepared programs on one renderer."""

    def __init__(self, renderer: Renderer, size: tuple[int, int], read_back: bool = False) -> None:
        self.r, self.size, self.read_back = renderer, size, read_back  # read_back: each draw reads its RGB back
        self.fbo = renderer.run(lambda: renderer.ctx.simple_framebuffer(size))

    def prepare(self, v: Variant) -> tuple[float, float]:
        """Compile v's program; return (link seconds, first-frame seconds)."""
        return self.r.run(self._prepare, v)

    def _prepare(self, v: Variant) -> tuple[float, float]:
        st = Settings.build(**v.settings)
        origin = shader_origin(v.node, v.camera.eye)
        t0 = time.perf_counter()
        source = generate(v.node, st, origin, projection=v.camera.projection)
        if v.source is not None:
            source = v.source(source)
        coarse = coarse_source(v.node, source, st.resolved(v.node.exactness), origin, v.camera.projection)
        image_draws(self.r.programs, source, coarse is not None)  # the link, timed here
        t1 = time.perf_counter()
        v.result["_source"], v.result["_prog"] = source, (origin, coarse)
        first = self.draw(v)
        return t1 - t0, first

    def draw(self, v: Variant) -> float:
        """Draw v once on the GL thread; return the seconds the draw took."""
        return self.r.run(self._draw, v)

    def _draw(self, v: Variant) -> float:
        source, (origin, coarse) = v.result["_source"], v.result["_prog"]
        t0 = time.perf_counter()
        # the coarse pass first and the image's programs of this frame, as render() draws them
        starts = None if coarse is None else self.r.coarse_pass(v.node, v.camera, self.size, coarse, origin)
        draws, _ = image_draws(self.r.programs, source, coarse is not None)
        bind_image(draws, v.node, v.camera, self.size, origin, self.r.data, starts=starts)
        self.fbo.use()
        self.r.ctx.viewport = (0, 0, *self.size)
        draw_image(self.r.ctx, draws, self.size)
        if self.read_back:
            v.result["_image"] = self.fbo.read(components=3)
        self.r.ctx.finish()
        dt = time.perf_counter() - t0
        if starts is not None:
            starts.release()
        return dt


def time_interleaved(timer: FrameTimer, variants: Sequence[Variant], frames: int, warmup: int,
                     progress: Progress) -> None:
    """Compile each variant, then draw all of them round-robin ``warmup + frames`` times."""
    for v in variants:
        link, first = timer.prepare(v)
        v.result.update(compile_s=link, first_frame_s=first)
        progress.step(f"compile {v.scene}/{v.label}")
    for rnd in range(warmup + frames):
        for v in variants:
            dt = timer.draw(v)
            if rnd >= warmup:
                v.times.append(dt)
        progress.step(f"round {rnd + 1}")
    for v in variants:
        ts = sorted(v.times)
        v.result.update(frame_ms_median=1000 * statistics.median(ts),
                        frame_ms_p95=1000 * ts[min(len(ts) - 1, int(round(0.95 * (len(ts) - 1))))])


def measure_errors(renderer: Renderer, v: Variant, ref: Reference, size: tuple[int, int]) -> None:
    """Steps statistics and errors against the reference for one variant."""
    res = renderer.render(v.node, v.camera, size, outputs=("color", "depth", "normal", "steps"), **v.settings)
    steps = res.steps.astype(np.float64)
    marched = steps > 0
    st = Settings.build(**v.settings)
    lo, hi, scale = scene_frame(v.node)
    limit = max_steps_of(st, scale, lo, hi)
    e = compare(res, ref)
    both = np.isfinite(res.depth) & ref.hit
    v.result.update(
        steps_mean=float(steps.mean()), steps_mean_marched=float(steps[marched].mean()) if marched.any() else 0.0,
        steps_p95=float(np.percentile(steps, 95)), steps_max=int(steps.max()),
        out_of_steps=float((steps >= limit).mean()),
        depth_abs_mse=float(np.mean(np.square(res.depth[both].astype(np.float64) - ref.t[both]))) if both.any() else 0.0,
        **e.as_dict())


# -- what to run -------------------------------------------------------------------------

METHOD_VARIANTS: dict[str, list[dict]] = {
    "sphere": [{"method": "sphere"}],
    "relaxed": [{"method": "relaxed"}],
    "enhanced": [{"method": "enhanced"}],
    "newton": [{"method": "newton"}],
    "forward_newton": [{"method": "forward_newton"}],
    "reference": [{"method": "reference"}],
}

FULL_EXTRA: list[dict] = [
    {"method": "sphere", "hit_scale": 0.1}, {"method": "sphere", "hit_scale": 0.5}, {"method": "sphere", "hit_scale": 1.0},
    {"method": "sphere", "hit": "absolute", "hit_scale": 1e-4},
    {"method": "relaxed", "omega": 1.2}, {"method": "relaxed", "omega": 1.9},
    {"method": "enhanced", "hit": "absolute", "hit_scale": 1e-4},
    {"method": "enhanced", "omega": 0.6}, {"method": "enhanced", "omega": 1.0},
    {"method": "enhanced", "hit_scale": 0.1}, {"method": "enhanced", "hit_scale": 0.5},
    {"method": "enhanced", "hit_scale": 1.0},
]

SEED_SCENES = ("rounded_box", "tunnel", "five_spheres", "product_union")
MORE_SCENES = ("grazing_sphere", "horizon_plane", "thin_shell", "twist", "repeat_boundary")

# The averages of Monzón González's thesis ("Modelado de geometría mediante Signed Distance Functions", Zaragoza 2021) (Tables 5.1-5.3) and medians over 17 scenes (Table 5.4):
# steps, time in seconds, squared depth error against Regular Marching.
SEED_TABLES = {
    "rounded_box": {"sphere": (13.772, 0.12, 4.43e-06), "enhanced": (9.38034, 0.12, 5.12e-06),
                    "newton": (238.188, 3.51, 16.742), "forward_newton": (27.4862, 0.62, 0.0928301),
                    "reference": (304.861, 1.08, 0.0)},
    "tunnel": {"sphere": (500, 2.77, 218650), "enhanced": (433.704, 3.44, 0.008832),
               "newton": (2, 0.06, 2.53e-05), "forward_newton": (31.0072, 0.52, 2.52e-05),
               "reference": (136.104, 0.54, 0.0)},
    "five_spheres": {"sphere": (12.4588, 0.12, 4.26e-07), "enhanced": (9.90928, 0.13, 0.030327),
                     "newton": (877.792, 21.48, 0.06056), "forward_newton": (181.529, 5.03, 2.04885),
                     "reference": (472.917, 2.62, 0.0)},
    "median of 17 scenes": {"sphere": (11.3928, 8.5711, 1.2533e-06), "enhanced": (8.50484, 0.127701, 5.12e-06),
                            "newton": (714.562, 21.4848, 0.01184), "forward_newton": (142.442, 12.3632, 0.00179),
                            "reference": (440.579, 2.62416, 0.0)},
}


def label_of(s: dict) -> str:
    extra = ",".join(f"{k}={v}" for k, v in s.items() if k != "method")
    return s["method"] + (f"[{extra}]" if extra else "")


def build_variants(scene_names: Sequence[str], full: bool) -> list[Variant]:
    out = []
    for name in scene_names:
        hc = hardcases.case(name)
        node, cam = hc.build()
        settings = [s for group in METHOD_VARIANTS.values() for s in group] + (FULL_EXTRA if full else [])
        for s in settings:
            if node.exactness == IMPLICIT and s["method"] in DISTANCE_METHODS:
                continue
            # the methods are compared marching: no closed-form shortcut for a lone sphere
            full_s = {"shadows": False, "ao": False, "max_dist": hc.max_dist, "analytic": False, **hc.settings, **s}
            if "method" in hc.settings:
                full_s["method"] = s["method"]
            out.append(Variant(name, label_of(s), full_s, node, cam))
    return out


def feature_variants() -> list[Variant]:
    """AA 1..4, shadows hard/soft and AO, each on its own, on the demo scene."""
    from .demo import demo_camera, demo_scene
    node, cam = demo_scene(), demo_camera()
    base = {"aa": 1, "shadows": False, "ao": False, "ground": True}
    toggles: list[tuple[str, dict]] = [("base (aa1, no shadows, no AO)", {})]
    toggles += [(f"aa{n}", {"aa": n}) for n in (2, 3, 4)]
    toggles += [("shadows hard", {"shadows": "hard"}), ("shadows soft", {"shadows": "soft"}), ("ao", {"ao": True}),
                ("all (aa2, soft, ao)", {"aa": 2, "shadows": "soft", "ao": True})]
    out = [Variant("demo", name, {**base, **t}, node, cam) for name, t in toggles]
    return out + look_variants(node, cam, base)


def look_variants(node: Node, cam: Camera, base: dict) -> list[Variant]:
    """The look's features on the demo scene: lights, materials, transparency, fog."""
    from .look import directional_light, point_light
    four = [directional_light((0.5, 0.7, 0.4), "#fff0dd", shadow="soft"), directional_light((-1, 0.5, -0.5), "#99aaff"),
            point_light((0, 3, 2), "orange", 2.0, range=3.0, shadow="hard"), directional_light((0, -1, 0), "#403020")]
    metal = node.material(metallic=0.6, roughness=0.3, emission=(0.02, 0.01, 0.0))
    rows = [("1 light, soft shadow", node, {"lights": [directional_light(shadow="soft")]}),
            ("4 lights (soft, hard, 2 unshadowed)", node, {"lights": four}),
            ("materials (metallic, roughness, emission)", metal, {}),
            ("alpha (transparent background)", node, {"alpha": True}),
            ("fog", node, {"fog": 10.0})]
    return [Variant("demo", name, {**base, **t}, n, cam) for name, n, t in rows]


# -- reports -------------------------------------------------------------------------------

def _fmt(x: float) -> str:
    return f"{x:.3g}" if isinstance(x, float) else str(x)


def methods_table(variants: Sequence[Variant]) -> str:
    rows = ["| scene | variant | frame ms (median / p95) | vs sphere | steps/px (mean / marched / p95 / max) "
            "| out of steps | depth err px (median / p99) | outliers | silhouette | normal deg (median) | compile ms |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    by_scene: dict[str, list[Variant]] = {}
    for v in variants:
        by_scene.setdefault(v.scene, []).append(v)
    for scene, vs in by_scene.items():
        base = next((v for v in vs if v.label == "sphere"), None)
        for v in vs:
            r = v.result
            ratio = f"{r['frame_ms_median'] / base.result['frame_ms_median']:.2f}" if base else "-"
            rows.append(
                f"| {scene} | {v.label} | {r['frame_ms_median']:.2f} / {r['frame_ms_p95']:.2f} | {ratio} | "
                f"{r['steps_mean']:.2f} / {r['steps_mean_marched']:.1f} / {r['steps_p95']:.0f} / {r['steps_max']} | "
                f"{100 * r['out_of_steps']:.2f}% | {r['depth_px_median']:.2g} / {r['depth_px_p99']:.2g} | "
                f"{r['depth_outliers']} | {r['silhouette_mismatch']} ({r['false_hits']}/{r['lost_hits']}) | "
                f"{r['normal_deg_median']:.2g} | {1000 * r['compile_s']:.0f} |")
    return "\n".join(rows)


def summary_table(variants: Sequence[Variant]) -> str:
    """One row per scene and method at default settings: steps and time as ratios to sphere tracing."""
    rows = ["| scene | method | steps/marched ray | steps vs sphere | frame ms | time vs sphere | depth err px "
            "(median) | depth outliers | silhouette mismatch | lost hits |", "|---|---|---|---|---|---|---|---|---|---|"]
    for v in variants:
        if "[" in v.label:
            continue
        r = v.result
        base = next((b.result for b in variants if b.scene == v.scene and b.label == "sphere"), None)
        sr = f"{r['steps_mean_marched'] / base['steps_mean_marched']:.2f}" if base and base['steps_mean_marched'] else "-"
        tr = f"{r['frame_ms_median'] / base['frame_ms_median']:.2f}" if base else "-"
        rows.append(f"| {v.scene} | {v.label} | {r['steps_mean_marched']:.2f} | {sr} | {r['frame_ms_median']:.2f} | "
                    f"{tr} | {r['depth_px_median']:.2g} | {r['depth_outliers']} | {r['silhouette_mismatch']} | "
                    f"{r['lost_hits']} |")
    return "\n".join(rows)


def seed_table(variants: Sequence[Variant]) -> str:
    rows = ["| scene | method | thesis steps | ours steps/marched ray | thesis time s | ours frame ms "
            "| thesis sq. depth err | ours mean sq. depth err | ours depth err px (median) |",
            "|---|---|---|---|---|---|---|---|---|"]
    for scene in SEED_SCENES:
        for v in variants:
            if v.scene != scene or "[" in v.label:
                continue
            t = SEED_TABLES.get(scene, {}).get(v.label)
            r = v.result
            ts = (f"{t[0]:g}", f"{t[1]:g}", f"{t[2]:.3g}") if t else ("-", "-", "-")
            rows.append(f"| {scene} | {v.label} | {ts[0]} | {r['steps_mean_marched']:.1f} | {ts[1]} | "
                        f"{r['frame_ms_median']:.2f} | {ts[2]} | {r['depth_abs_mse']:.3g} | {r['depth_px_median']:.2g} |")
    med = SEED_TABLES["median of 17 scenes"]
    rows.append("| thesis: median of 17 scenes | " + "; ".join(f"{m} {s[0]:g} steps" for m, s in med.items())
                + " | | | | | | | |")
    return "\n".join(rows)


def feature_table(variants: Sequence[Variant]) -> str:
    base = variants[0].result["frame_ms_median"]
    rows = ["| setting (demo scene) | frame ms (median / p95) | ratio to base | compile ms |", "|---|---|---|---|"]
    for v in variants:
        r = v.result
        rows.append(f"| {v.label} | {r['frame_ms_median']:.2f} / {r['frame_ms_p95']:.2f} | "
                    f"{r['frame_ms_median'] / base:.2f} | {1000 * r['compile_s']:.0f} |")
    return "\n".join(rows)


def pareto_plot(variants: Sequence[Variant], path: Path) -> None:
    """Frame time against depth error, one panel per scene; the Pareto front is joined."""
    try:
        import matplotlib
    except ImportError:
        raise SdfglError("the benchmark's plot needs matplotlib: pip install 'sdfgl[plots]'") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(dict.fromkeys(v.scene for v in variants))
    cols = min(3, len(scenes))
    rows = -(-len(scenes) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.2 * cols, 4.2 * rows), squeeze=False)
    for ax, scene in zip(axes.ravel(), scenes):
        vs = [v for v in variants if v.scene == scene]
        pts = [(v.result["frame_ms_median"], v.result["depth_px_p99"] + 1e-6, v.label) for v in vs]
        for x, y, lab in pts:
            ax.scatter(x, y, s=18)
            ax.annotate(lab, (x, y), fontsize=6, xytext=(3, 2), textcoords="offset points")
        front, best = [], float("inf")
        for x, y, _ in sorted(pts):
            if y < best:
                front.append((x, y))
                best = y
        ax.plot(*zip(*front), "k--", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(scene, fontsize=9)
        ax.set_xlabel("median frame time (ms)", fontsize=8)
        ax.set_ylabel("depth error p99 (pixel footprints)", fontsize=8)
    for ax in axes.ravel()[len(scenes):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _json_value(o: object) -> object:
    """JSON for what json does not know: numpy numbers, and lights (dataclasses) in settings."""
    from dataclasses import asdict, is_dataclass
    return asdict(o) if is_dataclass(o) and not isinstance(o, type) else float(o)  # type: ignore[arg-type]


SECTIONS = ("methods", "features", "model", "mesh", "mesh-field", "big", "png")


def run(quick: bool, size: tuple[int, int] | None, out: Path, progress: bool = True,
        scenes: Sequence[str] | None = None, sections: Sequence[str] | None = None) -> dict:
    """Run the benchmark, write bench.json, bench.md and pareto.png into ``out``; return the data.

    ``sections`` (of SECTIONS) picks the parts to run; the default is every part, except
    that the mesh-as-a-field rows run in the full benchmark only (their compiles would
    lengthen the quick one). Mesa's on-disk shader cache is turned off (before the context
    exists) so compile times are real compiles, not cache hits from an earlier run."""
    os.environ.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
    wanted = set(sections) if sections else set(SECTIONS) - ({"mesh-field"} if quick else set())
    unknown = wanted - set(SECTIONS)
    if unknown:
        raise ParameterError(f"bench: unknown section(s) {', '.join(sorted(unknown))}; "
                             f"choose from {', '.join(SECTIONS)}")
    size = size or ((160, 120) if quick else (400, 300))
    frames, warmup = (3, 1) if quick else (9, 2)
    names = list(scenes) if scenes else (list(SEED_SCENES) + ([] if quick else list(MORE_SCENES)))
    variants = build_variants(names, full=not quick) if "methods" in wanted else []
    features = feature_variants() if "features" in wanted else []
    renderer = Renderer(budget=CacheBudget(programs=None))  # timings hold every variant's program
    md_parts = [f"Machine: {platform.machine()}, {describe(renderer.ctx)}; size {size[0]}x{size[1]}, "
                f"{frames} timed frames after {warmup} warm-up, variants interleaved."]
    data: dict = {"size": size, "frames": frames, "warmup": warmup, "gl": describe(renderer.ctx)}
    small = (160, 120) if quick else (320, 240)
    if variants:
        refs: dict[str, Reference] = {}
        bar = Progress(len(variants) * 2 + (warmup + frames) * 2 + len(names), progress)
        for name in names:
            hc = hardcases.case(name)
            node, cam = hc.build()
            refs[name] = trace(node, cam, size, max_dist=hc.max_dist)
            bar.step(f"reference {name}")
        time_interleaved(FrameTimer(renderer, size), variants, frames, warmup, bar)
        for v in variants:
            measure_errors(renderer, v, refs[v.scene], size)
            bar.step(f"errors {v.scene}/{v.label}")
        md_parts += ["## Summary: default settings of each method\n\n" + summary_table(variants),
                     "## Methods and settings: speed and error\n\n" + methods_table(variants),
                     "## The tables of Monzón González's thesis beside ours\n\n" + seed_table(variants)]
        data["variants"] = [{"scene": v.scene, "label": v.label, "settings": v.settings,
                             **{k: val for k, val in v.result.items() if not k.startswith("_")}} for v in variants]
    if features:
        time_interleaved(FrameTimer(renderer, size), features, frames, warmup, Progress(0, False))
        md_parts.append("## Cost of each feature #define\n\n" + feature_table(features))
        data["features"] = [{"label": v.label, "settings": v.settings,
                             **{k: val for k, val in v.result.items() if not k.startswith("_")}} for v in features]
    if "model" in wanted:
        from .bench_model import run_model, run_whole
        md_parts.append("## Model only what a scene needs\n\n" + run_model(
            small, min(frames, 5), warmup, (16, 64, 256) if quick else (16, 64, 256, 1024), progress))
        whole = run_whole((320, 180) if quick else (1280, 720), min(frames, 7), warmup)
        if whole:
            md_parts.append("## Against whole shaders written by hand\n\n" + whole)
    if "big" in wanted:
        from .bench_big import run_big, run_phases
        from .bench_build import run_build
        md_parts.append("## Big scenes\n\n" + run_big(quick, small) + "\n\n" + run_phases(quick, small) + "\n\n"
                        + run_build(quick))
    if "mesh" in wanted:
        from .mesh.bench import run_mesh
        mesh_md, data["mesh"] = run_mesh(2 ** 18 if quick else 2 ** 22, 1 if quick else 3, None if quick else 1024)
        md_parts.append("## Mesh export against fogleman/sdf and DistForge\n\n" + mesh_md)
    if "mesh-field" in wanted:
        from .bench_mesh_field import run_mesh_field
        field_md, data["mesh_field"] = run_mesh_field(quick, renderer)
        md_parts.append(f"## A mesh as a field against libigl and rasterisation\n\n{field_md}")
    if "png" in wanted:
        from .bench_png import run_png
        png_md, data["png"] = run_png(quick)
        md_parts.append(f"## A PNG of the demo scene against DistForge\n\n{png_md}")

    out.mkdir(parents=True, exist_ok=True)
    md = "\n\n".join(md_parts)
    written = [out / "bench.md", out / "bench.json"]
    (out / "bench.md").write_text(md + "\n")
    (out / "bench.json").write_text(json.dumps(data, indent=1, default=_json_value))
    if variants:
        pareto_plot(variants, out / "pareto.png")
        written.append(out / "pareto.png")
    print(md)
    print(f"\nwrote {', '.join(str(w) for w in written)}")
    return data


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--quick", action="store_true", help="small size, few frames, the thesis scenes only")
    p.add_argument("--size", type=lambda s: tuple(int(x) for x in s.lower().split("x")), default=None,
                   help="WIDTHxHEIGHT (default 400x300, 160x120 with --quick)")
    p.add_argument("--out", type=Path, default=Path("bench-out"), help="output folder (default bench-out)")
    p.add_argument("--scenes", nargs="*", help="hard-case names to run (default: the thesis scenes, and more)")
    p.add_argument("--sections", nargs="*", choices=SECTIONS, metavar="SECTION",
                   help=f"parts to run, of {', '.join(SECTIONS)} (default: all; mesh-field in the full run only)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def main(argv: Sequence[str] | None = None, run_fn: Callable[..., dict] = run) -> int:
    p = argparse.ArgumentParser(prog="sdfgl bench", description=__doc__.split("\n")[0])
    add_arguments(p)
    a = p.parse_args(argv)
    run_fn(a.quick, a.size, a.out, not a.no_progress, a.scenes, a.sections)
    return 0
