"""Orthographic projection (shader and float64 twin) and framing for the image's aspect."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.reference import compare, trace


def test_orthographic_cube_along_an_axis_is_a_square_of_the_right_size():
    # view 4 units tall on 64 rows: 16 px per unit, so a unit cube is 16 x 16 px
    cam = sg.Camera((0, 0, 10), (0, 0, 0), projection="orthographic", ortho_height=4.0)
    res = sg.render(sg.box(1.0), cam, (96, 64), outputs=("color", "depth"), shadows=False, ao=False)
    hit = np.isfinite(res.depth)
    rows, cols = np.flatnonzero(hit.any(axis=1)), np.flatnonzero(hit.any(axis=0))
    assert len(rows) == 16 and len(cols) == 16 and hit.sum() == 256
    assert (rows[0], cols[0]) == (24, 40)
    # parallel rays: every hit is at the same depth, the face's distance from the eye plane
    assert np.allclose(res.depth[hit], 9.5, atol=1e-4)
    # a perspective view of the same cube shows it bigger than its far face: not a square of 16
    persp = sg.render(sg.box(1.0).rotate(30, sg.Y), sg.Camera((0, 0, 3), (0, 0, 0), fov=60), (96, 64),
                      outputs=("color", "depth"), shadows=False, ao=False)
    assert np.isfinite(persp.depth).sum() != 256


def test_orthographic_twin_rays_match_the_shader():
    cam = sg.OrbitCamera((0.2, 0.1, 0), 6, 35, 25, projection="orthographic", ortho_height=3.0)
    scene = sg.sphere(0.8) | sg.box(0.9).translate((0.8, 0, 0))
    o, d = cam.rays(40, 30)
    assert np.allclose(d, d[0, 0]) and not np.allclose(o, o[0, 0])
    res = sg.render(scene, cam, (40, 30), outputs=("color", "depth", "normal"), shadows=False, ao=False)
    ref = trace(scene, cam, (40, 30))
    both = np.isfinite(res.depth) & np.isfinite(ref.t)
    assert both.sum() > 200
    err = np.abs(res.depth[both] - ref.t[both])
    px = 3.0 / 30   # the pixel size: every footprint of an orthographic camera
    assert np.median(err) < 1e-4 * px and err.max() < 2 * px   # grazing edges: the 0.25 px hit test
    lost = np.isfinite(ref.t) & ~np.isfinite(res.depth)
    false = ~np.isfinite(ref.t) & np.isfinite(res.depth)   # near misses within the hit test, at edges
    assert lost.sum() == 0
    near = o[false] + d[false] * res.depth[false][:, None].astype(float)
    assert np.all(scene.distance(near) < 0.5 * px)   # a false hit: a ray passing within the hit test
    m = compare(res, ref)
    assert m.depth_px_median < 1e-3   # footprints of an orthographic camera: its pixel size
    # project() inverts rays(): the pixel centres of rays() map back to their image coordinates
    xy = cam.project(o + 2.0 * d, 40, 30)
    assert np.allclose(xy[0, 0], (-1 + 1 / 40, 1 - 1 / 30)) and np.allclose(xy[-1, -1], (1 - 1 / 40, -1 + 1 / 30))


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
@pytest.mark.parametrize("aspect", [0.25, 0.5, 1.0, 2.0, 4.0])
def test_framing_keeps_every_corner_in_view(aspect, projection):
    lo, hi = np.array([-3.0, -0.2, -0.4]), np.array([3.0, 0.4, 0.5])  # a long box
    for yaw, pitch in [(30, 20), (0, 0), (90, -40), (200, 60)]:
        cam = sg.OrbitCamera.framing(lo, hi, yaw, pitch, aspect=aspect, projection=projection)
        corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
        w, h = (int(64 * aspect), 64) if aspect >= 1 else (64, int(64 / aspect))
        xy = cam.project(corners, w, h)
        assert np.all(np.isfinite(xy)) and np.all(np.abs(xy) <= 1.0)
        assert np.max(np.abs(xy)) > 0.85   # and it fills the view (5% margin), not a speck


@pytest.mark.parametrize("size", [(24, 96), (96, 24), (64, 64)])
def test_default_camera_shows_the_whole_scene_at_any_aspect(size):
    """A long box at 1:4, 4:1 and 1:1: hits, and no hit on the image border."""
    scene = sg.box((6.0, 0.6, 0.9)).rotate(20, sg.Y)
    for projection in ("perspective", "orthographic"):
        cam = sg.OrbitCamera.framing(*scene.bounds, aspect=size[0] / size[1], projection=projection)
        res = sg.render(scene, cam if projection == "orthographic" else None, size, outputs=("color", "depth"),
                        shadows=False, ao=False)
        hit = np.isfinite(res.depth)
        border = np.concatenate([hit[0], hit[-1], hit[:, 0], hit[:, -1]])
        assert hit.sum() > 0.02 * hit.size and not border.any()


def test_camera_validation():
    with pytest.raises(sg.ParameterError, match="projection"):
        sg.Camera((0, 0, 5), projection="fisheye")
    with pytest.raises(sg.ParameterError, match="ortho_height"):
        sg.Camera((0, 0, 5), ortho_height=2.0)
    with pytest.raises(sg.ParameterError, match="ortho_height"):
        sg.Camera((0, 0, 5), projection="orthographic", ortho_height=-1)
    with pytest.raises(sg.ParameterError, match="aspect"):
        sg.OrbitCamera.framing(np.zeros(3), np.ones(3), aspect=0)
    cam = sg.OrbitCamera(distance=4, projection="orthographic")
    h = cam.ortho_height
    cam.zoom(0.5)
    assert np.isclose(cam.ortho_height, h / 2)   # zooming an orthographic view narrows it
