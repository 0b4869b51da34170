"""Accuracy against closed-form ground truth (tests/closed_form.py, independent of
sdfgl.reference), and the failure classes of the accuracy audit that are not a depth figure:
NaN, bounds, shadows, anti-aliased thin wires, implicit fields by default."""
import numpy as np
import pytest

import sdfgl as sg

from . import closed_form as cf

DEPTH_NORMAL = ("color", "depth", "normal")


def _render(scene, cam, size, **kw):
    return sg.render(scene, cam, size, outputs=DEPTH_NORMAL, shadows=False, ao=False, **kw)


def _footprint_errors(res, cam, size, t_true, n_true):
    w, h = size
    t = res.depth.reshape(-1).astype(np.float64)
    both = np.isfinite(t) & np.isfinite(t_true)
    fp = t_true[both] * cam.pixel_angle(h)
    derr = np.abs(t[both] - t_true[both]) / fp
    cos = np.sum(res.normal.reshape(-1, 3)[both] * n_true[both], axis=1)
    nerr = np.degrees(np.arccos(np.clip(cos, -1, 1)))
    lost = int((~np.isfinite(t) & np.isfinite(t_true)).sum())
    false = int((np.isfinite(t) & ~np.isfinite(t_true)).sum())
    return derr, nerr, lost, false, int(both.sum())


@pytest.mark.parametrize("deg", [0.5, 1.0, 2.0, 4.0])
def test_grazing_face_depth_against_closed_form(deg):
    # the example: a 1e-3 slab tilted by deg, 160x120; the old clamp put hits 3.9
    # footprints short at 2 degrees and 21 at 0.5
    size = (160, 120)
    cam = sg.Camera.look_at((0, 0, 4), (0, 0, 0), fov=30)
    res = _render(sg.box((2, 1e-3, 2)).rotate(deg, (1, 0, 0)), cam, size)
    o, d = cam.rays(*size)
    t, n = cf.box(o.reshape(-1, 3), d.reshape(-1, 3), (0, 0, 0), (1, 5e-4, 1), cf.rotation(deg, (1, 0, 0)))
    derr, nerr, lost, false, both = _footprint_errors(res, cam, size, t, n)
    assert both > 100
    assert np.median(derr) <= 0.01 and np.percentile(derr, 99) <= 0.25, (np.median(derr), np.percentile(derr, 99))
    assert lost <= 0.002 * both and false <= 0.002 * both


@pytest.mark.parametrize("ratio", [1e2, 1e4])
@pytest.mark.parametrize("offset", [0.0, 1.234567e5, 9.87654321e6])
def test_flat_face_normals_small_beside_big_far_from_origin(ratio, offset):
    # a cube of 200/ratio on a floor 200 wide, the pair moved off any power-of-two grid
    s = 200.0 / ratio
    c = np.array([offset, -0.37 * offset, 0.61 * offset])
    cube_c = c + (0.3 * s, s / 2, -0.2 * s)
    scene = (sg.box((200, 1, 200)).translate(tuple(c + (0, -0.5, 0))) | sg.box(s).translate(tuple(cube_c)))
    cam = sg.Camera.look_at(tuple(cube_c + (2.2 * s, 1.3 * s, 2.6 * s)), tuple(cube_c), fov=40)
    size = (64, 48)
    res = _render(scene, cam, size)
    o, d = cam.rays(*size)
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    t, n = cf.first(cf.box(o, d, c + (0, -0.5, 0), (100, 0.5, 100)), cf.box(o, d, cube_c, (s / 2,) * 3))
    derr, nerr, lost, false, both = _footprint_errors(res, cam, size, t, n)
    assert both > 0.9 * size[0] * size[1]
    assert np.percentile(nerr, 99) <= 1.0, np.percentile(nerr, 99)
    assert np.median(derr) <= 0.01 and lost <= 3 and false <= 3


def test_telephoto_and_far_sphere_against_closed_form():
    for cam, r, size in ((sg.Camera.look_at((0.3, 0.2, 1000), (0, 0, 0), fov=0.5), 1.0, (64, 48)),
                         (sg.OrbitCamera(distance=3.2e4, yaw=30, pitch=20), 1e4, (48, 36))):
        res = _render(sg.sphere(r), cam, size, analytic=False)
        o, d = cam.rays(*size)
        t, n = cf.sphere(o.reshape(-1, 3), d.reshape(-1, 3), (0, 0, 0), r)
        derr, nerr, lost, false, both = _footprint_errors(res, cam, size, t, n)
        assert both > 50 and lost == 0 and false == 0
        assert np.percentile(derr, 99) <= 0.25 and np.percentile(nerr, 99) <= 1.0


def test_bounded_scenes_are_not_clipped_by_max_dist():
    for node in (sg.sphere(300), sg.sphere(1e4), sg.torus(1e4, 3e3)):
        for analytic in (True, False):
            res = sg.render(node, size=(32, 24), outputs=("depth",), analytic=analytic)
            assert np.isfinite(res.depth).mean() > 0.1, (node.label(), analytic)
    assert "#define MAX_DIST 1000.0" in sg.compile(sg.plane((0, 1, 0), (0, 0, 0)) | sg.sphere(1))


@pytest.mark.slow
def test_no_nan_from_overflowing_fields_or_far_cameras():
    with pytest.raises(sg.ParameterError, match="exponent 1000"):  # the expression parser's limit
        sg.implicit("x**1000 + y**1000 + z**1000 - 1")
    s = sg.implicit("x**64 + y**64 + z**64 - 1")  # the largest exponent accepted: overflows float32 all the same
    for method in ("newton", "forward_newton"):
        res = sg.render(s, size=(48, 36), outputs=DEPTH_NORMAL, method=method)
        assert not np.isnan(res.depth).any() and np.isfinite(res.normal).all()
    with pytest.raises(sg.ParameterError, match="float32"):
        sg.render(sg.sphere(1), sg.Camera.look_at((0, 0, 1e300), (0, 0, 0)), (8, 6))


@pytest.mark.slow
def test_overflowing_implicit_fields_are_drawn_at_the_right_depth():
    # x**64 overflows float32 beyond |x| = 4 (its gradient sooner): such fields are written in
    # extended range (m * 2^e), so f / |grad f| is finite wherever the ray starts
    cam = sg.Camera.look_at((0.3, 0.2, 4), (0, 0, 0), fov=40)
    o, d = cam.rays(32, 24)
    for expr, exact_in in (("x**64 + y**64 + z**64 - 1", True), ("x**40 + y**40 + z**40 - 1", True),
                           ("1e6*(x**2 + y**2 + z**2 - 1)", False),
                           ("(x**2 + y**2 + z**2 - 1)*((x - 3)**2 + y**2 + z**2 - 1)", False)):
        s = sg.implicit(expr)
        assert s.extended == exact_in, expr
        for method in ("auto", "forward_newton"):
            res = sg.render(s, cam, (32, 24), outputs=DEPTH_NORMAL, method=method)
            assert res.settings.method == ("newton" if method == "auto" else method)
            assert not np.isnan(res.depth).any() and np.isfinite(res.normal).all()
            hit = np.isfinite(res.depth)
            assert hit.sum() > 150, (expr, method, hit.sum())
            # the centre ray: the rounded cube's face z = 1 (x, y < 0.05 there), or the unit sphere
            t = cf.sphere(o[12:13, 16], d[12:13, 16], (0, 0, 0), 1.0)[0][0] if not exact_in else \
                (1.0 - o[12, 16, 2]) / d[12, 16, 2]
            assert abs(float(res.depth[12, 16]) - t) < 1e-3 * t, (expr, method, res.depth[12, 16], t)


def test_forward_newton_from_a_millionth_of_the_scene_size():
    cam = sg.Camera.look_at((0, 0, 50 + 1e-4), (0, 0, 0), fov=60)
    res = sg.render(sg.box(100), cam, (16, 12), outputs=("depth",), method="forward_newton")
    o, d = cam.rays(16, 12)
    t_true = 1e-4 / d[..., 2] * -1
    assert np.all(res.depth > 0)
    eye32 = abs(float(np.float32(50 + 1e-4)) - (50 + 1e-4))  # the eye itself rounds to float32
    assert np.abs(res.depth - t_true).max() <= 2 * eye32 + 1e-7


def _luminance(img):
    lin = (img.astype(np.float64) / 255.0) ** 2.2
    return lin @ np.array([0.2126, 0.7152, 0.0722])


def test_soft_shadows_leave_no_isolated_dark_pixels():
    # where the normal faces the key light the old penumbra estimate went to 0: one dark
    # pixel in an evenly lit patch. Scan every interior pixel against its 8 neighbours.
    key = np.array([0.5, 0.7, 0.4]) / np.linalg.norm([0.5, 0.7, 0.4])
    scenes = [sg.sphere(1), sg.rounded_box(1.5, 0.3), sg.sphere(0.7) | sg.box(1.2).translate((1.2, 0, 0))]
    for scene in scenes:
        for eye in (2.6 * key + (0, 0.3, 0), (0.5, 2.0, 3.0)):
            cam = sg.Camera.look_at(tuple(eye), (0, 0, 0), fov=60)
            res = sg.render(scene, cam, (96, 72), shadows="soft", ao=False, outputs=("color", "depth"))
            lum = _luminance(res.color)
            hit = np.isfinite(res.depth)
            core = hit.copy()
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    core &= np.roll(np.roll(hit, dy, 0), dx, 1)
            nb = np.stack([np.roll(np.roll(lum, dy, 0), dx, 1) for dy in (-1, 0, 1) for dx in (-1, 0, 1)
                           if dy or dx])
            speck = core & (lum < 0.6 * nb.min(axis=0))
            speck[[0, -1], :] = speck[:, [0, -1]] = False
            assert not speck.any(), f"{scene.label()}: dark specks at {np.argwhere(speck)[:5].tolist()}"


@pytest.mark.parametrize("aa", [2, 3])
def test_sub_pixel_wire_stays_visible_with_anti_aliasing(aa):
    # a black wire 0.1 pixel wide, at a slant off the pixel diagonal so the samples see
    # every phase; its average coverage per pixel row must be about its width per row
    size = (96, 96)
    cam = sg.Camera.look_at((0, 0, 4), (0, 0, 0), fov=30)
    fp = 4 * cam.pixel_angle(size[1])
    a, b = np.array([-0.6, -0.47, 0.0]), np.array([0.6, 0.61, 0.0])
    wire = sg.capsule(tuple(a), tuple(b), 0.05 * fp).color(0, 0, 0)
    far = sg.sphere(1e-3).translate((0, 0, -50))  # far behind: keeps the box but draws nothing here
    bg = _luminance(sg.render(far, cam, size, aa=aa, shadows=False, ao=False).color)
    img = _luminance(sg.render(wire | far, cam, size, aa=aa, shadows=False, ao=False).color)
    cover = np.clip((bg - img) / np.maximum(bg, 1e-6), 0, 1)
    rows = cover[30:66].sum(axis=1)
    u = (b - a) / np.linalg.norm(b - a)
    expected = 0.1 / abs(u[0])  # pixels of a row the wire's width covers
    assert 0.5 * expected < rows.mean() < 2.0 * expected, rows.mean()
    seen = np.nonzero(rows > 0)[0]  # visible along its length, not in a few rows
    assert seen.size > 0.3 * rows.size and np.diff(seen).max() <= 4


def test_extended_range_implicit_fields_match_the_twin_where_float32_overflows():
    rng = np.random.default_rng(3)
    pts = np.concatenate([rng.uniform(-1.2, 1.2, (400, 3)), rng.uniform(-300, 300, (400, 3))])
    for expr in ("x**64 + y**64 + z**64 - 1", "x**9*y - z**3 + 2", "exp(x**2 + y**2 + z**2) - E",
                 "cosh(x) + sqrt(y**2 + 1)*z**40 - 3", "(x**2 + y**2 + z**2 - 1)**12 - x*y"):
        s = sg.implicit(expr)
        assert s.extended, expr
        gpu = sg.evaluate(s, pts).astype(np.float64)
        twin = s.distance(pts)
        ok = np.isfinite(twin) & (np.abs(twin) < 1e30)
        assert np.isfinite(gpu[ok]).all(), expr
        rel = np.abs(gpu[ok] - twin[ok]) / np.maximum(np.abs(twin[ok]), 1e-3)
        assert np.percentile(rel, 99) < 1e-4, (expr, np.percentile(rel, 99))
    plain = sg.implicit("tanh(x) + y**2 + z**2 - 1/E")  # tanh and E print in plain GLSL too
    assert not plain.extended
    near = pts[:400]
    assert np.allclose(sg.evaluate(plain, near), plain.distance(near), rtol=1e-4, atol=1e-5)
