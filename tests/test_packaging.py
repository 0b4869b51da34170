"""The GLSL ships with the package: a built wheel holds every shader file."""
import subprocess
import sys
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_wheel_contains_all_shaders(tmp_path):
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q",
                        "-w", str(tmp_path), str(ROOT)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    wheel = next(tmp_path.glob("sdfgl-*.whl"))
    names = set(zipfile.ZipFile(wheel).namelist())
    shipped = {f"sdfgl/shaders/{p.relative_to(ROOT / 'shaders').as_posix()}" for p in (ROOT / "shaders").rglob("*.glsl")}
    assert shipped and shipped <= names, sorted(shipped - names)
    web = {f"sdfgl/web/{p.name}" for p in (ROOT / "sdfgl" / "web").iterdir() if p.suffix in (".js", ".css", ".html")}
    assert {"sdfgl/web/viewer.js", "sdfgl/web/page.html"} <= web and web <= names, sorted(web - names)
    modules = {f"sdfgl/animate/{p.name}" for p in (ROOT / "sdfgl" / "animate").glob("*.py")}
    assert modules and modules <= names, sorted(modules - names)
