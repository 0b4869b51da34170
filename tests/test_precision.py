"""float32 precision where the work is: normals of walls thinner than the normal stencil,
endless repetition far from the world origin (with and without a rotation), and the shader
origin of a scene whose near part is far smaller than the whole."""
import sys

import numpy as np

import sdfgl as sg
from sdfgl.compiler.tables import reduce_modulo

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
