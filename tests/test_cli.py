"""The command line, run as a user would: a real subprocess."""
import subprocess
import sys
from pathlib import Path

import numpy as np
from PIL import Image

ROOT = Path(__file__).resolve().parents[1]


def sdfgl(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "sdfgl.cli", *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=120)


def test_render_scene_file(tmp_path):
    out = tmp_path / "csg.png"
    r = sdfgl("render", "examples/csg.py", "-o", str(out), "--size", "64x48", "--aa", "2")
    assert r.returncode == 0, r.stderr
    assert "wrote" in r.stdout
    img = Image.open(out)
    assert img.size == (64, 48)
    assert len(np.unique(np.asarray(img).reshape(-1, 3), axis=0)) > 20  # a shaded object, not a blank frame


def test_render_demo(tmp_path):
    out = tmp_path / "demo.png"
    r = sdfgl("render", "--demo", "-o", str(out), "--size", "80x60")
    assert r.returncode == 0, r.stderr
    assert Image.open(out).size == (80, 60)


def test_shader_prints_generated_glsl():
    r = sdfgl("shader", "examples/csg.py", "--aa", "2", "--shadows", "off")
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("#version 330 core")
    assert "float map(vec3 p)" in r.stdout and "#define AA 2" in r.stdout and "#define SHADOWS" not in r.stdout


def test_bad_scene_file_gives_one_clear_line(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("import sdfgl as sg\nscene = sg.sphere(-1)\n")
    r = sdfgl("render", str(bad), "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2
    assert "Traceback" not in r.stderr
    assert f"scene file '{bad}', line 2: sphere: parameter 'radius' must be > 0" in r.stderr

    empty = tmp_path / "empty.py"
    empty.write_text("x = 1\n")
    r = sdfgl("render", str(empty))
    assert r.returncode == 2 and "does not define 'scene'" in r.stderr

    r = sdfgl("render", str(tmp_path / "nope.py"))
    assert r.returncode == 2 and "does not exist" in r.stderr


def test_bad_size_argument():
    r = sdfgl("render", "--demo", "--size", "big")
    assert r.returncode == 2 and "size must look like 800x600" in r.stderr


def test_render_transparent_orthographic(tmp_path):
    out = tmp_path / "cut.png"
    r = sdfgl("render", "examples/csg.py", "-o", str(out), "--size", "48x96", "--alpha", "--ortho",
              "--background", "white,#336699")
    assert r.returncode == 0, r.stderr
    a = np.asarray(Image.open(out))
    assert a.shape == (96, 48, 4)
    alpha = a[..., 3]
    assert (alpha == 0).any() and (alpha == 255).any()
    assert alpha[0].max() == 0 and alpha[-1].max() == 0 and alpha[:, 0].max() == 0  # framed with room around
    bad = sdfgl("render", "examples/csg.py", "-o", str(tmp_path / "x.png"), "--background", "nonsense")
    assert bad.returncode != 0 and "not a colour" in bad.stderr and "Traceback" not in bad.stderr
