"""Grid union records: the move of each instance stored in as few floats as it needs
(sdfgl/compiler/data/grid_record.py), checked against the float64 twin on the real GL path."""
import numpy as np

import sdfgl as sg
from sdfgl.compiler.data import grid_record
from sdfgl.compiler.data.grid import GRID_MIN
from sdfgl.nodes.transforms import Rotate


def _rotations(n, seed=0):
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    x, y, z, w = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1)], 1)


def _apply(q, v):
    u, w = q[:, :3], q[:, 3:]
    return v + 2 * np.cross(u, np.cross(u, v) + w * v)


def test_quaternions_reproduce_rotations_including_half_turns():
    m = np.concatenate([_rotations(500), np.array([np.diag([1.0, -1, -1]), np.diag([-1.0, 1, -1]),
                                                   np.diag([-1.0, -1, 1]), np.eye(3)])])
    v = np.random.default_rng(1).normal(size=(len(m), 3))
    np.testing.assert_allclose(_apply(grid_record.quaternions(m), v), np.einsum("nij,nj->ni", m, v), atol=1e-12)


def _kind(s, t):
    return grid_record.kind(t, np.array([s.grid.peeled[i][2] for i in t.members]))


def _parity(scene, renderer, pts):
    return float(np.abs(sg.evaluate(scene, pts, renderer=renderer) - scene.distance(pts)).max())


def _union(make, n=GRID_MIN):
    rng = np.random.default_rng(2)
    return sg.union(*[make(i).rotate(float(rng.uniform(0, 360)), tuple(rng.normal(size=3)))
                      .translate(tuple(rng.uniform(-2, 2, 3))) for i in range(n)])


def test_rotated_primitives_are_quaternions_and_match_the_twin(renderer):
    s = _union(lambda i: sg.capsule((0, -0.3, 0), (0.1, 0.3, 0), 0.1) if i % 2 else sg.torus(0.3, 0.08).scale(0.5 + i / 64))
    pts = np.random.default_rng(3).uniform(-3, 3, (4000, 3))
    assert {_kind(s, t) for t in s.grid.types} == {"quat"}
    assert _parity(s, renderer, pts) < 1e-5


def test_rotated_spheres_store_a_translation_only(renderer):
    s = _union(lambda i: sg.sphere(0.2 + i / 200))
    assert [_kind(s, t) for t in s.grid.types] == ["translate"]
    assert s.grid.records(s.grid.types[0], (1.0, 1.0, 1.0)).shape[1] == 1  # (centre, radius); the one colour is code
    assert "cross(" not in sg.compile(s).split("g0Dist(vec3 p)")[1].split("float map(")[0]
    assert _parity(s, renderer, np.random.default_rng(4).uniform(-3, 3, (3000, 3))) < 1e-5


def test_a_reflected_member_keeps_the_matrix(renderer):
    mirror = np.diag([1.0, 1.0, -1.0])
    parts = [Rotate(sg.cone(0.4, 0.2, 0.05), mirror if i == 3 else np.eye(3)).translate((i % 6, i // 6, 0))
             for i in range(GRID_MIN)]
    s = sg.union(*parts)
    assert [_kind(s, t) for t in s.grid.types] == ["matrix"]
    assert _parity(s, renderer, np.random.default_rng(5).uniform(-1, 7, (3000, 3))) < 1e-5


def _hit_colors(scene, renderer, cam, **kw):
    out = renderer.render(scene, cam, (96, 72), outputs=("color", "depth"), shadows=False, ao=False, aa=1, **kw)
    return out.color[..., :3].astype(int), out.depth < 1e9


def test_members_of_one_colour_keep_it_in_code_and_others_in_their_records(renderer):
    """A type whose members share a colour (or all have none) writes it once in code: one
    texel a sphere instead of two; members of different colours keep theirs in the records.
    Each renders in its members' colours, as the union written as code does."""
    cam = sg.OrbitCamera(distance=9, yaw=20, pitch=30)
    same = _union(lambda i: sg.sphere(0.3).color("red"))
    mixed = _union(lambda i: sg.sphere(0.3).color("red" if i % 2 else "blue"))
    plain = _union(lambda i: sg.sphere(0.3))
    assert [s.grid.types[0].color_in_record for s in (same, mixed, plain)] == [False, True, False]
    assert [s.grid.records(s.grid.types[0], (1.0, 1.0, 1.0)).shape[1] for s in (same, mixed, plain)] == [1, 2, 1]
    for scene in (same, mixed, plain):
        img, hit = _hit_colors(scene, renderer, cam)
        code, code_hit = _hit_colors(scene, renderer, cam, grid=False)
        assert hit.mean() > 0.05 and np.mean(hit != code_hit) < 0.005
        assert np.mean(np.abs(img - code).max(-1)[hit & code_hit] > 8) < 0.01
    img, hit = _hit_colors(mixed, renderer, cam)
    assert np.mean((img[..., 0] > img[..., 2] + 40) & hit) > 0.01
    assert np.mean((img[..., 2] > img[..., 0] + 40) & hit) > 0.01
