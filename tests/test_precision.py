"""float32 precision where the work is: normals of walls thinner than the normal stencil,
endless repetition far from the world origin (with and without a rotation), and the shader
origin of a scene whose near part is far smaller than the whole."""
import numpy as np

import sdfgl as sg

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
