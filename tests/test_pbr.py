"""Path-traced renders through Mitsuba 3 (sdfgl.pbr): real Mitsuba, real EGL sampling."""
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import sdfgl as sg
from sdfgl.pbr import Blend, Material
from sdfgl.pbr.backend import FALLBACK, variant_works
from sdfgl.pbr.field_grid import auto_resolution, cell_size, scene_box
from sdfgl.pbr.lighting import Sky, Sun

ROOT = Path(__file__).resolve().parents[1]
mi = pytest.importorskip("mitsuba", reason="sdfgl[pbr] (mitsuba) is part of the test extra")

CSG = (sg.sphere(1) & sg.box(1.5)) - (sg.cylinder(0.5, 4).orient(sg.X) | sg.cylinder(0.5, 4)
                                      | sg.cylinder(0.5, 4).orient(sg.Z))
CAM = sg.OrbitCamera(distance=5, yaw=30, pitch=20)


def edge_pixels(hit: np.ndarray) -> np.ndarray:
    """Pixels whose 3x3 neighbourhood holds both hits and misses."""
    h, w = hit.shape
    pad = np.pad(hit, 1, mode="edge")
    nb = np.stack([pad[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] for dy in (-1, 0, 1) for dx in (-1, 0, 1)])
    return nb.any(0) & ~nb.all(0)


@pytest.mark.slow
def test_silhouette_matches_the_egl_render():
    """Coverage against coverage: the path tracer's alpha (share of a pixel's samples that hit)
    and the EGL render's alpha at aa 4 (16 samples a pixel) agree within 0.2 on the edge
    pixels. (Thresholding both at 0.5 flips pixels whose coverage is near 0.5 by sampling
    noise alone: 96-97 % of edge pixels agree that way.)"""
    size = (160, 120)
    img = sg.render_pbr(CSG, CAM, size, spp=64, quality=2)
    egl = sg.render(CSG, CAM, size, aa=4, alpha=True).color[..., 3] / 255.0
    edge = edge_pixels(egl > 0.5)
    close = np.abs(img.alpha - egl) <= 0.2
    assert edge.sum() > 300
    assert close[edge].mean() > 0.98, f"edge pixels within 0.2 coverage: {close[edge].mean():.4f}"
    assert close.mean() > 0.995
    assert np.isfinite(img.rgba).all() and np.isfinite(img.hdr).all()


def test_colours_come_from_the_scene_and_materials_map_to_bsdfs():
    scene = sg.sphere(0.7).translate((-1, 0, 0)).color(0.9, 0.1, 0.1) | sg.box(1.2).translate((1, 0, 0)).color(0.1, 0.1, 0.9)
    cam = sg.Camera.look_at((0, 0, 6), (0, 0, 0), fov=40)
    img = sg.render_pbr(scene, cam, (64, 32), spp=16)
    left, right = img.hdr[13:19, 22:28].mean((0, 1)), img.hdr[13:19, 36:42].mean((0, 1))
    assert left[0] > 2 * left[2] and right[2] > 2 * right[0]
    assert img.settings["material"] == "diffuse"

    def kind(m: Material) -> str:
        return sg.to_mitsuba(sg.sphere(1), material=m, size=(8, 8), spp=1)["sdf_bsdf"]["type"]
    assert kind(Material(color=(0.9, 0.6, 0.2), metallic=1, roughness=0.3)) == "roughconductor"
    assert kind(Material(metallic=1, roughness=0)) == "conductor"
    assert kind(Material(transmission=1, roughness=0)) == "dielectric"
    assert kind(Material(specular=0.5, roughness=0.2, color=(1, 1, 1))) == "roughplastic"
    assert kind(Material(specular=0.5, roughness=0.2)) == "principled"
    assert kind(Material()) == "diffuse"
    with pytest.raises(sg.ParameterError, match="roughness"):
        Material(roughness=2)
    with pytest.raises(sg.ParameterError, match="color"):
        Material(color="red")


def test_blend_splits_two_materials_across_a_field():
    red, blue = Material(color=(0.9, 0.05, 0.05)), Material(color=(0.05, 0.05, 0.9))
    look = Blend(red, blue, boundary=sg.plane((0, 1, 0)), width=0.05)   # red below y = 0, blue above
    d = sg.to_mitsuba(sg.sphere(1), material=look, size=(8, 8), spp=1)
    assert d["sdf_bsdf"]["type"] == "blendbsdf"
    img = sg.render_pbr(sg.sphere(1), sg.Camera.look_at((0, 0, 4), fov=40), (48, 48), spp=16, material=look)
    top, bottom = img.hdr[10:18, 20:28].mean((0, 1)), img.hdr[30:38, 20:28].mean((0, 1))
    assert top[2] > 2 * top[0] and bottom[0] > 2 * bottom[2]
    with pytest.raises(sg.ParameterError, match="width"):
        Blend(red, blue, sg.plane(), width=0)


def test_fields_that_are_not_distances_render_from_their_sign():
    cam = sg.Camera.look_at((0, 0, 4), fov=40)
    ref = sg.render_pbr(sg.sphere(1), cam, (48, 48), spp=4).alpha > 0.5
    for scene in (sg.implicit("x**2 + y**2 + z**2 - 1", bounds=((-1.2,) * 3, (1.2,) * 3)),
                  sg.sphere(1).twist(30)):
        got = sg.render_pbr(scene, cam, (48, 48), spp=4).alpha > 0.5
        assert (got != ref).sum() <= 0.03 * ref.sum(), type(scene).__name__


def test_unbounded_scenes_need_bounds():
    with pytest.raises(sg.ParameterError, match="bounds"):
        sg.render_pbr(sg.plane(), size=(16, 16), spp=1)
    img = sg.render_pbr(sg.plane(), sg.Camera.look_at((0, 2, 4)), (32, 24), spp=1, bounds=((-5, -1, -5), (5, 1, 5)))
    assert img.alpha[-1].mean() > 0.9 and img.alpha[0].mean() < 0.1
    with pytest.raises(sg.ParameterError, match="spp"):
        sg.render_pbr(sg.sphere(1), spp=0)
    with pytest.raises(sg.ParameterError, match="resolution"):
        sg.render_pbr(sg.sphere(1), spp=1, resolution=5)


def test_variant_is_chosen_and_reported():
    img = sg.render_pbr(sg.sphere(1), size=(16, 12), spp=1, variant="scalar_rgb")
    assert img.settings["variant"] == "scalar_rgb" and img.settings["variant_choice"] == "asked for"
    auto = sg.render_pbr(sg.sphere(1), size=(16, 12), spp=1)
    assert auto.settings["variant"] in mi.variants()
    ok, why = variant_works(FALLBACK)
    assert ok, why
    with pytest.raises(sg.SdfglError, match="not available"):
        sg.render_pbr(sg.sphere(1), size=(8, 8), spp=1, variant="no_such_variant")


def test_images_save_as_png_transparent_png_and_exr(tmp_path):
    img = sg.render_pbr(sg.sphere(1), sg.Camera.look_at((0, 0, 4), fov=40), (40, 30), spp=8)
    rgba = np.asarray(Image.open(img.save(tmp_path / "a.png", transparent=True)))
    assert rgba.shape == (30, 40, 4) and rgba[15, 20, 3] == 255 and rgba[0, 0, 3] == 0
    rgb = np.asarray(Image.open(img.save(tmp_path / "b.png")))
    assert rgb.shape == (30, 40, 3) and rgb[0, 0].mean() > 150       # the sky behind
    exr = mi.Bitmap(str(img.save(tmp_path / "c.exr")))
    assert np.allclose(np.asarray(exr)[..., 3], img.alpha, atol=1e-6)
    assert img._repr_png_().startswith(b"\x89PNG")


def test_cli_writes_the_image_and_reports_the_variant(tmp_path):
    scene = tmp_path / "s.py"
    scene.write_text("import sdfgl as sg\nscene = sg.sphere(1).color(0.2, 0.8, 0.3)\n")
    out = tmp_path / "o.png"
    r = subprocess.run([sys.executable, "-m", "sdfgl.cli", "pbr", str(scene), "-o", str(out), "--size", "32x24",
                        "--spp", "4"], capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    assert "Mitsuba" in r.stdout and "path tracing" in r.stderr
    assert Image.open(out).size == (32, 24)


def test_missing_mitsuba_gives_a_clear_message(tmp_path):
    code = ("import sys; sys.modules['mitsuba'] = None\n"
            "import sdfgl as sg\n"
            "try:\n    sg.render_pbr(sg.sphere(1), size=(8, 8), spp=1)\n"
            "except sg.SdfglError as e:\n    print('ERR', e)\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=ROOT,
                       env={**os.environ, "XDG_CACHE_HOME": str(tmp_path)})
    assert "ERR" in r.stdout and "pip install 'sdfgl[pbr]'" in r.stdout, r.stdout + r.stderr
    assert not list(tmp_path.glob("**/*.json"))  # nothing cached without Mitsuba
    json.dumps(r.stdout)


def test_far_away_scene_renders_like_one_at_the_origin():
    near = sg.render_pbr(sg.sphere(1), sg.Camera.look_at((0, 0, 4), fov=40), (40, 40), spp=4)
    c = np.array([1e5, -3e4, 0.0])
    far = sg.render_pbr(sg.sphere(1).translate(c), sg.Camera.look_at(c + (0, 0, 4), c, fov=40), (40, 40), spp=4)
    assert far.settings["offset"] == c.tolist() and near.settings["offset"] == [0.0, 0.0, 0.0]
    assert ((near.alpha > 0.5) != (far.alpha > 0.5)).sum() <= 4


def test_node_materials_and_orthographic_cameras_carry_over():
    metal = sg.sphere(0.6).material((0.9, 0.7, 0.3), metallic=1.0, shininess=200).translate((-0.8, 0, 0))
    matte = sg.box(1.0).color(0.2, 0.4, 0.8).translate((0.8, 0, 0))
    scene = metal | matte
    d = sg.to_mitsuba(scene, size=(8, 8), spp=1, geometry="grid")
    assert d["sdf_bsdf"]["type"] == "principled"
    metallic = np.asarray(d["sdf_bsdf"]["metallic"]["volume"]["grid"])
    assert metallic.max() > 0.9 and metallic.min() < 0.1          # metal on the sphere only
    m = sg.to_mitsuba(scene, size=(64, 48), spp=1, geometry="mesh")
    assert m["sdf_bsdf"]["metallic"] == {"type": "mesh_attribute", "name": "vertex_metallic"}
    per_vertex = np.asarray(mi.traverse(m["sdf_mesh"])["vertex_metallic"])
    assert per_vertex.max() > 0.9 and per_vertex.min() < 0.1     # per vertex, on the mesh path
    cam = sg.Camera.look_at((0, 0, 5), projection="orthographic", ortho_height=2.0)
    size = (64, 32)
    img = sg.render_pbr(sg.box(1.0), cam, size, spp=4)
    egl = np.isfinite(sg.render(sg.box(1.0), cam, size, outputs=("color", "depth")).depth)
    assert img.settings["projection"] == "orthographic"
    assert egl.sum() == 16 * 16 and ((img.alpha > 0.5) != egl).sum() <= 8


def test_unknown_options_and_bad_seeds_are_named():
    with pytest.raises(sg.ParameterError, match=r"render_pbr: unknown option 'colour'; it takes size, spp, .*seed"):
        sg.render_pbr(sg.sphere(1), size=(8, 8), spp=1, colour=(1, 0, 0))
    with pytest.raises(sg.ParameterError, match=r"to_mitsuba: unknown option 'seed'"):
        sg.to_mitsuba(sg.sphere(1), seed=1)
    with pytest.raises(sg.ParameterError, match=r"render_pbr: 'seed' must be an integer in 0\.\.65535, got 'x'"):
        sg.render_pbr(sg.sphere(1), size=(8, 8), spp=1, seed="x")


def silhouette_agreement(img, egl_hit: np.ndarray) -> float:
    """Share of the EGL render's silhouette-edge pixels (mixed 3x3 neighbourhood of its
    pixel-centre hits) where the path tracer's coverage is on the same side of 0.5."""
    edge = edge_pixels(egl_hit)
    return float(((img.alpha > 0.5) == egl_hit)[edge].mean())


def egl_hits(scene, cam, size) -> np.ndarray:
    return np.isfinite(sg.render(scene, cam, size, outputs=("color", "depth")).depth)


def test_the_mesh_path_matches_the_egl_silhouette():
    """The mesh (vertices on the exact surface, sharp CSG edges) against the EGL render's
    pixel-centre hits: the grid path agrees on about 97 % of these pixels (the trilinear
    interpolant rounds the edges off), the mesh path on 99.9 % (256 spp)."""
    size = (160, 120)
    img = sg.render_pbr(CSG, CAM, size, spp=256, max_depth=2, geometry="mesh")
    assert img.settings["geometry"] == "mesh" and img.settings["mesh_faces"] > 10000
    got = silhouette_agreement(img, egl_hits(CSG, CAM, size))
    assert got >= 0.99, f"silhouette-edge pixels agreeing: {got:.4f}"


def test_a_plate_one_grid_cell_thick_renders_on_the_mesh_path():
    size = (160, 120)
    cam = sg.OrbitCamera(distance=3.5, yaw=30, pitch=55)

    def plate(t: float):
        return sg.box((1.6, t, 1.2)).orient((0.25, 1, 0.15))
    lo, hi = scene_box(plate(0.02))
    cell = cell_size(lo, hi, auto_resolution(lo, hi, cam.eye, cam.pixel_angle(size[1]), 1.0))
    scene = plate(cell)                                   # one cell of the grid path's default grid
    hit = egl_hits(scene, cam, size)
    assert hit.sum() > 2000
    img = sg.render_pbr(scene, cam, size, spp=256, max_depth=2)
    assert img.settings["geometry"] == "mesh", img.settings["geometry_choice"]
    assert (img.alpha[hit] > 0.5).mean() >= 0.99
    got = silhouette_agreement(img, hit)
    assert got >= 0.99, f"silhouette-edge pixels agreeing: {got:.4f}"


def test_emissive_materials_light_up_on_the_mesh_path():
    lamp = sg.sphere(0.4).material((0.8, 0.8, 0.8), emission=(1.0, 0.15, 0.05)).translate((-0.6, 0, 0))
    scene = lamp | sg.box((0.6, 1.2, 1.2)).color(0.8, 0.8, 0.8).translate((0.5, 0, 0))
    cam = sg.Camera.look_at((0, 0, 4), fov=40)
    dark = {"sky": Sky(intensity=0.02), "sun": Sun(intensity=0.0)}
    img = sg.render_pbr(scene, cam, (64, 48), spp=16, geometry="mesh", **dark)
    assert img.settings["emitters"] == 1 and "not_rendered" not in img.settings
    glow = img.hdr[20:28, 19:26].mean((0, 1))                  # the lamp, seen directly
    assert glow[0] > 0.8 and glow[0] > 4 * glow[2]
    assert (img.rgba[img.alpha == 0][:, :3] < 1e-3).all()      # the sky seen past the scene is taken out
    grid = sg.render_pbr(scene, cam, (64, 48), spp=16, geometry="grid", **dark)
    assert "emission" in grid.settings["not_rendered"]
    assert grid.hdr[20:28, 19:26].mean((0, 1))[0] < 0.5 * glow[0]


def test_a_bad_geometry_is_named():
    with pytest.raises(sg.ParameterError, match="'geometry' must be one of 'auto', 'mesh', 'grid', got 'voxels'"):
        sg.render_pbr(sg.sphere(1), size=(8, 8), spp=1, geometry="voxels")
    with pytest.raises(sg.ParameterError, match="geometry"):
        sg.to_mitsuba(sg.sphere(1), geometry=3)
    assert sg.to_mitsuba(sg.plane(), size=(8, 8), spp=1, bounds=((-1, -1, -1), (1, 1, 1)))["sdf_0"]["type"] == "sdfgrid"
