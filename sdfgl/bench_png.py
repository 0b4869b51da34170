"""Benchmark rows of a PNG of the demo scene, sdfgl against DistForge, each in a fresh process.

Both draw the demo scene (sdfgl.demo; DistForge's copy is sdfgl.peers.distforge_demo) with soft
shadows, ambient occlusion and a ground, one sample a pixel, and write a PNG:

- the save call in its process: sdfgl's ``render(...).save(path)`` (:func:`main`, run as
  ``python -m sdfgl.bench_png OUT W H``), DistForge's ``save_frame`` (its glfw window on a
  private Xvfb display), both including the context, the compile, the draw, the read-back and
  the encoding;
- the whole process: ``sdfgl render --demo -o OUT --size WxH --aa 1`` against
  ``python -m sdfgl.peers.distforge_demo OUT 1 W H``, start to exit.

Runs interleave round by round, first with Mesa's shader cache off, then with a private one
filled by an untimed round; the rows report medians and the ratios sdfgl / DistForge.
DistForge is a peer, not a dependency: where it is not installed (or no Xvfb can start) its
rows are skipped with a note.
"""
from __future__ import annotations

import json
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from .bench_process import fresh_process, last_json
from .extras import installed
from .xdisplay import start_xvfb, stop_xvfb

FULL = {"size": (1920, 1080), "rounds": 3}
QUICK = {"size": (480, 270), "rounds": 1}
"""The sizes of the full bench and of ``--quick``."""

TIMEOUT_S = 600
CACHES = {"cold": {"MESA_SHADER_CACHE_DISABLE": "true"},
          "warm": {"MESA_SHADER_CACHE_DISABLE": "false", "MESA_SHADER_CACHE_DIR": "TMP/mesa-cache"}}
"""Mesa's on-disk shader cache for each kind of run (TMP: the run's own temporary folder)."""


def _sdfgl_cli() -> list[str]:
    """The ``sdfgl`` command of this interpreter."""
    beside = Path(sys.executable).with_name("sdfgl")
    return [str(beside)] if beside.exists() else [sys.executable, "-m", "sdfgl"]


def run_png(quick: bool) -> tuple[str, dict[str, Any]]:
    """The PNG rows (sizes :data:`FULL` or :data:`QUICK`): (markdown, data)."""
    sizes = QUICK if quick else FULL
    w, h = sizes["size"]
    notes: list[str] = []
    runs: dict[str, list[float]] = {}
    xvfb, display = None, ""
    if not installed("distforge"):
        notes.append("DistForge skipped: not installed (pip install distforge)")
    else:
        xvfb, display = start_xvfb(f"{w}x{h}x24")
        if xvfb is None:
            notes.append(f"DistForge skipped: it needs a display and {display}")
    with tempfile.TemporaryDirectory() as d:
        out = str(Path(d) / "frame.png")
        jobs: dict[str, tuple[list[str], dict[str, str], str | None]] = {
            "sdfgl call": ([sys.executable, "-m", "sdfgl.bench_png", out, str(w), str(h)], {}, "seconds"),
            "sdfgl process": (_sdfgl_cli() + ["render", "--demo", "-o", out, "--size", f"{w}x{h}", "--aa", "1"], {}, None),
        }
        if xvfb is not None:
            peer = [sys.executable, "-m", "sdfgl.peers.distforge_demo", out, "1", str(w), str(h)]
            jobs["DistForge call"] = (peer, {"DISPLAY": display}, "seconds")
            jobs["DistForge process"] = (peer, {"DISPLAY": display}, None)
        try:
            for cache, cache_env in CACHES.items():
                cache_env = {k: v.replace("TMP", d) for k, v in cache_env.items()}
                rounds = sizes["rounds"] + (1 if cache == "warm" else 0)  # a warm cache's first round fills it
                for r in range(rounds):
                    for name, (cmd, env, key) in jobs.items():
                        got = fresh_process(cmd, {**env, **cache_env}, TIMEOUT_S)
                        if isinstance(got, str):
                            notes.append(f"{name} {got}")
                        elif not (cache == "warm" and r == 0):
                            wall, stdout = got
                            runs.setdefault(f"{name} {cache}", []).append(
                                float(last_json(stdout)[key]) if key else wall)
        finally:
            if xvfb is not None:
                stop_xvfb(xvfb)
    med = {name: statistics.median(ts) for name, ts in runs.items()}
    lines = ["| measure | shader cache | sdfgl (s) | DistForge (s) | sdfgl / DistForge |", "|---|---|---:|---:|---:|"]
    for cache in CACHES:
        for what, label in (("call", "save call in its process"), ("process", "whole process")):
            ours, theirs = med.get(f"sdfgl {what} {cache}"), med.get(f"DistForge {what} {cache}")
            cells = [f"{x:.3f}" if x is not None else "-" for x in (ours, theirs)]
            ratio = f"{ours / theirs:.2f}" if ours is not None and theirs is not None else "-"
            lines.append(f"| {label} | {cache} | {cells[0]} | {cells[1]} | {ratio} |")
    md = (f"`sdfgl bench --sections png`: each tool writes the demo scene as a {w}x{h} PNG (soft shadows, AO, "
          f"ground, 1 sample a pixel) in a fresh process; the runs take turns, {sizes['rounds']} times, and the "
          f"table gives medians. A cold shader cache is a first run (Mesa's on-disk cache off: every program is "
          f"compiled, and llvmpipe generates its machine code at the first draw); a warm one follows a run with "
          f"the same shaders, as repeated renders of a scene do.\n\n" + "\n".join(lines))
    if notes:
        md += "\n\n" + "\n".join(f"- {n}" for n in dict.fromkeys(notes))
    return md, {"size": [w, h], "rounds": sizes["rounds"], "runs_s": runs, "median_s": med, "notes": notes}


def main() -> None:
    """``python -m sdfgl.bench_png OUT W H``: render the demo scene at W x H and save it as OUT;
    print {"seconds": the render-and-save call}."""
    out, w, h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    from .demo import demo_camera, demo_scene
    from .render import render
    scene, cam = demo_scene(), demo_camera()
    t0 = time.perf_counter()
    render(scene, cam, (w, h), aa=1, shadows="soft", ao=True, ground=True).save(out)
    print(json.dumps({"seconds": time.perf_counter() - t0}))


if __name__ == "__main__":
    main()
