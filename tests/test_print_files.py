"""Print files: several named parts with their materials in 3MF / OBJ / glTF, the 3MF unit,
read back by trimesh and by the standard library, and sliced by PrusaSlicer when it is installed."""
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.mesh.threemf import read_3mf

trimesh = pytest.importorskip("trimesh")
ROOT = Path(__file__).resolve().parents[1]
PRUSA = shutil.which("prusa-slicer")
needs_slicer = pytest.mark.skipif(PRUSA is None, reason="prusa-slicer is not installed (./install.sh --test installs it)")

BODY = sg.box((20, 20, 5))
INLAY = sg.box((6, 6, 5.2))
PARTS = {"body": (BODY - INLAY).material("white"), "inlay": INLAY.material("red")}
SCENE_FILE = """import sdfgl as sg
body = sg.box((20, 20, 5))
inlay = sg.box((6, 6, 5.2))
parts = {"body": (body - inlay).material("white"), "inlay": inlay.material("red")}
scene = sg.union(*parts.values())
"""


@pytest.fixture(scope="module")
def two_parts(tmp_path_factory) -> Path:
    return sg.save_3mf(PARTS, tmp_path_factory.mktemp("print") / "two.3mf", units="mm", resolution=24)


def test_3mf_holds_one_object_per_part_with_its_colour_and_the_unit(two_parts):
    doc = read_3mf(two_parts)
    assert doc["unit"] == "millimeter" and list(doc["objects"]) == ["body", "inlay"]
    assert set(doc["objects"]["body"]["colors"]) == {"#FFFFFFFF"}
    assert set(doc["objects"]["inlay"]["colors"]) == {"#FF0000FF"}
    assert doc["objects"]["inlay"]["materials"] == ["inlay"]
    lo, hi = doc["objects"]["inlay"]["vertices"].min(axis=0), doc["objects"]["inlay"]["vertices"].max(axis=0)
    assert np.allclose(lo, [-3, -3, -2.6], atol=0.05) and np.allclose(hi, [3, 3, 2.6], atol=0.05)  # not moved


def test_trimesh_reads_back_the_3mf_parts_and_unit(two_parts):
    s = trimesh.load(str(two_parts))
    assert s.units == "millimeter" and sorted(s.geometry) == ["body", "inlay"]
    doc = read_3mf(two_parts)
    for name, g in s.geometry.items():
        assert g.is_watertight and len(g.faces) == len(doc["objects"][name]["faces"]), name
    assert abs(s.geometry["inlay"].volume - 6 * 6 * 5.2) < 0.03 * 6 * 6 * 5.2  # marching cubes rounds edges
    assert abs(s.geometry["body"].volume - (20 * 20 * 5 - 6 * 6 * 5)) < 0.03 * (20 * 20 * 5 - 6 * 6 * 5)


def test_a_single_mesh_keeps_its_colours_as_base_materials_and_its_unit(tmp_path):
    two = sg.box(1).material("red") | sg.sphere(0.5).translate((1, 0, 0)).material("blue")
    path = sg.mesh(two, resolution=24).save(tmp_path / "one.3mf", units="cm")
    doc = read_3mf(path)
    assert doc["unit"] == "centimeter" and list(doc["objects"]) == ["one"]
    colours = set(doc["objects"]["one"]["colors"])
    assert {"#FF0000FF", "#0000FFFF"} <= colours
    assert trimesh.load(str(path)).units == "centimeter"
    m = two.save(tmp_path / "node.3mf", units="inch", resolution=16)  # Node.save passes the unit on
    assert read_3mf(tmp_path / "node.3mf")["unit"] == "inch" and len(m.faces) > 0


def test_obj_and_glb_keep_the_parts_and_their_materials(tmp_path):
    for suffix in (".obj", ".glb"):
        s = trimesh.load(str(sg.save_parts(PARTS, tmp_path / f"two{suffix}", resolution=24)))
        assert sorted(s.geometry) == ["body", "inlay"], suffix
        colour = {k: tuple(g.visual.material.main_color[:3]) for k, g in s.geometry.items()}
        assert colour == {"body": (255, 255, 255), "inlay": (255, 0, 0)}, suffix
    mtl = (tmp_path / "two.mtl").read_text()
    assert "newmtl body\nKd 1.0000 1.0000 1.0000" in mtl and "newmtl inlay\nKd 1.0000 0.0000 0.0000" in mtl


def test_bad_parts_units_and_suffixes_are_clear_errors(tmp_path):
    with pytest.raises(sg.ParameterError, match="unknown unit 'furlong'"):
        sg.save_3mf(PARTS, tmp_path / "a.3mf", units="furlong", resolution=8)
    with pytest.raises(sg.SdfglError, match="does not end in .3mf"):
        sg.save_3mf(PARTS, tmp_path / "a.obj", resolution=8)
    with pytest.raises(sg.SdfglError, match="'units' is stored by 3MF only"):
        sg.save_parts(PARTS, tmp_path / "a.obj", units="mm", resolution=8)
    with pytest.raises(sg.SdfglError, match="keeps no parts apart"):
        sg.save_parts(PARTS, tmp_path / "a.stl", resolution=8)
    with pytest.raises(sg.ParameterError, match="part 'lid' must be an sdfgl node or mesh, got int"):
        sg.save_3mf({"lid": 3}, tmp_path / "a.3mf")
    with pytest.raises(sg.SdfglError, match="OBJ names cannot hold spaces, and part 'the lid' has one"):
        sg.save_parts({"the lid": sg.sphere(1)}, tmp_path / "a.obj", resolution=8)
    with pytest.raises(sg.SdfglError, match="'units' is stored by 3MF only"):
        sg.mesh(sg.sphere(1), resolution=8).save(tmp_path / "a.stl", units="mm")
    assert not list(tmp_path.iterdir())


def test_cli_writes_the_parts_of_a_scene_file_with_its_unit(tmp_path):
    scene = tmp_path / "two.py"
    scene.write_text(SCENE_FILE)
    out = tmp_path / "part.3mf"
    r = subprocess.run([sys.executable, "-m", "sdfgl", "mesh", str(scene), "-o", str(out), "--units", "inch",
                        "--resolution", "16", "--quiet"], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "2 parts (body" in r.stdout
    doc = read_3mf(out)
    assert doc["unit"] == "inch" and list(doc["objects"]) == ["body", "inlay"]
    r = subprocess.run([sys.executable, "-m", "sdfgl", "mesh", str(scene), "-o", str(tmp_path / "p.stl"),
                        "--units", "mm"], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert r.returncode == 2 and "--units is stored by 3MF only" in r.stderr
    r = subprocess.run([sys.executable, "-m", "sdfgl", "mesh", str(scene), "-o", str(tmp_path / "p.glb"),
                        "--units", "cm", "--density", "1", "--resolution", "16", "--quiet"],
                       capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "print inlay: size 6 x 6 x 5.2 cm" in r.stdout and "print body: size 20 x 20 x 5 cm" in r.stdout


def test_a_scene_file_with_bad_parts_is_refused(tmp_path):
    from sdfgl.scenefile import load_scene_file
    scene = tmp_path / "bad.py"
    scene.write_text("import sdfgl as sg\nscene = sg.sphere(1)\nparts = {'lid': 3}\n")
    with pytest.raises(sg.SceneFileError, match="'lid' maps to int"):
        load_scene_file(scene)


def slice_file(path: Path, tmp_path: Path, extruders: int) -> str:
    """G-code PrusaSlicer makes of ``path`` (positions kept, ``extruders`` nozzles)."""
    gcode = tmp_path / (path.stem + ".gcode")
    r = subprocess.run([PRUSA, "--export-gcode", str(path), "--dont-arrange", "--nozzle-diameter",
                        ",".join(["0.4"] * extruders), "--output", str(gcode)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    return gcode.read_text()


def extrusion_box(gcode: str) -> dict[str, tuple[float, float, float, float]]:
    """Per tool, the XY box of its extruding moves."""
    tool, points = "T0", {}
    for line in gcode.splitlines():
        if re.match(r"T\d+$", line):
            tool = line
        m = re.match(r"G1 X(-?[\d.]+) Y(-?[\d.]+) E", line)
        if m:
            points.setdefault(tool, []).append((float(m[1]), float(m[2])))
    return {t: (*np.min(p, axis=0), *np.max(p, axis=0)) for t, p in points.items()}


@needs_slicer
def test_prusaslicer_slices_a_single_part(tmp_path):
    path = sg.mesh(sg.rounded_box((20, 20, 5), 1).material("#2a6"), resolution=32).save(tmp_path / "plate.3mf")
    t0 = time.perf_counter()
    gcode = slice_file(path, tmp_path, 1)
    assert time.perf_counter() - t0 < 20
    assert re.search(r"^G1 .*E", gcode, re.M) and not re.search(r"^T1$", gcode, re.M)


@needs_slicer
def test_prusaslicer_prints_the_two_parts_with_two_tools_in_place(two_parts, tmp_path):
    gcode = slice_file(two_parts, tmp_path, 2)
    assert re.search(r"^T0$", gcode, re.M) and re.search(r"^T1$", gcode, re.M)
    box = extrusion_box(gcode)
    # the inlay (extruder 2) is printed where it sits in the body, not moved beside it
    assert np.allclose(box["T1"], (-2.8, -2.8, 2.8, 2.8), atol=0.3), box
