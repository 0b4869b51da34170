"""Scene files loaded in a child process with a time limit (what the viewer's reload uses)."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import sdfgl as sg
from sdfgl.compiler.generate import generate
from sdfgl.errors import ParameterError, SceneFileError
from sdfgl.scenefile_process import SceneFileLoader
from sdfgl.settings import Settings

ROOT = Path(__file__).resolve().parent.parent
PID_LINE = "import os, pathlib\npathlib.Path(__file__).with_suffix('.pid').write_text(str(os.getpid()))\n"


def _gone(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return True
    return "\nState:\tZ" in state


def _wait_pid(path: Path, timeout: float = 30.0) -> int:
    deadline = time.monotonic() + timeout
    pid_file = path.with_suffix(".pid")
    while not pid_file.exists() or not pid_file.read_text():
        assert time.monotonic() < deadline, "the scene file never ran"
        time.sleep(0.02)
    return int(pid_file.read_text())


@pytest.fixture()
def loader():
    ld = SceneFileLoader(timeout=20)
    yield ld
    ld.close()


def test_a_scene_comes_back_with_its_camera_settings_and_shared_parameters(tmp_path, loader):
    f = tmp_path / "scene.py"
    f.write_text("import sdfgl as sg\nr = sg.param(1.0, name='r', range=(0.1, 2))\n"
                 "scene = sg.sphere(r) | sg.torus(r, 0.2)\ncamera = sg.OrbitCamera(distance=5, yaw=30)\n"
                 "settings = {'aa': 2}\n")
    sf = loader.wait(f)
    assert sf.path == f and sf.settings == {"aa": 2} and isinstance(sf.camera, sg.OrbitCamera)
    assert sf.camera.distance == 5 and sf.camera.yaw == 30
    src = generate(sf.scene, Settings.build())
    assert [p.name for p in src.params] == ["r"]  # one uniform: both nodes hold the same parameter
    two = sg.sphere(sg.param(1.0, name="r")) | sg.torus(sg.param(1.0, name="r"), 0.2)
    assert len(generate(two, Settings.build()).params) == 2  # (as two parameters would not)
    with pytest.raises(ParameterError, match="outside its range"):
        src.params[0].value = 5.0  # its range check came along
    assert sf.scene.label() == (sg.sphere(1.0) | sg.torus(1.0, 0.2)).label()


def test_a_json_document_loads_too(tmp_path, loader):
    f = tmp_path / "scene.json"
    sg.save_scene(sg.box(1.5).color(0.2, 0.6, 0.9), f)
    assert loader.wait(f).scene.label() == sg.box(1.5).color(0.2, 0.6, 0.9).label()


def test_an_endless_loop_is_stopped_at_the_time_limit(tmp_path):
    f = tmp_path / "loop.py"
    f.write_text(PID_LINE + "while True:\n    pass\n")
    ld = SceneFileLoader(timeout=2)
    try:
        t0 = time.monotonic()
        ld.start(f)
        pid = _wait_pid(f)
        with pytest.raises(SceneFileError, match=r"loop.py' did not finish loading within 2 s"):
            while ld.poll() is None:
                time.sleep(0.02)
        assert 1.9 < time.monotonic() - t0 < 10 and _gone(pid)
    finally:
        ld.close()


def test_polling_never_waits_for_a_slow_file(tmp_path, loader):
    f = tmp_path / "slow.py"
    f.write_text("import time\ntime.sleep(2)\nimport sdfgl as sg\nscene = sg.sphere(1)\n")
    loader.start(f)
    t0, worst, sf = time.monotonic(), 0.0, None
    while sf is None:
        t = time.perf_counter()
        sf = loader.poll()
        worst = max(worst, time.perf_counter() - t)
        time.sleep(0.01)
    assert time.monotonic() - t0 >= 2.0 and worst < 0.1
    assert loader.loading is None and loader.elapsed() == 0.0


@pytest.mark.parametrize("code, match", [
    ("import os\nos._exit(3)\n",
     r"ended with exit status 3 before the file defined 'scene' \(does the file call os._exit\?\)"),
    ("import os, signal\nos.kill(os.getpid(), signal.SIGKILL)\n", "killed by SIGKILL"),
    ("import sys\nsys.exit(4)\n", r"sys.exit\(4\)"),
    ("scene = 1 +\n", "line 1: syntax error"),
    ("x = 1\n", "does not define 'scene'"),
])
def test_a_file_that_fails_or_ends_its_process_is_reported(tmp_path, loader, code, match):
    f = tmp_path / "bad.py"
    f.write_text(code)
    with pytest.raises(SceneFileError, match=match) as info:
        loader.wait(f)
    assert "bad.py" in str(info.value)


def test_a_newer_load_stops_the_one_in_progress(tmp_path, loader):
    f = tmp_path / "loop.py"
    f.write_text(PID_LINE + "while True:\n    pass\n")
    loader.start(f)
    pid = _wait_pid(f)
    g = tmp_path / "ok.py"
    g.write_text("import sdfgl as sg\nscene = sg.box(1)\n")
    assert loader.wait(g).scene.label() == sg.box(1).label()
    assert _gone(pid)


def test_a_scene_of_classes_the_file_defines_is_loaded_here(tmp_path, loader):
    f = tmp_path / "own.py"
    f.write_text("import sdfgl as sg\n"
                 "class Ball(sg.Node):\n"
                 "    kind = 'test_file_defined_ball'\n"
                 "    exactness = 'exact'\n"
                 "    bounds = sg.sphere(1).bounds\n"
                 "scene = Ball()\n")
    sf = loader.wait(f)
    assert type(sf.scene).__name__ == "Ball"


def test_a_loading_child_ends_with_its_parent(tmp_path):
    f = tmp_path / "loop.py"
    f.write_text(PID_LINE + "while True:\n    pass\n")
    parent = subprocess.Popen([sys.executable, "-c", "import sys, time\nfrom sdfgl.scenefile_process import "
                               "SceneFileLoader\nSceneFileLoader(600).start(sys.argv[1])\ntime.sleep(600)\n",
                               str(f)], env={**os.environ, "PYTHONPATH": str(ROOT)})
    try:
        pid = _wait_pid(f)
    finally:
        parent.send_signal(signal.SIGKILL)
        parent.wait(10)
    deadline = time.monotonic() + 10
    while not _gone(pid):
        assert time.monotonic() < deadline, "the loading child outlived its parent"
        time.sleep(0.05)


def test_the_time_limit_must_be_positive():
    for bad in (0, -1, float("nan"), float("inf"), "5", True):
        with pytest.raises(ParameterError, match="timeout"):
            SceneFileLoader(bad)


def test_view_exits_with_a_message_when_the_first_load_does_not_finish(tmp_path):
    f = tmp_path / "loop.py"
    f.write_text("while True:\n    pass\n")
    env = {**os.environ, "PYTHONPATH": str(ROOT), "DISPLAY": ""}
    t0 = time.monotonic()
    out = subprocess.run([sys.executable, "-m", "sdfgl.cli", "view", str(f), "--load-timeout", "1"], env=env,
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 2 and "did not finish loading within 1 s" in out.stderr
    assert "Traceback" not in out.stderr and time.monotonic() - t0 < 30
    bad = subprocess.run([sys.executable, "-m", "sdfgl.cli", "view", str(f), "--load-timeout", "0"], env=env,
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "--load-timeout" in bad.stderr and "> 0" in bad.stderr
