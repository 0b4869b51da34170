"""Printing checks of a mesh (Mesh.print_report): figures held to shapes with known answers."""
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def box():
    return sg.mesh(sg.box((20, 10, 4)), resolution=40, mode="sharp")


def test_box_size_volume_mass_and_its_bottom_face_as_overhang(box):
    r = box.print_report(density=1.24)
    assert np.allclose(r.bbox_min, (-10, -5, -2), atol=1e-6) and np.allclose(r.size, (20, 10, 4), atol=1e-6)
    assert r.units == "millimeter" and abs(r.volume - 800) < 1e-3
    assert abs(r.mass - 0.8 * 1.24) < 1e-5  # 800 mm^3 = 0.8 cm^3
    assert abs(r.overhang_area - 200) < 1e-3 and r.overhang_area_off_bed < 1e-9  # the bottom rests on the plate
    assert r.min_wall is None and r.thinnest is None
    assert "size 20 x 10 x 4 mm; volume 800 mm^3, mass 0.992 g" in str(r)


def test_units_scale_the_mass_and_up_picks_the_build_direction(box):
    assert abs(box.print_report(density=1.0, units="cm").mass - 800) < 1e-3  # 800 cm^3 of water
    side = box.print_report(up="x")  # standing on its 10 x 4 end
    assert abs(side.overhang_area - 40) < 1e-3 and side.overhang_area_off_bed < 1e-9


def test_overhang_of_a_spherical_shell_matches_its_caps():
    m = sg.mesh(sg.shell(sg.sphere(10), 0.4), resolution=100)
    r = m.print_report(overhang=45)
    # the outer sphere's lower cap and the inner sphere's upper cap lie more than 45 degrees from vertical
    caps = 2 * math.pi * (10.2 ** 2 + 9.8 ** 2) * (1 - math.cos(math.radians(45)))
    assert abs(r.overhang_area - caps) < 0.01 * caps
    steep = m.print_report(overhang=80).overhang_area
    assert abs(steep - 2 * math.pi * (10.2 ** 2 + 9.8 ** 2) * (1 - math.cos(math.radians(10)))) < 0.03 * steep


def test_a_thin_shell_is_flagged_with_its_thickness_and_place():
    r = sg.mesh(sg.shell(sg.sphere(10), 0.4), resolution=100).print_report(min_wall=1.0)
    assert abs(r.thinnest - 0.4) < 0.01 and r.thin_samples > 100
    assert abs(np.linalg.norm(r.thinnest_at) - 10) < 0.05
    assert "THIN WALL: 0.4 mm" in str(r)


def test_the_thin_fin_is_found_not_the_thick_plate():
    part = sg.box((20, 20, 5)) | sg.box((0.6, 10, 10)).translate((8, 0, 7))
    m = sg.mesh(part, resolution=80)
    r = m.print_report(min_wall=1.0)
    assert abs(r.thinnest - 0.6) < 0.01
    x, y, z = r.thinnest_at
    assert abs(x - 8) < 0.05 and abs(y) <= 5 and 2.4 <= z <= 12  # in the fin, which stands on the plate at z = 2.5
    assert m.print_report(min_wall=0.5).thinnest is None  # the fin is thicker than 0.5
    assert sg.mesh(sg.box((20, 20, 5)), resolution=40).print_report(min_wall=4.0).thinnest is None


def test_bad_print_report_options_are_clear_errors(box):
    with pytest.raises(sg.ParameterError, match="'overhang' must be an angle in \\[0, 90\\]"):
        box.print_report(overhang=120)
    with pytest.raises(sg.ParameterError, match="'density' must be > 0"):
        box.print_report(density=-1)
    with pytest.raises(sg.ParameterError, match="'min_wall' must be a length > 0"):
        box.print_report(min_wall=0)
    with pytest.raises(sg.ParameterError, match="unknown unit 'parsec'"):
        box.print_report(units="parsec")
    bare = sg.Mesh(box.vertices, box.faces, box.normals)
    assert abs(bare.print_report().volume - 800) < 1e-3  # what needs no field works without a scene
    with pytest.raises(sg.ParameterError, match="'min_wall' reads the scene's field, and this mesh has no scene"):
        bare.print_report(min_wall=1)


def test_cli_prints_the_checks(tmp_path):
    scene = tmp_path / "fin.py"
    scene.write_text("import sdfgl as sg\nscene = sg.box((20, 20, 5)) | sg.box((0.6, 10, 10)).translate((8, 0, 7))\n")
    r = subprocess.run([sys.executable, "-m", "sdfgl", "mesh", str(scene), "-o", str(tmp_path / "fin.3mf"),
                        "--resolution", "80", "--quiet", "--min-wall", "1", "--density", "1.24", "--units", "mm"],
                       capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert r.returncode == 0, r.stderr
    line = next(x for x in r.stdout.splitlines() if x.startswith("print: "))
    assert "THIN WALL: 0.6 mm at (8," in line and "g at 1.24 g/cm^3" in line
