"""Every subcommand x every kind of scene x its main outputs, run as a user runs them: a
subprocess of a non-editable install (the built wheel's files, so shaders and web assets must
ship), in a folder outside the source tree. Sizes are tiny; the costly cells are marked slow."""
from __future__ import annotations

import json
import os
import shutil
import struct
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

# the whole matrix runs from a non-editable install: the full suite's, not the fast tier's
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[1]
SIZE = "32x24"
KINDS = ("plain", "full", "json", "demo")
"""plain: a .py defining only 'scene'; full: also 'camera' and 'settings'; json: a scene
document with camera and settings; demo: --demo."""
AA = {"plain": 1, "full": 2, "json": 2, "demo": 1}

PLAIN = "import sdfgl as sg\nscene = sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0)).color(0.9, 0.4, 0.2)\n"
FULL = PLAIN + ("camera = sg.OrbitCamera(target=(0.5, 0, 0), distance=4, yaw=60, pitch=25)\n"
                "settings = {'aa': 2, 'shadows': False}\n")


@pytest.fixture(scope="session")
def installed(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """sdfgl installed (not editable) into a folder of its own, built from a copy of the tree."""
    base = tmp_path_factory.mktemp("install")
    src = base / "src"
    src.mkdir()
    for name in ("pyproject.toml", "setup.py", "README.md", "LICENSE"):
        shutil.copy2(ROOT / name, src / name)
    for name in ("sdfgl", "shaders"):
        shutil.copytree(ROOT / name, src / name, ignore=shutil.ignore_patterns("__pycache__"))
    target = base / "site"
    r = subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target", str(target), str(src)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    return target


@pytest.fixture(scope="session")
def scenes(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[str]]:
    """The command line arguments naming each kind of scene."""
    import sdfgl as sg
    folder = tmp_path_factory.mktemp("scenes")
    (folder / "plain.py").write_text(PLAIN)
    (folder / "full.py").write_text(FULL)
    sg.save_scene(sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0)).color(0.9, 0.4, 0.2), folder / "doc.json",
                  camera=sg.OrbitCamera(target=(0.5, 0, 0), distance=4, yaw=60, pitch=25),
                  settings={"aa": 2, "shadows": False})
    return {"plain": [str(folder / "plain.py")], "full": [str(folder / "full.py")],
            "json": [str(folder / "doc.json")], "demo": ["--demo"]}


def sdfgl(installed: Path, cwd: Path, *args: str, timeout: float = 120,
          env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    """``python -m sdfgl ARGS`` from the installed copy, in ``cwd``; fails the test on a nonzero exit."""
    r = subprocess.run([sys.executable, "-m", "sdfgl", *args], capture_output=True, text=True, cwd=cwd,
                       timeout=timeout, env={**os.environ, **(env or {}), "PYTHONPATH": str(installed)})
    assert r.returncode == 0, f"sdfgl {' '.join(args)}:\n{r.stdout}\n{r.stderr}"
    assert "Traceback" not in r.stderr
    return r


@pytest.mark.slow
def test_the_install_is_the_one_run(installed, tmp_path):
    code = "import sdfgl, sdfgl.cli, pathlib; print(sdfgl.__file__); print(sdfgl.cli.__file__)"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=60,
                       env={**os.environ, "PYTHONPATH": str(installed)})
    assert r.returncode == 0, r.stderr
    assert all(Path(line).is_relative_to(installed) for line in r.stdout.split())
    assert (installed / "sdfgl" / "shaders" / "lib").is_dir() and (installed / "sdfgl" / "web" / "page.html").exists()
    # the console script (sdfgl = "sdfgl.cli:main") starts the same command line
    script = installed / "bin" / "sdfgl"
    r = subprocess.run([str(script), "--version"], capture_output=True, text=True, cwd=tmp_path, timeout=60,
                       env={**os.environ, "PYTHONPATH": str(installed)})
    assert r.returncode == 0 and r.stdout.startswith("sdfgl "), r.stderr


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.slow
def test_render(installed, scenes, tmp_path, kind):
    r = sdfgl(installed, tmp_path, "render", *scenes[kind], "--size", SIZE, "-o", "out.png", "--outputs", "depth")
    assert f"wrote out.png, out.depth.png ({SIZE}, aa {AA[kind]})" in r.stdout, r.stdout
    color = np.asarray(Image.open(tmp_path / "out.png"))
    depth = np.asarray(Image.open(tmp_path / "out.depth.png"))
    assert color.shape == (24, 32, 3) and len(np.unique(color.reshape(-1, 3), axis=0)) > 8
    assert depth.shape == (24, 32) and depth.max() > depth.min()  # nearer is whiter (misses black)
    r = sdfgl(installed, tmp_path, "render", *scenes[kind], "--size", SIZE, "-o", "all.npz")
    with np.load(tmp_path / "all.npz") as npz:
        assert {"color", "depth", "normal", "steps"} <= set(npz.files) and npz["depth"].shape == (24, 32)


@pytest.mark.parametrize("kind", KINDS)
def test_shader(installed, scenes, tmp_path, kind):
    r = sdfgl(installed, tmp_path, "shader", *scenes[kind])
    assert "void main" in r.stdout and f"#define AA {AA[kind]}" in r.stdout


@pytest.mark.parametrize("kind", KINDS)
def test_html(installed, scenes, tmp_path, kind):
    r = sdfgl(installed, tmp_path, "html", *scenes[kind], "--size", SIZE, "-o", "v.html")
    assert r.stdout.startswith("wrote v.html (") and f"view {SIZE}): open it in a browser" in r.stdout
    page = (tmp_path / "v.html").read_text()
    assert page.lstrip().lower().startswith("<!doctype html") and "webgl2" in page


def binary_stl_triangles(path: Path) -> int:
    data = path.read_bytes()
    (n,) = struct.unpack("<I", data[80:84])
    assert len(data) == 84 + 50 * n
    return n


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.slow
def test_mesh(installed, scenes, tmp_path, kind):
    r = sdfgl(installed, tmp_path, "mesh", *scenes[kind], "-o", "m.stl", "--resolution", "12", "--quiet")
    assert r.stdout.startswith("wrote m.stl: ") and "triangles" in r.stdout and "report:" not in r.stdout
    assert binary_stl_triangles(tmp_path / "m.stl") > 20
    r = sdfgl(installed, tmp_path, "mesh", *scenes[kind], "-o", "m.obj", "--resolution", "12", "--quiet")
    assert sum(line.startswith("f ") for line in (tmp_path / "m.obj").read_text().splitlines()) > 20


@pytest.mark.slow
@pytest.mark.parametrize("kind", ("plain", "json"))
def test_mesh_glb_and_report(installed, scenes, tmp_path, kind):
    import trimesh
    r = sdfgl(installed, tmp_path, "mesh", *scenes[kind], "-o", "m.glb", "--resolution", "12", "--quiet",
              "--report")
    assert "report: " in r.stdout and "Hausdorff" in r.stdout
    assert len(trimesh.load(str(tmp_path / "m.glb"), force="mesh").faces) > 20


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.slow
def test_animate(installed, scenes, tmp_path, kind):
    r = sdfgl(installed, tmp_path, "animate", *scenes[kind], "-o", "a.gif", "--frames", "2", "--size", SIZE,
              "--no-progress")
    assert r.stdout.startswith(f"wrote a.gif: 2 frames {SIZE} at 30 fps"), r.stdout
    with Image.open(tmp_path / "a.gif") as gif:
        assert gif.n_frames == 2 and gif.size == (32, 24)
    sdfgl(installed, tmp_path, "animate", *scenes[kind], "-o", "frames/%02d.png", "--frames", "2", "--size", SIZE,
          "--turntable", "--no-progress")
    assert sorted(p.name for p in (tmp_path / "frames").iterdir()) == ["00.png", "01.png"]


@pytest.mark.slow
@pytest.mark.parametrize("kind", ("full", "demo"))
def test_animate_video(installed, scenes, tmp_path, kind):
    import imageio_ffmpeg
    r = sdfgl(installed, tmp_path, "animate", *scenes[kind], "-o", "a.mp4", "--frames", "3", "--size", SIZE,
              "--no-progress")
    assert r.stdout.startswith(f"wrote a.mp4: 3 frames {SIZE}")
    assert imageio_ffmpeg.count_frames_and_secs(str(tmp_path / "a.mp4"))[0] == 3


@pytest.mark.slow
def test_batch(installed, scenes, tmp_path):
    jobs = [{"scene": scenes[k][0], "size": [32, 24], "output": f"out/{k}.png", "data": f"out/{k}.npz"}
            for k in ("plain", "full", "json")]
    (tmp_path / "jobs.json").write_text(json.dumps({"jobs": jobs}))
    r = sdfgl(installed, tmp_path, "batch", "jobs.json", "--workers", "1", "--no-progress")
    assert "3 jobs: 3 done" in r.stdout and "0 failed" in r.stdout, r.stdout
    for k in ("plain", "full", "json"):
        assert np.asarray(Image.open(tmp_path / "out" / f"{k}.png")).shape == (24, 32, 3)
        with np.load(tmp_path / "out" / f"{k}.npz") as npz:
            assert npz["depth"].shape == (24, 32)
    r = sdfgl(installed, tmp_path, "batch", "jobs.json", "--workers", "1", "--no-progress")
    assert "3 skipped" in r.stdout


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
def test_pbr(installed, scenes, tmp_path, kind):
    r = sdfgl(installed, tmp_path, "pbr", *scenes[kind], "--size", SIZE, "-o", "p.png", "--spp", "2",
              "--resolution", "16", "--quiet", timeout=300)
    assert r.stdout.startswith(f"wrote p.png ({SIZE}, 2 spp, Mitsuba "), r.stdout
    assert np.asarray(Image.open(tmp_path / "p.png")).shape[:2] == (24, 32)


def test_bench_help(installed, tmp_path):
    # bench takes no scene; its run is timed in tests/test_methods.py (over a minute even --quick)
    r = sdfgl(installed, tmp_path, "bench", "--help")
    assert all(flag in r.stdout for flag in ("--quick", "--size", "--out", "--scenes", "--no-progress"))


@pytest.mark.slow
@pytest.mark.window
@pytest.mark.parametrize("kind", KINDS)
def test_view(installed, scenes, tmp_path, kind):
    from sdfgl import xdisplay

    from .xserver import start_xvfb
    xvfb, display = start_xvfb()
    state = tmp_path / "state.json"
    proc = subprocess.Popen([sys.executable, "-m", "sdfgl", "view", *scenes[kind], "--size", "200x150",
                             "--state-file", str(state), "--no-panel"], cwd=tmp_path, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "DISPLAY": display, "PYTHONPATH": str(installed)})
    try:
        deadline = time.time() + 90
        st: dict = {}
        while time.time() < deadline and proc.poll() is None:
            try:
                st = json.loads(state.read_text())
            except (OSError, ValueError):
                st = {}
            if st.get("size"):
                break
            time.sleep(0.1)
        assert proc.poll() is None, proc.stderr.read()
        assert st.get("size") == [200, 150], st
        if kind in ("full", "json"):
            assert st["yaw"] == pytest.approx(60) and st["distance"] == pytest.approx(4)
    finally:
        proc.kill()
        proc.wait(10)
        xdisplay.stop_xvfb(xvfb)
