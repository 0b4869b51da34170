"""Animation timing: a turntable of the demo scene to MP4 and GIF, time per
frame against single render() calls of the same frames, and DistForge's save_frames.

    python benchmarks/animate_figures.py [--frames 120] [--size 640x360] [--rounds 2] [--out bench-out/animate]

Variants are interleaved round by round; medians over rounds are reported. DistForge
runs in a subprocess under a private Xvfb (it draws through a glfw window).
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import imageio_ffmpeg

import sdfgl as sg
from sdfgl.animate.paths import Turntable
from sdfgl.demo import demo_camera, demo_scene

HERE = Path(__file__).resolve().parent
SETTINGS = {"aa": 1, "shadows": "soft", "ao": True, "ground": True}  # `sdfgl render --demo` defaults


def turntable() -> Turntable:
    cam = demo_camera()
    return sg.turntable(distance=cam.distance, pitch=cam.pitch, target=cam.target, yaw=cam.yaw, fov=cam.fov)


def sdfgl_clip(out: Path, frames: int, size: tuple[int, int]) -> dict:
    res = sg.animate(demo_scene(), out, frames=frames, fps=30, camera=turntable(), size=size, **SETTINGS)
    return {"seconds": res.seconds, "per_frame_s": res.seconds / frames, "compiles": res.compiles,
            "render_median_s": statistics.median(res.render_s), "write_median_s": statistics.median(res.write_s)}


def single_renders(frames: int, size: tuple[int, int], every: int) -> float:
    """Mean time of one sg.render() (codegen, uniforms, draw, read-back) over every ``every``-th frame."""
    scene, path, times = demo_scene(), turntable(), []
    for i in range(0, frames, every):
        cam = path.camera(i / 30, frames / 30, scene)
        t0 = time.perf_counter()
        sg.render(scene, cam, size, **SETTINGS)
        times.append(time.perf_counter() - t0)
    return sum(times) / len(times)


def paired(out: Path, rounds: int, frames: int, size: tuple[int, int]) -> dict[str, list[float]]:
    """Per round and writer: a ``frames``-frame clip, then single render()s of the same frames right after;
    the ratio of their times per frame (pairs taken close in time cancel most of the machine's load drift)."""
    ratios: dict[str, list[float]] = {"mp4": [], "gif": []}
    for r in range(rounds):
        for kind in (("mp4", "gif") if r % 2 == 0 else ("gif", "mp4")):
            clip = sdfgl_clip(out / f"paired.{kind}", frames, size)["per_frame_s"]
            ratios[kind].append(clip / single_renders(frames, size, 1))
    return ratios


def distforge_clip(out: Path, frames: int, size: tuple[int, int], display: str) -> dict:
    r = subprocess.run([sys.executable, "-m", "sdfgl.peers.distforge_demo", str(out), str(frames), str(size[0]),
                        str(size[1])], env={**os.environ, "DISPLAY": display}, capture_output=True, text=True,
                       timeout=1800)
    if r.returncode != 0:
        raise RuntimeError(r.stderr[-2000:])
    d = json.loads(r.stdout.strip().splitlines()[-1])
    return {"seconds": d["seconds"], "per_frame_s": d["seconds"] / frames}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--frames", type=int, default=120)
    ap.add_argument("--size", default="640x360")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--every", type=int, default=4, help="single renders of every N-th frame")
    ap.add_argument("--out", default="bench-out/animate")
    ap.add_argument("--no-distforge", action="store_true")
    ap.add_argument("--paired", type=int, default=6, help="rounds of short clip / single-render pairs")
    ap.add_argument("--paired-frames", type=int, default=24)
    a = ap.parse_args()
    size = tuple(int(x) for x in a.size.split("x"))
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    xvfb = None
    if not a.no_distforge:
        sys.path.insert(0, str(HERE.parent))
        from tests.xserver import start_xvfb
        xvfb, display = start_xvfb()
    rows: dict[str, list[dict]] = {"mp4": [], "gif": [], "single": [], "distforge_mp4": []}
    sg.render(demo_scene(), demo_camera(), size, **SETTINGS)  # compile once: every variant draws warm
    try:
        for r in range(a.rounds):
            rows["mp4"].append(sdfgl_clip(out / "turntable.mp4", a.frames, size))
            rows["single"].append({"per_frame_s": single_renders(a.frames, size, a.every)})
            if xvfb:
                rows["distforge_mp4"].append(distforge_clip(out / "distforge.mp4", a.frames, size, display))
            rows["gif"].append(sdfgl_clip(out / "turntable.gif", a.frames, size))
            print(f"round {r + 1}: " + ", ".join(f"{k} {v[-1]['per_frame_s'] * 1000:.0f} ms/frame"
                                                 for k, v in rows.items() if v), flush=True)
    finally:
        if xvfb:
            xvfb.kill()
    pairs = paired(out, a.paired, a.paired_frames, size) if a.paired else {}
    n, secs = imageio_ffmpeg.count_frames_and_secs(str(out / "turntable.mp4"))
    reader = imageio_ffmpeg.read_frames(str(out / "turntable.mp4"))
    meta = next(reader)
    reader.close()
    med = {k: statistics.median(x["per_frame_s"] for x in v) for k, v in rows.items() if v}
    summary = {"frames": a.frames, "size": list(size), "settings": SETTINGS, "rounds": a.rounds,
               "load_average": os.getloadavg(), "median_per_frame_s": med,
               "mp4_read_back": {"frames": n, "seconds": secs, "size": list(meta["size"])},
               "mp4_bytes": (out / "turntable.mp4").stat().st_size, "gif_bytes": (out / "turntable.gif").stat().st_size,
               "ratio_mp4_to_single_render": med["mp4"] / med["single"],
               "ratio_gif_to_single_render": med["gif"] / med["single"],
               "paired_ratio_median": {k: statistics.median(v) for k, v in pairs.items()},
               "paired_ratios": pairs, "rows": rows}
    if "distforge_mp4" in med:
        summary["fps"] = {"sdfgl_mp4": 1 / med["mp4"], "sdfgl_gif": 1 / med["gif"],
                          "distforge_mp4": 1 / med["distforge_mp4"]}
    (out / "figures.json").write_text(json.dumps(summary, indent=2))
    print(json.dumps({k: v for k, v in summary.items() if k != "rows"}, indent=2))


if __name__ == "__main__":
    main()
