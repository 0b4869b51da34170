"""Compiles off the window's loop: the window answers input while a big program compiles."""
import json
import os
import statistics
import time

import pytest

from .test_viewer import display  # noqa: F401 - the Xvfb fixture
from .xserver import Driver, XTest

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
    proc = drv.launch(str(scene), "--size", size, "--max-samples", "2", *extra)
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


def pct(values: list[float], q: float) -> float:
    """The q-th percentile (nearest rank) of ``values``."""
    v = sorted(values)
    return v[min(len(v) - 1, max(0, round(q / 100 * len(v)) - 1))]


@pytest.mark.slow
def test_window_answers_input_during_a_slow_compile(display, tmp_path):
    """Input-to-redraw latency over a whole 256-primitive compile: codegen, link, llvmpipe's machine-code
    build at the first draw (the render thread's warm-up draw), and the switch to the new program."""
    drv, proc = open_viewer(display, tmp_path, BIG)
    try:
        s0 = drv.wait_for(lambda s: s["samples"] >= 1 and not s["compiling"], timeout=180, what="the first image")
        assert s0["compiles"] == 1 and s0["error"] == ""
        drv.key("s")  # shadows: a new 256-primitive program, built by the idle render thread
        drv.wait_for(lambda s: s["compiling"], what="the compile to start")
        sends, done_at = [], None
        geo = dict(line.split("=") for line in drv.xdo("getwindowgeometry", "--shell", drv.window).split())
        wx, wy = int(geo["X"]), int(geo["Y"])
        drv.xdo("mousemove", "--window", drv.window, "32", "24", "mousedown", "1")
        xt = XTest(display)
        x = 32
        try:
            while len(sends) < 2000:
                x = 32 + (x - 30) % 24  # to and fro: every move changes the yaw
                sends.append(time.time())
                xt.move(wx + x, wy + 24)
                time.sleep(0.06)
                if len(sends) % 5 == 0 and done_at is None and not drv.state()["compiling"]:
                    done_at = time.time()
                if done_at is not None and time.time() - done_at > 1.5:  # and on through the switch
                    break
        finally:
            xt.close()
            drv.xdo("mouseup", "1")
        st = drv.wait_for(lambda s: not s["compiling"] and s["compiles"] == 2, timeout=180, what="the compile")
        assert st["settings"]["shadows"] == "hard" and st["error"] == ""
        w = st["compile_log"][-1]
        log = st["present_log"]
        sent = [t for t in sends if t > log[0][0]]  # the log keeps the newest presents
        lat = latencies(sent, log)
        t0 = w["wall_start"]
        linked = t0 + w["codegen_s"] + w["link_s"]
        phase = {"link": [t for t in sent if t < linked], "warm-up": [t for t in sent if linked <= t < w["wall_end"]],
                 "after": [t for t in sent if t >= w["wall_end"]]}
        figures = {"compile_s": w["s"], "phases_s": {k: round(v, 3) for k, v in w.items() if k.endswith("_s")},
                   "inputs": len(sent), "answered": len(lat),
                   "latency_ms": {"median": 1000 * statistics.median(lat), "p90": 1000 * pct(lat, 90),
                                  "max": 1000 * max(lat)},
                   "median_ms_by_phase": {k: (1000 * statistics.median(x) if (x := latencies(v, log)) else None)
                                          for k, v in phase.items()},
                   "inputs_by_phase": {k: len(v) for k, v in phase.items()},
                   "load": os.getloadavg()[0]}
        print("async compile figures:", json.dumps(figures))
        out = os.environ.get("SDFGL_FIGURES")
        if out:
            with open(out, "a") as fh:
                fh.write(json.dumps(figures) + "\n")
        # inputs were sent through the link, the machine-code build and the switch, and nearly all answered
        assert all(len(v) >= 2 for v in phase.values()), figures
        assert len(lat) >= 0.9 * len(sent)
        # the bound: redraws follow input within 100 ms (median; the p90 and the maximum are
        # printed: on this shared 2-core machine a busy neighbour can delay any one frame)
        assert statistics.median(lat) < 0.1, figures
        if figures["load"] < (os.cpu_count() or 1):  # a machine not shared with other work: 9 in 10 inputs too
            assert figures["latency_ms"]["p90"] < 100, figures  # (idle here: p90 22-24 ms, median 20 ms)
        # no phase of the compile stalls the window (the first draw of the new program used to take seconds)
        assert max(m for m in figures["median_ms_by_phase"].values() if m is not None) < 100, figures
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
        (tmp_path / "scene.py").write_text("import sdfgl as sg\nscene = sg.sphere(sg.param(1e-10) * 1e39)\n")
        s1 = drv.wait_for(lambda s: s["error"] != "", timeout=60, what="the compile error")
        assert "does not fit in a float32" in s1["error"] and "sphere" in s1["error"]
        assert s1["scene"] == s0["scene"] and s1["reloads"] == 0 and not s1["compiling"]
        drv.drag(1, 32, 24, 20, 0)  # the last good program still draws
        drv.wait_for(lambda s: s["yaw"] != s0["yaw"] and s["samples"] >= 1, what="a redraw with the old program")
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)
