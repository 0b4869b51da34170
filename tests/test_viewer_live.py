"""The viewer under Xvfb driven by OSC over loopback UDP: a message moves the parameter on screen, no recompile."""
import json
import os
import subprocess
import sys

import pytest

from .test_cli_extras import refused, run_without
from .test_viewer import display  # noqa: F401 - the Xvfb fixture
from .xserver import Driver

pytest.importorskip("pythonosc")
pytest.importorskip("mido")
from sdfgl.live import send_osc  # noqa: E402 - after the skip: needs the [live] extra

pytestmark = pytest.mark.window

SCENE = """import sdfgl as sg
r = sg.param(0.6, name="radius", range=(0.3, 1.2))
scene = sg.sphere(r).color(0.9, 0.3, 0.2)
settings = {"shadows": False, "ao": False}
camera = sg.OrbitCamera(distance=5, yaw=0, pitch=0)
"""
BINDINGS = {"version": 1, "bindings": [{"param": "radius", "osc": "/radius"},
                                       {"param": "radius", "osc": "/knob", "normalized": True}]}
W, H = 820, 480


def still(drv, pred, what):
    return drv.wait_for(lambda s: not s["compiling"] and s["samples"] >= 2 and pred(s), timeout=60, what=what)


@pytest.mark.slow
def test_osc_moves_the_displayed_parameter_without_a_new_program_and_learn_binds(display, tmp_path):  # noqa: F811
    (tmp_path / "scene.py").write_text(SCENE)
    (tmp_path / "live.json").write_text(json.dumps(BINDINGS))
    drv = Driver(display, tmp_path / "state.json")
    proc = drv.launch(str(tmp_path / "scene.py"), "--size", f"{W}x{H}", "--max-samples", "2",
                      "--osc", "0", "--bindings", str(tmp_path / "live.json"))
    try:
        s0 = still(drv, lambda s: s["live"].get("osc_port") and s["panel"].get("rects"), "the first image")
        port = s0["live"]["osc_port"]
        assert s0["live"]["bindings"] == ["/radius -> radius", "/knob -> radius"]
        send_osc("/radius", 1.0, port=port)
        s1 = still(drv, lambda s: s["panel"]["params"]["radius"] == pytest.approx(1.0), "the OSC value")
        assert s1["compiles"] == s0["compiles"] and s1["param_edits"] > s0["param_edits"]
        send_osc("/knob", 2.0, port=port)          # normalized, clamped to 1: the top of the range
        still(drv, lambda s: s["panel"]["params"]["radius"] == pytest.approx(1.2), "the clamped value")
        # the panel's learn button: the next OSC address sent is bound to the parameter
        x0, y0, x1, y1 = s1["panel"]["rects"]["learn:radius"]
        drv.xdo("mousemove", "--window", drv.window, str(int((x0 + x1) / 2)), str(int((y0 + y1) / 2)), "click", "1")
        drv.wait_for(lambda s: s["live"]["learning"] == "radius", what="learning")
        send_osc("/fader/3", 0.4, port=port)
        s3 = still(drv, lambda s: "/fader/3 -> radius" in s["live"]["bindings"]
                   and s["panel"]["params"]["radius"] == pytest.approx(0.4), "the learned binding")
        assert s3["live"]["learning"] is None and s3["compiles"] == s0["compiles"]
        x0, y0, x1, y1 = s3["panel"]["rects"]["save bindings"]
        drv.xdo("mousemove", "--window", drv.window, str(int((x0 + x1) / 2)), str(int((y0 + y1) / 2)), "click", "1")
        drv.wait_for(lambda s: s["panel"]["message"].startswith("saved"), what="the saved bindings")
        saved = json.loads((tmp_path / "live.json").read_text())
        assert saved["bindings"][-1] == {"param": "radius", "osc": "/fader/3"}
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)


def test_a_bad_bindings_file_stops_the_viewer_before_a_window_opens(tmp_path):
    (tmp_path / "scene.py").write_text(SCENE)
    bad = tmp_path / "live.json"
    bad.write_text(json.dumps({"version": 1, "bindings": [{"param": "size", "osc": "/size"}]}))
    r = subprocess.run([sys.executable, "-m", "sdfgl.cli", "view", str(tmp_path / "scene.py"), "--bindings", str(bad)],
                       capture_output=True, text=True, timeout=120, env={k: v for k, v in os.environ.items() if k != "DISPLAY"})
    assert r.returncode != 0
    assert f"{bad}: bindings[0]: no live parameter named 'size'" in r.stderr, r.stderr


def test_view_with_osc_but_without_python_osc_names_the_extra():
    r, _ = run_without("pythonosc", "view", "--demo", "--osc", "9000")
    assert refused(r, "pip install 'sdfgl[live]'") and "pythonosc" in r.stderr, r.stderr
    r, _ = run_without("rtmidi", "view", "--demo", "--midi", "")
    assert refused(r, "pip install 'sdfgl[live]'") and "rtmidi" in r.stderr, r.stderr
