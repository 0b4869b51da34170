"""float32 precision where the work is: normals of walls thinner than the normal stencil,
endless repetition far from the world origin (with and without a rotation), and the shader
origin of a scene whose near part is far smaller than the whole."""
import sys

import numpy as np

import sdfgl as sg
from sdfgl.compiler.analysis import near_work
from sdfgl.compiler.tables import reduce_modulo
from sdfgl.reference import trace

render_module = sys.modules["sdfgl.render"]  # sdfgl.render is also the name of the function


def _angles(res, n):
    hit = np.isfinite(res.depth)
    cos = np.abs(res.normal[hit] @ n)
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


def test_a_plate_thinner_than_the_stencil_keeps_its_face_normal():
    # 1e-4 thick: the first stencil (1e-4 of the scene size) straddled it and the normals
    # snapped toward a cube diagonal (median 28 degrees); shrunk until the taps agree, < 0.1
    turn = sg.box((2.0, 1e-4, 1.6)).rotate(12, (1, 0, 0.3))
    res = sg.render(turn, sg.OrbitCamera(distance=3.5, yaw=25, pitch=40), (48, 36), outputs=("depth", "normal"),
                    shadows=False, ao=False)
    n = turn.m @ np.array([0.0, 1.0, 0.0])
    ang = _angles(res, n)
    assert ang.size > 300 and np.percentile(ang, 95) < 0.2, np.percentile(ang, [50, 95, 100])


def test_a_thin_implicit_shell_has_smooth_normals():
    # a shell 1e-3 thick as one polynomial: f bends within the stencil (p99 2.1 degrees before)
    a2, b2 = 0.9995 ** 2, 1.0005 ** 2
    shell = sg.implicit(f"(x*x + y*y + z*z - {a2!r}) * (x*x + y*y + z*z - {b2!r})", bounds=((-1.1,) * 3, (1.1,) * 3))
    cam = sg.OrbitCamera(distance=3.0, yaw=20, pitch=30)
    res = sg.render(shell, cam, (48, 36), outputs=("depth", "normal"), shadows=False, ao=False)
    hit = np.isfinite(res.depth)
    o, d = cam.rays(48, 36)
    p = o[hit] + d[hit] * res.depth[hit][:, None]
    n = p / np.linalg.norm(p, axis=-1, keepdims=True)
    ang = np.degrees(np.arccos(np.clip(np.sum(res.normal[hit] * n, axis=-1), -1.0, 1.0)))
    assert hit.sum() > 300 and np.percentile(ang, 99) < 0.5, np.percentile(ang, [50, 99])


def test_reduce_modulo_keeps_the_point_within_half_a_period_on_repeated_axes():
    v = reduce_modulo(np.array([1e6 + 0.3, -7.7e5 - 0.45, 1e6]), np.array([1.0, 0.5, 0.0]))
    assert np.allclose(v, [0.3, 0.05, 1e6], atol=1e-9)


def _uniforms(scene, cam):
    res = sg.render(scene, cam, (8, 6), outputs=("depth",), shadows=False, ao=False)
    origin = render_module.shader_origin(scene, cam.eye)
    return res, render_module.origin_uniforms(res.source, scene, origin)


def test_endless_repetition_folds_at_the_size_of_a_cell_far_out():
    # the origin offset was added before the fold: at 1e6 the fold ran at float32 steps of 0.06
    at = np.array([7.07e5, 0.0, -7.07e5])
    scene = sg.sphere(0.6).repeat((2.0, 0.0, 2.0))
    res, values = _uniforms(scene, sg.OrbitCamera(target=tuple(at), distance=8, yaw=20, pitch=30))
    offsets = np.array([v for k, v in values.items() if k.startswith("uOrg")])
    assert offsets.size and np.all(np.abs(offsets[:, [0, 2]]) <= 1.0 + 1e-9)


def test_a_turned_endless_lattice_far_out_folds_exactly():
    # the rotation took the point at world magnitude (1e6) before the fold: 38 % of hits wrong
    at = 1e6 * np.array([0.48, -0.6, 0.64])
    lattice = sg.sphere(0.22).repeat(1.0).rotate(40, (1.0, 0.3, -0.5))
    cam = sg.OrbitCamera(target=tuple(at + 0.37), distance=2.5, yaw=30, pitch=20)
    res, values = _uniforms(lattice, cam)
    offsets = np.array([v for k, v in values.items() if k.startswith("uOrg")])
    assert offsets.size and np.all(np.abs(offsets) <= 0.5 + 1e-9)
    near = sg.sphere(0.22).repeat(1.0).rotate(40, (1.0, 0.3, -0.5))  # the same view at the origin, shifted
    shift = lattice.m.T @ (at + 0.37)
    cam0 = sg.OrbitCamera(target=tuple(lattice.m @ (shift - np.round(shift))), distance=2.5, yaw=30, pitch=20)
    far = sg.render(lattice, cam, (32, 24), outputs=("depth",), shadows=False, ao=False)
    here = sg.render(near, cam0, (32, 24), outputs=("depth",), shadows=False, ao=False)
    assert np.array_equal(np.isfinite(far.depth), np.isfinite(here.depth))
    both = np.isfinite(far.depth)
    assert both.sum() > 100 and np.max(np.abs(far.depth[both] - here.depth[both])) < 1e-4


def _near_and_far(size, gap):
    near = (sg.box(size) - sg.sphere(0.62 * size)).translate((0, 0, -gap))
    return near | sg.box((4000, 4000, 1.0)).translate((0, 0, -1000))


def test_the_origin_of_a_scene_that_spans_scales_lies_at_the_eye():
    scene = _near_and_far(3e-3, 5e-3)
    near = near_work(scene, np.zeros(3))
    assert near is not None and 5e-3 < near < 8e-3  # the far corner of the part's box
    origin = render_module.shader_origin(scene, np.array([1e-4, 0.0, 0.0]))
    assert np.linalg.norm(origin - [1e-4, 0.0, 0.0]) <= near  # near the eye, on a grid of the near part's size
    # an ordinary view keeps the box centre: a sphere seen from afar, a room seen from inside
    assert near_work(sg.sphere(1.0), np.array([0.0, 0.0, 5.0])) is None
    room = sg.box(10.0) - sg.box(9.0)
    assert near_work(room, np.zeros(3)) is None
    assert np.allclose(render_module.shader_origin(room, np.zeros(3)), 0.0)


def test_a_tiny_near_part_before_a_far_wall_is_exact():
    # a 3 mm part 5 mm from the eye, a wall 1000 away: with the origin at the box centre one
    # float32 step was two footprints there and the normal's floor (1e-7 of the scene) larger
    # than the part's features
    scene = _near_and_far(3e-3, 5e-3)
    cam = sg.Camera.look_at((0, 0, 0), (0, 0, -5e-3), fov=56)
    res = sg.render(scene, cam, (48, 36), outputs=("depth", "normal"), shadows=False, ao=False)
    ref = trace(scene, cam, (48, 36), max_dist=4000)
    t = ref.t
    a, b = np.isfinite(res.depth) & (res.depth < 1), np.isfinite(t) & (t < 1)
    assert b.sum() > 500 and (a != b).sum() <= 4
    both = a & b & ~ref.undecided
    fp = t[both] * cam.pixel_angle(36)
    assert np.percentile(np.abs(res.depth[both] - t[both]) / fp, 99) < 0.25
