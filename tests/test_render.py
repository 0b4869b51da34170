"""Rendering on real EGL: every node renders, geometry matches closed-form answers."""
import numpy as np
import pytest

import sdfgl as sg

from .conftest import all_primitives, no_nan

ALL = ("color", "depth", "normal", "steps")


@pytest.mark.parametrize("name", sorted(all_primitives()))
def test_every_primitive_renders(renderer, name):
    node = all_primitives()[name]
    cam = sg.OrbitCamera(distance=4, yaw=25, pitch=25)
    res = renderer.render(node.color(0.8, 0.3, 0.2), cam, (48, 40), outputs=ALL)
    assert res.color.shape == (40, 48, 3) and res.color.dtype == np.uint8
    assert res.depth.shape == (40, 48) and res.depth.dtype == np.float32
    assert res.normal.shape == (40, 48, 3) and res.steps.dtype == np.int32
    no_nan(res)
    hit = np.isfinite(res.depth)
    assert 0.02 < hit.mean() < 1.0 or name == "plane"
    assert hit[19:22, 23:26].any(), "the object at the origin must cover the image centre"  # the torus hole: not the centre ray
    n = res.normal[hit]
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-3)
    # hit points lie on the surface: the float64 twin is ~0 there
    o, d = cam.rays(48, 40)
    p = o[hit] + d[hit] * res.depth[hit][:, None].astype(np.float64)
    footprint = res.depth[hit] * cam.pixel_angle(40)
    assert np.all(np.abs(node.distance(p)) <= footprint + 1e-5)


@pytest.mark.parametrize("analytic", [False, True], ids=["marched", "closed-form"])
def test_unit_sphere_depth_and_silhouette(renderer, analytic):
    cam = sg.OrbitCamera(distance=4, yaw=0, pitch=0, fov=40)
    w = h = 65  # odd: the centre pixel's ray passes through the sphere centre
    res = renderer.render(sg.sphere(1), cam, (w, h), outputs=ALL, shadows=False, ao=False, analytic=analytic)
    centre = float(res.depth[h // 2, w // 2])
    assert abs(centre - 3.0) < 1e-5, centre
    o, d = cam.rays(w, h)
    closest = np.linalg.norm(np.cross(d, -o), axis=-1)  # distance from the centre to each ray line
    analytic = closest < 1.0
    rendered = np.isfinite(res.depth)
    mismatch = analytic != rendered
    # any disagreement lies within one pixel footprint of the true silhouette: the cone
    # hit test counts a ray that passes within hit_scale (0.25) footprints as a hit
    footprint = 3.0 * cam.pixel_angle(h)
    assert np.all(np.abs(closest[mismatch] - 1.0) < footprint)
    assert np.all(rendered[mismatch])  # only grazing near-misses, never a lost hit
    perimeter_px = 2 * np.pi * analytic.sum() ** 0.5 / np.sqrt(np.pi)
    assert mismatch.sum() < 0.6 * perimeter_px
    # normals point from the centre to the hit point
    p = o[rendered] + d[rendered] * res.depth[rendered][:, None].astype(np.float64)
    want = p / np.linalg.norm(p, axis=1, keepdims=True)
    cosang = np.sum(want * res.normal[rendered], axis=1)
    assert np.degrees(np.arccos(np.clip(cosang, -1, 1))).max() < 0.1


def test_rays_match_shader_layout():
    cam = sg.Camera.look_at((0, 0, 5), (0, 0, 0), fov=90)
    o, d = cam.rays(4, 2)
    assert o.shape == d.shape == (2, 4, 3)
    assert np.allclose(np.linalg.norm(d, axis=-1), 1)
    assert d[0, 0, 1] > 0 and d[1, 0, 1] < 0  # row 0 on top
    assert d[0, 0, 0] < 0 and d[0, 3, 0] > 0  # column 0 on the left


def test_image_rows_run_top_to_bottom(renderer):
    # a sphere above the view centre shows in the upper half of the image
    res = renderer.render(sg.sphere(0.5).translate((0, 1, 0)), sg.Camera.look_at((0, 0, 5), (0, 0, 0)),
                          (32, 32), outputs=("color", "depth"))
    rows = np.where(np.isfinite(res.depth).any(axis=1))[0]
    assert rows.max() < 16


def test_aa_smooths_edges_and_keeps_centre_outputs(renderer):
    cam = sg.OrbitCamera(distance=4, yaw=10, pitch=10)
    s = sg.box(1.2)
    one = renderer.render(s, cam, (40, 40), aa=1, outputs=("color", "depth"))
    four = renderer.render(s, cam, (40, 40), aa=3, outputs=("color", "depth"))
    assert np.array_equal(np.isfinite(one.depth), np.isfinite(four.depth))  # depth: pixel centre ray
    levels = lambda img: len(np.unique(img.reshape(-1, 3), axis=0))  # noqa: E731
    assert levels(four.color) > levels(one.color)


def test_colour_is_carried_through_booleans(renderer):
    red, blue = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)
    s = sg.box(1.0).color(*red) - sg.sphere(0.3).translate((0, 0, 0.5)).color(*blue)
    res = renderer.render(s, sg.Camera.look_at((0, 0, 4), (0, 0, 0)), (41, 41), shadows=False, ao=False)
    centre = res.color[20, 20].astype(int)   # inside the spherical dent: blue
    side = res.color[20, 14].astype(int)     # the box face: red
    assert centre[2] > centre[0] and side[0] > side[2]


def test_ground_plane_is_hit_analytically(renderer):
    res = renderer.render(sg.sphere(0.5), sg.OrbitCamera(distance=4, pitch=30), (32, 24), ground=True,
                          outputs=("color", "depth", "normal"))
    assert np.isfinite(res.depth[-1]).all()  # bottom row sees the ground
    assert np.allclose(res.normal[-1], (0, 1, 0))
    no_nan(res)


def test_camera_far_from_origin_keeps_precision(renderer):
    # a unit sphere 1e5 units from the origin: float32 alone would see steps of ~0.008
    c = np.array([1e5, 2e5, -1e5])
    cam = sg.OrbitCamera(target=c, distance=4, yaw=0, pitch=0, fov=40)
    res = renderer.render(sg.sphere(1).translate(c), cam, (33, 33), outputs=("color", "depth"))
    assert abs(float(res.depth[16, 16]) - 3.0) < 1e-4


def test_bad_render_arguments(renderer):
    with pytest.raises(sg.ParameterError, match="'size' must be two integers"):
        renderer.render(sg.sphere(1), size=(0, 10))
    with pytest.raises(sg.ParameterError, match="'scene' must be an sdfgl node"):
        renderer.render(None)
    with pytest.raises(sg.ParameterError, match="setting 'outputs' has unknown entries"):
        renderer.render(sg.sphere(1), size=(4, 4), outputs=("colour",))
    with pytest.raises(sg.ParameterError, match="'eye' and 'target' coincide"):
        sg.Camera.look_at((1, 1, 1), (1, 1, 1))


def test_save_png(renderer, tmp_path):
    res = renderer.render(sg.sphere(1), size=(16, 12))
    path = res.save(tmp_path / "a.png")
    from PIL import Image
    assert Image.open(path).size == (16, 12)
    with pytest.raises(sg.SdfglError, match="cannot write image file"):
        res.save(tmp_path / "missing-dir" / "a.png")


def test_lone_sphere_and_plane_are_intersected_not_marched(renderer):
    cam = sg.OrbitCamera(distance=4, yaw=0, pitch=0, fov=40)
    for scene, want in [(sg.sphere(0.5).scale(2).color(1, 0, 0), 3.0),
                        (sg.plane((0, 1, 0), (0, -0.5, 0)).rotate(10, (1, 0, 0)), 4 + 0.5 / np.sin(np.radians(10)))]:
        a = renderer.render(scene, cam, (33, 33), outputs=ALL)
        m = renderer.render(scene, cam, (33, 33), outputs=ALL, analytic=False)
        assert a.steps.max() == 0 and m.steps.max() > 0
        assert abs(float(a.depth[16, 16]) - want) < 1e-5 * want
        assert abs(float(m.depth[16, 16]) - want) < 0.05 * want
        no_nan(a)
    assert "march_analytic" not in sg.compile(sg.sphere(1) | sg.box(1))
    assert "closed form" in sg.compile(sg.sphere(1)) and "closed form" not in sg.compile(sg.sphere(1), analytic=False)


@pytest.mark.parametrize("alpha", [False, True], ids=["rgb", "rgba"])
def test_read_back_matches_the_raw_textures_flipped(renderer, alpha):
    # odd width: RGB rows of 3 * 37 bytes are not 4-byte aligned; an asymmetric scene shows any flip or shift
    w, h = 37, 23
    scene = sg.box(1).translate((0.4, 0.3, 0)).color(0.9, 0.2, 0.1) | sg.sphere(0.5).translate((-1, -0.5, 0))
    res = renderer.render(scene, sg.OrbitCamera(distance=5, yaw=30, pitch=20), (w, h), outputs=ALL, alpha=alpha)

    def raw(name, comps, dtype):
        tex = renderer.targets.get(renderer.ctx, (w, h), res.settings.outputs).textures[name]
        return np.frombuffer(tex.read(), dtype=dtype).reshape(h, w, comps)[::-1]

    color, depth, normal, steps = renderer.run(lambda: (raw("color", 4, np.uint8), raw("depth", 1, np.float32),
                                                        raw("normal", 4, np.float32), raw("steps", 1, np.float32)))
    assert np.array_equal(res.color, color[..., :4 if alpha else 3])
    assert np.array_equal(res.depth, np.where(depth[..., 0] < 0, np.inf, depth[..., 0]))
    assert np.array_equal(res.normal, normal[..., :3])
    assert np.array_equal(res.steps, steps[..., 0].astype(np.int32))
    assert np.isfinite(res.depth).any() and not np.isfinite(res.depth).all()
    for a in (res.color, res.depth, res.normal, res.steps):
        assert a.flags.c_contiguous
