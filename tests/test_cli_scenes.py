"""Scenes through the command line: every subcommand loads .py, .json and --demo the same way and
reports what it rendered."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import sdfgl as sg

ROOT = Path(__file__).resolve().parents[1]
SUBCOMMANDS = ("render", "shader", "view", "html", "mesh", "pbr", "bench", "animate", "batch")

STILL = """import sdfgl as sg
scene = sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0))
camera = sg.OrbitCamera(target=(0.5, 0, 0), distance=4, yaw=60, pitch=25)
settings = {"aa": 2, "shadows": False}
"""
TURNING = STILL + "camera_path = sg.turntable(distance=4, pitch=25, target=(0.5, 0, 0))\n"


def run(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "sdfgl", *args], capture_output=True, text=True, cwd=cwd,
                          timeout=120)


def frames(folder: Path) -> list[np.ndarray]:
    return [np.asarray(Image.open(p)).astype(int) for p in sorted(folder.glob("*.png"))]


def test_usage_lists_every_subcommand():
    r = run("--help")
    assert r.returncode == 0
    usage = r.stdout.split("\n\n")[0]
    assert all(c in usage for c in SUBCOMMANDS), usage


def test_animate_help_shows_the_frame_pattern_unescaped():
    r = run("animate", "--help")
    assert r.returncode == 0 and "frames/%04d.png" in r.stdout and "%%" not in r.stdout


def test_render_reports_the_aa_the_scene_file_asked_for(tmp_path):
    f = tmp_path / "s.py"
    f.write_text(STILL)
    r = run("render", str(f), "--size", "32x24", "-o", str(tmp_path / "a.png"))
    assert r.returncode == 0, r.stderr
    assert "(32x24, aa 2)" in r.stdout, r.stdout
    # a flag given wins over the file's settings, even when it names the default
    r = run("render", str(f), "--size", "32x24", "-o", str(tmp_path / "b.png"), "--aa", "1")
    assert r.returncode == 0 and "(32x24, aa 1)" in r.stdout, r.stdout
    want = sg.render(sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0)),
                     sg.OrbitCamera(target=(0.5, 0, 0), distance=4, yaw=60, pitch=25), (32, 24), aa=1,
                     shadows=False).color
    assert np.abs(np.asarray(Image.open(tmp_path / "b.png")).astype(int) - want).max() <= 1


def test_animate_without_turntable_uses_the_files_fixed_camera(tmp_path):
    f = tmp_path / "still.py"
    f.write_text(STILL)
    out = tmp_path / "still"
    r = run("animate", str(f), "-o", str(out / "%03d.png"), "--frames", "3", "--size", "32x24", "--no-progress")
    assert r.returncode == 0, r.stderr
    assert "3 frames 32x24" in r.stdout
    got = frames(out)
    assert len(got) == 3 and all(np.array_equal(got[0], g) for g in got)  # a still scene, a fixed camera
    want = sg.render(sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0)),
                     sg.OrbitCamera(target=(0.5, 0, 0), distance=4, yaw=60, pitch=25), (32, 24), aa=2,
                     shadows=False).color
    assert np.abs(got[0] - want).max() <= 1


def test_animate_without_turntable_follows_the_files_camera_path(tmp_path):
    f = tmp_path / "turning.py"
    f.write_text(TURNING)
    out = tmp_path / "turning"
    r = run("animate", str(f), "-o", str(out / "%03d.png"), "--frames", "4", "--fps", "4", "--size", "32x24",
            "--no-progress")
    assert r.returncode == 0, r.stderr
    got = frames(out)
    assert len(got) == 4 and not np.array_equal(got[0], got[1])  # the camera moves
    path = sg.turntable(distance=4, pitch=25, target=(0.5, 0, 0))
    want = sg.render(sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0)), path.camera(0.25, 1.0), (32, 24), aa=2,
                     shadows=False).color
    assert np.abs(got[1] - want).max() <= 1
    # camera flags fix the camera instead
    r = run("animate", str(f), "-o", str(tmp_path / "fixed" / "%03d.png"), "--frames", "2", "--size", "32x24",
            "--yaw", "10", "--no-progress")
    assert r.returncode == 0, r.stderr
    a, b = frames(tmp_path / "fixed")
    assert np.array_equal(a, b)


def test_a_bad_camera_path_is_named(tmp_path):
    f = tmp_path / "bad.py"
    f.write_text(STILL + "camera_path = 3\n")
    r = run("animate", str(f), "-o", str(tmp_path / "x.gif"), "--frames", "2", "--no-progress")
    assert r.returncode == 2 and "'camera_path' must be sg.turntable(...)" in r.stderr and str(f) in r.stderr
    f.write_text(STILL.replace("camera = sg.OrbitCamera(", "camera = sg.turntable(") + "")
    r = run("render", str(f), "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2 and "a camera that moves goes in 'camera_path'" in r.stderr


def test_batch_job_with_a_json_scene_document(tmp_path):
    sg.save_scene(sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0)), tmp_path / "s.json",
                  camera=sg.OrbitCamera(target=(0.5, 0, 0), distance=4, yaw=60, pitch=25), settings={"aa": 2})
    (tmp_path / "jobs.json").write_text(json.dumps(
        {"jobs": [{"scene": "s.json", "size": [32, 24], "output": "out/j.png", "settings": {"shadows": False}}]}))
    r = run("batch", str(tmp_path / "jobs.json"), "--workers", "1", "--no-progress")
    assert r.returncode == 0, r.stdout + r.stderr
    want = sg.render(sg.sphere(0.8) | sg.box(0.6).translate((1.1, 0, 0)),
                     sg.OrbitCamera(target=(0.5, 0, 0), distance=4, yaw=60, pitch=25), (32, 24), aa=2,
                     shadows=False).color
    assert np.abs(np.asarray(Image.open(tmp_path / "out" / "j.png")).astype(int) - want).max() <= 1


def test_the_loader_gives_the_same_scene_for_py_json_and_the_demo(tmp_path):
    from sdfgl.scenefile import load_demo, load_scene_file
    (tmp_path / "s.py").write_text(TURNING)
    py = load_scene_file(tmp_path / "s.py")
    assert py.settings == {"aa": 2, "shadows": False} and isinstance(py.camera, sg.OrbitCamera)
    assert py.camera_path is not None
    sg.save_scene(py.scene, tmp_path / "s.json", camera=py.camera, settings=py.settings)
    doc = load_scene_file(tmp_path / "s.json")
    assert sg.compile(doc.scene) == sg.compile(py.scene) and doc.settings == py.settings
    assert doc.camera_path is None and doc.path == tmp_path / "s.json"
    demo = load_demo()
    assert demo.path is None and demo.settings == {"ground": True} and demo.camera is not None
    with pytest.raises(sg.SceneFileError, match="does not exist"):
        load_scene_file(tmp_path / "nope.json")


def test_setting_flags_default_to_the_settings_type_and_override_only_when_given(capsys):
    from sdfgl.cli import build_parser
    from sdfgl.cli.common import DEFAULTS, settings_overrides
    from sdfgl.settings import Settings
    st = Settings()
    assert {k: DEFAULTS[k] for k in ("aa", "shadows", "ao", "ground", "method", "max_steps")} == {
        "aa": st.aa, "shadows": st.shadows, "ao": st.ao, "ground": st.ground, "method": st.method,
        "max_steps": st.max_steps}
    parser = build_parser(["render"])
    with pytest.raises(SystemExit):
        parser.parse_args(["render", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert f"(default {st.max_steps};" in help_text and f"(default {st.aa})" in help_text
    assert settings_overrides(parser.parse_args(["render", "--demo"])) == {}
    given = parser.parse_args(["render", "--demo", "--aa", "1", "--shadows", "off", "--no-ao", "--ground"])
    assert settings_overrides(given) == {"aa": 1, "shadows": False, "ao": False, "ground": True}
