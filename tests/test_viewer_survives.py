"""The window never dies: every failure of a reload, compile, render, screenshot or input is shown
in the window (the state file's 'error' is the overlay's text) and the last good scene stays."""
import time

import pytest

from .test_viewer import SCENE_A, display, viewer  # noqa: F401 - fixtures

pytestmark = pytest.mark.window


def _write(path, text: str) -> None:
    time.sleep(0.05)  # a new mtime
    path.write_text(text)


def _failure_keeps_scene(drv, proc, scene, text: str, expect: str, good: dict) -> dict:
    _write(scene, text)
    st = drv.wait_for(lambda s: expect in s["error"], what=f"the error {expect!r}")
    assert proc.poll() is None, "the viewer exited"
    assert st["scene"] == good["scene"]
    # the window still draws: a key toggles and a frame follows
    frames = st["frames"]
    drv.key("o")
    drv.wait_for(lambda s: s["frames"] > frames, what="a frame after the error")
    drv.key("o")
    return st


@pytest.mark.slow
def test_reload_failures_of_any_kind_leave_the_window_running(viewer):
    drv, proc, scene, _ = viewer
    good = drv.state()
    # sympy cannot print gamma() as GLSL: not one of our error classes
    _failure_keeps_scene(drv, proc, scene, "import sdfgl as sg\nscene = sg.implicit('gamma(x) + y - 1')\n"
                         "settings = {'method': 'newton', 'ao': False}\n", "gamma", good)
    # a scene file that exits is reported, not obeyed
    _failure_keeps_scene(drv, proc, scene, "import sys\nsys.exit(3)\n", "sys.exit(3)", good)
    # Python's recursion limit hit while compiling (any exception type reaches the overlay)
    _failure_keeps_scene(drv, proc, scene, "import sdfgl as sg\n"
                         "class Deep(sg.Node):\n"
                         "    kind = 'deep'\n"
                         "    exactness = 'exact'\n"
                         "    bounds = sg.sphere(1).bounds\n"
                         "    def _emit(self, em, p):\n"
                         "        return self._emit(em, p)\n"
                         "scene = Deep()\n", "recursion", good)
    _write(scene, SCENE_A)
    drv.wait_for(lambda s: s["error"] == "" and s["reloads"] == good["reloads"] + 1, what="recovery")


@pytest.mark.slow
def test_reloaded_settings_apply(viewer):
    drv, proc, scene, _ = viewer
    assert drv.state()["settings"]["shadows"] == "soft"
    _write(scene, SCENE_A + "settings = {'shadows': False, 'aa': 2}\n")
    st = drv.wait_for(lambda s: s["reloads"] == 1, what="a reload")
    assert st["settings"]["shadows"] is False and st["settings"]["aa"] == 2 and st["error"] == ""
    drv.key("s")  # a key toggle survives a reload that does not change that setting
    drv.wait_for(lambda s: s["settings"]["shadows"] == "hard", what="shadows hard")
    _write(scene, SCENE_A + "settings = {'shadows': False, 'aa': 3}\n")
    st = drv.wait_for(lambda s: s["reloads"] == 2, what="a second reload")
    assert st["settings"]["aa"] == 3 and st["settings"]["shadows"] == "hard"
    _write(scene, SCENE_A + "settings = {'aa': 0}\n")  # an invalid setting is an error, not a crash
    st = drv.wait_for(lambda s: "'aa'" in s["error"], what="the settings error")
    assert st["settings"]["aa"] == 3 and proc.poll() is None


def test_unwritable_screenshot_dir_is_reported(viewer):
    drv, proc, _, tmp = viewer
    (tmp / "shots").write_text("a file where the screenshot folder should be")
    drv.key("p")
    st = drv.wait_for(lambda s: "cannot write screenshots" in s["error"], what="the screenshot error")
    assert proc.poll() is None and st["screenshots"] == []


@pytest.mark.slow
def test_zoom_is_clamped_to_the_scene_size(viewer):
    drv, proc, _, _ = viewer
    d0 = drv.state()["distance"]
    drv.xdo("click", "--repeat", "400", "--delay", "2", "--window", drv.window, "5")  # wheel down: out
    st = drv.wait_for(lambda s: not s["moving"] and s["samples"] >= 1 and s["distance"] > 20 * d0,
                      what="zoomed out")
    assert st["distance"] <= 100 * d0 * 1.5 and st["error"] == ""
    drv.xdo("click", "--repeat", "600", "--delay", "2", "--window", drv.window, "4")  # wheel up: in
    st = drv.wait_for(lambda s: not s["moving"] and s["samples"] >= 1 and s["distance"] < 1e-2 * d0,
                      what="zoomed in")
    assert st["distance"] >= 1e-4 * d0 * 0.5 and st["error"] == "" and proc.poll() is None
