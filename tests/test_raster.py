"""Raster meshes in a render: drawn first, composited with the march by depth, shaded and
shadowed by the scene (sg.raster, render(meshes=...))."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg

trimesh = pytest.importorskip("trimesh")

SIZE = (160, 120)
CAM = sg.Camera((3.0, 2.5, 4.0), (0.0, 0.0, 0.0), fov=40)
FAR = sg.sphere(0.01).translate((0.0, 0.0, -1000.0))  # an SDF scene out of view: the mesh alone


def box_mesh(extents=(1.2, 1.2, 1.2), at=(0.0, 0.0, 0.0), color="#cccccc"):
    return sg.raster(trimesh.creation.box(extents, trimesh.transformations.translation_matrix(at)), color=color)


def same_depth(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.isclose(a, b, rtol=1e-4, atol=1e-5) | (np.isinf(a) & np.isinf(b))


@pytest.mark.parametrize("camera", [CAM, sg.Camera((3.0, 2.5, 4.0), (0.0, 0.0, 0.0), projection="orthographic",
                                                   ortho_height=3.0)], ids=["perspective", "orthographic"])
def test_depth_is_the_minimum_of_mesh_and_scene(camera):
    box = box_mesh()
    sphere = sg.sphere(0.8).translate((0.0, 0.3, -0.5))  # cuts through the box's faces
    both = sg.render(sphere, camera, SIZE, meshes=[box], outputs=("depth", "normal"))
    scene_only = sg.render(sphere, camera, SIZE, outputs=("depth",)).depth
    mesh_only = sg.render(FAR, camera, SIZE, meshes=[box], outputs=("depth",)).depth
    covered = np.isfinite(mesh_only) & np.isfinite(scene_only)
    # each is in front of the other on some pixels
    assert (covered & (mesh_only < scene_only)).mean() > 0.01 and (covered & (scene_only < mesh_only)).mean() > 0.01
    assert same_depth(both.depth, np.minimum(scene_only, mesh_only)).mean() >= 0.999
    assert np.all(np.isfinite(both.normal)) and not np.isnan(both.depth).any()


def test_an_unbounded_scene_shares_its_moving_origin_with_the_mesh():
    plane = sg.plane((0.0, 1.0, 0.0), 0.3)  # unbounded: the shader origin follows the eye
    both = sg.render(plane, CAM, SIZE, meshes=[box_mesh()], outputs=("depth",)).depth
    scene_only = sg.render(plane, CAM, SIZE, outputs=("depth",)).depth
    mesh_only = sg.render(FAR, CAM, SIZE, meshes=[box_mesh()], outputs=("depth",)).depth
    assert (np.isfinite(mesh_only) & (mesh_only < scene_only)).mean() > 0.02
    assert same_depth(both, np.minimum(scene_only, mesh_only)).mean() >= 0.999


def test_mesh_depth_is_the_ray_parameter():
    # a face of the box facing the camera straight on: t = distance from the eye to the face
    cam = sg.Camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), fov=30)
    res = sg.render(FAR, cam, SIZE, meshes=[box_mesh()], outputs=("depth", "normal"))
    o, d = cam.rays(*SIZE)
    t_face = (0.6 - o[..., 2]) / d[..., 2]
    hit = np.isfinite(res.depth)
    assert hit.mean() > 0.1
    np.testing.assert_allclose(res.depth[hit], t_face[hit], rtol=1e-5)
    np.testing.assert_allclose(res.normal[hit], np.broadcast_to([0.0, 0.0, 1.0], res.normal[hit].shape), atol=1e-5)


def test_mesh_in_front_hides_the_scene_and_the_scene_hides_the_mesh():
    cam = sg.Camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), fov=30)
    centre = (SIZE[1] // 2, SIZE[0] // 2)
    red = box_mesh((0.5, 0.5, 0.5), at=(0.0, 0.0, 1.5), color="red")  # in front of the sphere
    res = sg.render(sg.sphere(1.0), cam, SIZE, meshes=[red], outputs=("depth",), ground=True)
    r, g, b = (int(x) for x in res.color[centre])
    assert r > 2 * g and r > 2 * b
    assert res.depth[centre] == pytest.approx(5.0 - 1.75, rel=1e-4)
    behind = box_mesh((0.5, 0.5, 0.5), at=(0.0, 0.0, -1.5), color="red")  # hidden by the sphere
    res = sg.render(sg.sphere(1.0), cam, SIZE, meshes=[behind], outputs=("depth",), ground=True)
    r, g, b = (int(x) for x in res.color[centre])
    assert abs(r - g) < 20 and abs(r - b) < 20
    assert res.depth[centre] == pytest.approx(4.0, rel=1e-3)


def test_scene_shadow_falls_on_the_mesh():
    plate = box_mesh((4.0, 0.1, 4.0), at=(0.0, -1.0, 0.0))
    cam = sg.Camera((0.0, 4.0, 4.0), (0.0, -1.0, 0.0), fov=50)
    kw = dict(outputs=("depth",), shadows="hard", ao=False)
    lit = sg.render(FAR, cam, SIZE, meshes=[plate], **kw)
    shaded = sg.render(sg.sphere(0.5), cam, SIZE, meshes=[plate], **kw)
    on_plate = same_depth(lit.depth, shaded.depth) & np.isfinite(lit.depth)  # plate pixels in both
    diff = lit.color.astype(int).sum(-1) - shaded.color.astype(int).sum(-1)
    assert (diff[on_plate] > 60).sum() > 100  # a shadow of the sphere on the plate
    assert (diff[on_plate] < -3).sum() == 0  # and nothing lighter
    no_shadow = sg.render(sg.sphere(0.5), cam, SIZE, meshes=[plate], outputs=("depth",), shadows=False, ao=False)
    assert np.array_equal(no_shadow.color[on_plate], lit.color[on_plate])


def test_outputs_and_alpha_follow_the_settings():
    res = sg.render(FAR, CAM, SIZE, meshes=[box_mesh()], alpha=True)
    assert res.depth is None and res.settings.outputs == ("color",)
    assert res.color.shape == (SIZE[1], SIZE[0], 4)
    assert (res.color[..., 3] == 255).mean() > 0.05 and (res.color[..., 3] == 0).mean() > 0.5


def test_raster_reads_a_file_and_takes_a_material(tmp_path):
    path = tmp_path / "box.stl"
    trimesh.creation.box((1.0, 1.0, 1.0)).export(path)
    m = sg.raster(path, color=(1.0, 0.0, 0.0), material={"metallic": 1.0, "emission": (0.2, 0.2, 0.2)})
    assert m.faces.shape == (12, 3) and m.color == (1.0, 0.0, 0.0)
    assert m.material["metallic"] == 1.0 and m.material["specular"] == 0.25
    assert np.allclose(np.linalg.norm(m.normals, axis=1), 1.0, atol=1e-5)


def test_bad_input_is_refused_by_name(tmp_path):
    with pytest.raises(sg.MeshError, match="nope.stl.*no such file"):
        sg.raster(tmp_path / "nope.stl")
    bad = tmp_path / "bad.stl"
    bad.write_text("not a mesh")
    with pytest.raises(sg.MeshError, match="bad.stl"):
        sg.raster(bad)
    with pytest.raises(sg.ParameterError, match="unknown fields.*gloss"):
        sg.raster(trimesh.creation.box(), material={"gloss": 1})
    with pytest.raises(sg.ParameterError, match=r"meshes\[0\].*sg.raster"):
        sg.render(FAR, CAM, SIZE, meshes=[trimesh.creation.box()])
    nan = trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [np.nan, 1, 0]], [[0, 1, 2]], process=False)
    with pytest.raises(sg.MeshError, match="not finite"):
        sg.raster(nan)


def test_cli_render_draws_a_mesh_file(tmp_path):
    trimesh.creation.box((3.0, 3.0, 3.0)).export(tmp_path / "box.stl")  # holds the sphere scene inside
    (tmp_path / "s.py").write_text("import sdfgl as sg\nscene = sg.sphere(1)\n")
    env = {**os.environ, "PYTHONPATH": str(Path(sg.__file__).parents[1])}
    out = tmp_path / "out.npz"
    args = [sys.executable, "-m", "sdfgl", "render", str(tmp_path / "s.py"), "--size", "40x30", "-o", str(out)]
    plain = tmp_path / "plain.npz"
    assert subprocess.run(args[:-1] + [str(plain)], env=env, capture_output=True).returncode == 0
    r = subprocess.run(args + ["--mesh", str(tmp_path / "box.stl"), "--mesh-color", "red"], env=env,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with np.load(out) as meshed, np.load(plain) as alone:
        hit = np.isfinite(alone["depth"])
        assert hit.any() and np.all(meshed["depth"][hit] < alone["depth"][hit])  # the box hides the sphere
        red = meshed["color"][hit].astype(int)
        assert np.all(red[:, 0] > red[:, 1] + 40)
    r = subprocess.run(args + ["--mesh", str(tmp_path / "nope.stl")], env=env, capture_output=True, text=True)
    assert r.returncode != 0 and "nope.stl" in r.stderr and "no such file" in r.stderr


def test_antialiased_edges_of_the_scene_blend_with_the_mesh_behind():
    # an unlit pure-red wall behind the sphere looks like a red background: the sphere's
    # anti-aliased edge must blend with it, not with the sky
    wall = sg.raster(trimesh.creation.box((40.0, 40.0, 0.1), trimesh.transformations.translation_matrix((0, 0, -3))),
                     color=(0.0, 0.0, 0.0), material={"emission": (1.0, 0.0, 0.0), "specular": 0.0})
    cam = sg.Camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), fov=30)
    kw = dict(aa=3, ao=False, shadows=False)
    over_wall = sg.render(sg.sphere(1.0), cam, SIZE, meshes=[wall], **kw).color.astype(int)
    over_red = sg.render(sg.sphere(1.0), cam, SIZE, background="red", **kw).color.astype(int)
    sky = sg.render(sg.sphere(1.0), cam, SIZE, **kw).color.astype(int)
    edge = (np.abs(sky - over_red).max(-1) > 0) & (np.abs(over_red - [255, 0, 0]).max(-1) > 0)
    assert edge.sum() > 50  # the partly covered pixels of the silhouette
    assert np.abs(over_wall - over_red).max() <= 1
