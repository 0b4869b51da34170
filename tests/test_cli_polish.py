"""The command line as a user meets it: version, python -m, camera flags, outputs, usage, errors."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import sdfgl as sg

ROOT = Path(__file__).resolve().parents[1]


def run(*args: str, module: str = "sdfgl") -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", module, *args], capture_output=True, text=True, cwd=ROOT,
                          timeout=120)


@pytest.mark.slow
def test_version_and_python_dash_m():
    r = run("--version")
    assert r.returncode == 0 and r.stdout.strip() == f"sdfgl {sg.__version__}"
    r = run("--help")
    assert r.returncode == 0 and "render" in r.stdout and "view" in r.stdout


@pytest.mark.slow
def test_usage_shows_choices():
    r = run("render", "--help")
    assert "{auto,sphere,relaxed,enhanced,newton,forward_newton,reference}" in r.stdout
    assert "{off,hard,soft}" in r.stdout and "{1,2,3,4}" in r.stdout
    for flag in ("--yaw", "--pitch", "--distance", "--fov", "--target", "--outputs"):
        assert flag in r.stdout
    for cmd in ("shader", "view"):
        out = run(cmd, "--help").stdout
        assert all(f in out for f in ("--yaw", "--pitch", "--distance", "--fov", "--target")), cmd
    r = run("render", "--demo", "--method", "fast")
    assert r.returncode == 2 and "invalid choice: 'fast'" in r.stderr


def test_render_without_a_scene_says_so(tmp_path):
    r = run("render", "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2
    assert "render: give a scene file (.py or .json) or --demo" in r.stderr
    assert not (tmp_path / "x.png").exists()


@pytest.mark.slow
def test_camera_flags_change_the_view_the_same_way_in_render_and_shader(tmp_path):
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    base = ("render", "examples/csg.py", "--size", "64x48", "--shadows", "off", "--no-ao")
    assert run(*base, "-o", str(a)).returncode == 0
    r = run(*base, "-o", str(b), "--yaw", "120", "--pitch", "40", "--distance", "7", "--fov", "30",
            "--target", "0,0.5,0")
    assert r.returncode == 0, r.stderr
    assert not np.array_equal(np.asarray(Image.open(a)), np.asarray(Image.open(b)))
    # the same flags on the library side give the same picture
    from sdfgl.scenefile import load_scene_file
    sf = load_scene_file(ROOT / "examples" / "csg.py")
    cam = sg.OrbitCamera((0, 0.5, 0), 7, 120, 40, 30)
    want = sg.render(sf.scene, cam, (64, 48), shadows=False, ao=False).color
    assert np.abs(np.asarray(Image.open(b)).astype(int) - want).max() <= 1
    r = run("shader", "examples/csg.py", "--yaw", "10", "--target", "1,2")
    assert r.returncode == 2 and "expected three numbers" in r.stderr
    r = run("render", "examples/csg.py", "--distance", "nan")
    assert r.returncode == 2 and "expected a finite number" in r.stderr
    r = run("render", "examples/csg.py", "--distance", "-3", "-o", str(tmp_path / "c.png"))
    assert r.returncode == 2 and "parameter 'distance' must be > 0" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow
def test_outputs_write_depth_and_normal_images_and_npz(tmp_path):
    out = tmp_path / "o.png"
    r = run("render", "examples/csg.py", "--size", "48x32", "-o", str(out), "--outputs", "depth,normal,steps")
    assert r.returncode == 0, r.stderr
    depth = np.asarray(Image.open(tmp_path / "o.depth.png"))
    normal = np.asarray(Image.open(tmp_path / "o.normal.png"))
    steps = np.asarray(Image.open(tmp_path / "o.steps.png"))
    assert depth.shape == (32, 48) and depth.max() == 65535 and (depth == 0).any()  # nearest white, misses black
    assert normal.shape == (32, 48, 3) and len(np.unique(normal.reshape(-1, 3), axis=0)) > 20
    assert steps.shape == (32, 48) and steps.max() > 0
    npz = tmp_path / "all.npz"
    r = run("render", "examples/csg.py", "--size", "48x32", "-o", str(npz))
    assert r.returncode == 0, r.stderr
    data = np.load(npz)
    assert set(data.files) == {"color", "depth", "normal", "steps"}
    assert data["depth"].dtype == np.float32 and np.isinf(data["depth"]).any() and np.isfinite(data["depth"]).any()
    r = run("render", "examples/csg.py", "--outputs", "depth,albedo")
    assert r.returncode == 2 and "outputs must be a comma list of" in r.stderr


@pytest.mark.parametrize("args, message", [
    (("render", "examples/csg.py", "--size", "0x10"), "size must be two whole numbers in 1..16384"),
    (("render", "examples/csg.py", "--max-steps", "0"), "setting 'max_steps' must be an integer 1..100000"),
    (("render", "examples/csg.py", "--pitch", "95"), "'pitch' must lie in [-89.9, 89.9]"),
    (("render", "examples/csg.py", "--fov", "500"), "'fov' must be in [1e-4, 179]"),
    (("render", "examples/csg.py", "-o", "/nonexistent/dir/x.png"), "cannot write image file"),
])
@pytest.mark.slow
def test_bad_values_are_one_clear_line(args, message, tmp_path):
    r = run(*args)
    assert r.returncode == 2, r.stdout
    assert message in r.stderr and "Traceback" not in r.stderr
