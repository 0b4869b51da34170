"""Compiles off the window's loop: the window answers input while a big program compiles."""
import json
import os
import statistics
import subprocess
import sys
import time

import pytest

from .test_viewer import display  # noqa: F401 - the Xvfb fixture
from .xserver import Driver

pytestmark = pytest.mark.window

# 256 primitives written out as code (grid=False), so the program is big and slow to build
BIG = """import sdfgl as sg
import numpy as np
rng = np.random.default_rng(7)
scene = sg.union(*[sg.sphere(0.08 + 0.06 * rng.random()).translate(tuple(rng.uniform(-1.5, 1.5, 3)))
                   for _ in range(256)], k=0.05).color(0.8, 0.5, 0.3)
settings = {"grid": False, "shadows": False, "ao": False}
camera = sg.OrbitCamera(distance=14, yaw=30, pitch=20)  # small on screen: cheap frames
"""


def open_viewer(display, tmp_path, text, size="64x48", extra=()):
    scene = tmp_path / "scene.py"
    scene.write_text(text)
    state = tmp_path / "state.json"
    drv = Driver(display, state)
    drv.env["MESA_SHADER_CACHE_DISABLE"] = "true"  # every compile is a real one, run after run
    proc = subprocess.Popen([sys.executable, "-m", "sdfgl.cli", "view", str(scene), "--size", size,
                             "--state-file", str(state), "--max-samples", "2", *extra], env=drv.env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    drv.find_window(timeout=60)
    return drv, proc


def latencies(sends: list[float], log: list) -> list[float]:
    """For each input sent at wall time t: time until the first present showing a new camera yaw."""
    out = []
    for t in sends:
        before = [yaw for (w, yaw, _) in log if w <= t]
        if not before:
            continue  # sent before the oldest logged frame
        after = [(w, yaw) for (w, yaw, _) in log if w > t and yaw != before[-1]]
        if after:
            out.append(after[0][0] - t)
    return out


def test_window_answers_input_during_a_slow_compile(display, tmp_path):
    drv, proc = open_viewer(display, tmp_path, BIG)
    try:
        s0 = drv.wait_for(lambda s: s["samples"] >= 1 and not s["compiling"], timeout=180, what="the first image")
        assert s0["compiles"] == 1 and s0["error"] == ""
        # orbit once first: llvmpipe builds the shown program's code for the moving (low-resolution)
        # target at its first such draw, on the window's thread; that is not the compile measured here
        drv.drag(1, 32, 24, 6, 0, steps=3)
        drv.wait_for(lambda s: not s["moving"] and s["samples"] >= 1, timeout=180, what="a still image")
        drv.key("s")  # shadows: a new 256-primitive program, compiled by the worker
        drv.wait_for(lambda s: s["compiling"], what="the compile to start")
        sends = []
        drv.xdo("mousemove", "--window", drv.window, "32", "24", "mousedown", "1")
        x = 32
        while True:
            x += 2
            sends.append(time.time())
            drv.xdo("mousemove", "--window", drv.window, str(x), "24")
            time.sleep(0.04)
            st = drv.state()
            if not st["compiling"] or len(sends) > 400:
                break
        drv.xdo("mouseup", "1")
        st = drv.wait_for(lambda s: not s["compiling"] and s["compiles"] == 2, timeout=180, what="the compile")
        assert st["settings"]["shadows"] == "hard" and st["error"] == ""
        compile_s = st["compile_log"][-1]["s"]
        log = [e for e in st["present_log"]]
        during = [t for t in sends if any(c for (w, _, c) in log if w > t)]  # sent while still compiling
        lat = latencies(during, log)
        frames = [w for (w, _, c) in log if c]
        gaps = [b - a for a, b in zip(frames, frames[1:])]
        end = st["compile_log"][-1]["wall_end"]
        after = [w for (w, _, _) in log if w >= end]
        # the new program's first frame: llvmpipe builds its machine code then, on the window's thread
        first_frame = (after[0] - max([w for (w, _, _) in log if w < end] or [end])) if after else None
        figures = {"compile_s": compile_s, "inputs_during_compile": len(during), "answered": len(lat),
                   "latency_median_ms": 1000 * statistics.median(lat) if lat else None,
                   "latency_max_ms": 1000 * max(lat) if lat else None,
                   "frames_during_compile": len(frames),
                   "frame_gap_max_ms": 1000 * max(gaps) if gaps else None,
                   "gap_at_new_program_ms": 1000 * first_frame if first_frame is not None else None,
                   "worker": st["compile_log"][-1]}
        print("async compile figures:", json.dumps(figures))
        w = st["compile_log"][-1]
        t0 = w["wall_start"]
        big = [(round(a - t0, 2), round(b - a, 2)) for a, b in zip(frames, frames[1:]) if b - a > 0.2]
        print("phases", {k: round(v, 2) for k, v in w.items() if k.endswith("_s")}, "big gaps (start, len)", big)
        out = os.environ.get("SDFGL_FIGURES")
        if out:
            with open(out, "a") as fh:
                fh.write(json.dumps(figures) + "\n")
        # the camera moved on screen, many times, while the program was being built
        assert len(lat) >= 3 and len(frames) >= 3
        # answering input never waited for the compile
        assert statistics.median(lat) < 0.25 * compile_s
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)


def test_failed_compile_keeps_the_last_good_program(display, tmp_path):
    good = "import sdfgl as sg\nscene = sg.sphere(1).color(0.2, 0.6, 0.9)\n"
    drv, proc = open_viewer(display, tmp_path, good)
    try:
        s0 = drv.wait_for(lambda s: s["samples"] >= 1 and not s["compiling"], timeout=60, what="the first image")
        # the scene file loads, but its program cannot be built (the worker's codegen refuses it)
        (tmp_path / "scene.py").write_text("import sdfgl as sg\nscene = sg.sphere(1e39)\n")
        s1 = drv.wait_for(lambda s: s["error"] != "", timeout=60, what="the compile error")
        assert "does not fit in a float32" in s1["error"] and "sphere" in s1["error"]
        assert s1["scene"] == s0["scene"] and s1["reloads"] == 0 and not s1["compiling"]
        drv.drag(1, 32, 24, 20, 0)  # the last good program still draws
        drv.wait_for(lambda s: s["yaw"] != s0["yaw"] and s["samples"] >= 1, what="a redraw with the old program")
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)
