"""The GLSL ships with the package: a built wheel holds every shader file."""
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
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
    assert {"sdfgl/fonts/DejaVuSans.ttf", "sdfgl/fonts/DejaVuSans-LICENSE.txt"} <= names  # sg.text's default font
    modules = {f"sdfgl/animate/{p.name}" for p in (ROOT / "sdfgl" / "animate").glob("*.py")}
    assert modules and modules <= names, sorted(modules - names)


@pytest.mark.slow
def test_wheel_metadata_license_types_and_one_version(tmp_path):
    import email

    import sdfgl
    r = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path), str(ROOT)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    wheel = zipfile.ZipFile(next(tmp_path.glob("sdfgl-*.whl")))
    names = set(wheel.namelist())
    assert "sdfgl/py.typed" in names
    modules = {p.relative_to(ROOT).as_posix() for p in (ROOT / "sdfgl").rglob("*.py")}
    assert {"sdfgl/scene_io/__init__.py", "sdfgl/expr.py", "sdfgl/__main__.py"} <= modules
    assert modules <= names, sorted(modules - names)  # every subpackage is listed in pyproject
    assert any(n.endswith("LICENSE") for n in names)
    meta = email.message_from_bytes(wheel.read(next(n for n in names if n.endswith(".dist-info/METADATA"))))
    assert meta["Version"] == sdfgl.__version__  # one source: sdfgl/version.py
    assert meta["Author"] or meta["Author-email"]
    assert "sdf" in meta["Keywords"] and "License :: OSI Approved :: MIT License" in meta.get_all("Classifier")
    extras = meta.get_all("Provides-Extra")
    assert {"implicit", "plots", "test"} <= set(extras)
    requires = " ".join(meta.get_all("Requires-Dist"))
    assert "sympy" in requires and 'extra == "implicit"' in requires  # optional, not a core dependency
    assert not any(r.startswith(("sympy", "matplotlib")) and "extra" not in r for r in meta.get_all("Requires-Dist"))


def test_import_is_lazy():
    code = ("import sys, sdfgl; heavy = [m for m in ('sympy', 'matplotlib', 'PIL', 'glfw', 'multiprocessing') "
            "if m in sys.modules]; print(heavy)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "[]"
