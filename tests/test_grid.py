"""Big unions kept as data: parity with the twin, the same image as code, flat compile size."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.compiler.data.grid import GRID_MIN


def scattered(n, seed=0):
    rng = np.random.default_rng(seed)
    ext = 2.0 * n ** (1 / 3)
    kinds = [lambda: sg.sphere(0.4), lambda: sg.box(0.6), lambda: sg.torus(0.35, 0.1),
             lambda: sg.cylinder(0.2, 0.7).rotate(30, (1, 0, 0)), lambda: sg.rounded_box(0.7, 0.1).scale(1.3)]
    parts = [kinds[i % 5]().color(*rng.uniform(0, 1, 3)).translate(rng.uniform(-ext, ext, 3)) for i in range(n)]
    return sg.union(*parts), sg.OrbitCamera(distance=3.2 * ext, yaw=30, pitch=25), ext


def test_a_big_union_keys_only_the_instances_that_share_a_box(renderer):
    """Its instances go into the grid once each without a structural key for every one (the
    cost that dominated a 10^5-node chain's compile): a node given twice is one object, and
    only nodes whose box another shares (equal copies built apart) have their keys compared."""
    rng = np.random.default_rng(3)
    parts = [sg.sphere(0.3).translate(tuple(rng.uniform(-3, 3, 3))) for _ in range(GRID_MIN + 20)]
    twice = parts[0]
    copy = sg.sphere(0.3).translate(tuple(twice.offset))  # equal to parts[0], built apart
    s = sg.union(*parts, twice, copy)
    assert "g0Dist(" in sg.compile(s)
    assert [c for c in s.children if "_key" in c.__dict__] == [twice, twice, copy]  # parts[0] is twice
    assert len(s.grid.children) == len(parts)  # the copy and the repeat are left out
    pts = rng.uniform(-4, 4, (5000, 3))
    assert np.abs(sg.evaluate(s, pts, renderer=renderer) - s.distance(pts)).max() < 1e-5


def test_big_union_is_data_and_matches_the_twin(renderer):
    s, _, ext = scattered(GRID_MIN + 40)
    assert s.grid is not None and s.exactness == sg.BOUND
    src = sg.compile(s)
    assert "g0Dist(" in src and src.count("sdSphere(") == 3  # the library function, one loop in map() and one in mapColor()
    pts = np.random.default_rng(1).uniform(-ext - 3, ext + 3, (20000, 3))
    err = np.abs(sg.evaluate(s, pts, renderer=renderer) - s.distance(pts))
    assert err.max() < 1e-5
    near = s.distance(pts) < s.grid.cap(pts) - 1e-9  # below the cap the field is the exact min
    assert near.mean() > 0.05
    plain = np.min([c.distance(pts[near]) for c in s.children], axis=0)
    assert np.allclose(s.distance(pts[near]), plain)


def test_grid_and_code_render_the_same_image(renderer):
    s, cam, _ = scattered(GRID_MIN + 10, seed=3)
    a = renderer.render(s, cam, (64, 48), outputs=("color", "depth"), shadows=False, ao=False)
    b = renderer.render(s, cam, (64, 48), outputs=("color", "depth"), shadows=False, ao=False, grid=False)
    hit = np.isfinite(a.depth)
    # the capped field takes other steps, so a near miss at a silhouette may go either way
    assert (hit != np.isfinite(b.depth)).sum() <= 0.02 * hit.sum()
    both = hit & np.isfinite(b.depth)
    footprint = a.depth[both] * cam.pixel_angle(48)
    assert np.median(np.abs(a.depth[both] - b.depth[both]) / footprint) < 0.01
    assert np.mean(np.abs(a.color.astype(int) - b.color.astype(int)) > 8) < 0.02


@pytest.mark.slow
def test_shader_size_does_not_grow_with_the_union():
    small, _, _ = scattered(GRID_MIN)
    large, _, _ = scattered(16 * GRID_MIN)
    a, b = sg.compile(small), sg.compile(large)
    assert abs(len(a) - len(b)) < 80  # only the grid's dimensions and counts in comments differ
    assert len(sg.compile(large, grid=False)) > 5 * len(b)


def test_unions_with_unpackable_or_too_few_children_stay_code():
    s, _, _ = scattered(GRID_MIN - 1)
    assert s.grid is None
    # a blend folds in order: two types (two loops) or a child as code beside would reorder it
    spheres = [sg.sphere(0.3).translate((i, 0, 0)) for i in range(GRID_MIN)]
    assert sg.union(*spheres, k=0.1).grid is not None
    assert sg.union(*spheres, sg.box(0.3), k=0.1).grid is None
    assert sg.union(*spheres, sg.plane(), k=0.1).grid is None
    assert sg.union(*spheres, k=sg.param(0.1, "k")).grid is None
    mixed = sg.union(*[sg.sphere(0.3).translate((i, 0, 0)) for i in range(GRID_MIN)], sg.plane())
    assert mixed.grid is not None and len(mixed.grid.children) == GRID_MIN
    assert "sdPlane" in sg.compile(mixed)  # an unbounded child stays code beside the grid


def test_cells_list_instances_by_their_balls_and_every_unlisted_one_lies_beyond_the_margin():
    rng = np.random.default_rng(5)
    members = [sg.sphere(0.15).translate(tuple(rng.uniform(-3, 3, 3))) for _ in range(300)]
    members += [sg.box((0.5, 0.1, 0.1)).rotate(float(rng.uniform(0, 90)), tuple(rng.normal(size=3)))
                .translate(tuple(rng.uniform(-3, 3, 3))) for _ in range(100)]
    g = sg.union(*members).grid
    cells, child = g._entries()
    listed = set(zip(cells.tolist(), child.tolist()))
    # the box test alone lists more: the balls cut the entries near the boxes' corners
    ball_at = g._ball_at
    g._ball_at = None
    assert len(cells) < 0.85 * len(g._entries()[0])
    g._ball_at = ball_at
    # the cap's promise at random points: an instance nearer than the margin is in the point's list
    p = rng.uniform(g.lo, g.lo + g.dims * g.cell, (20000, 3))
    ijk = np.clip(np.floor((p - g.lo) / g.cell), 0, g.dims - 1).astype(np.int64)
    index = (ijk[:, 2] * g.dims[1] + ijk[:, 1]) * g.dims[0] + ijk[:, 0]
    for i, m in enumerate(members):
        near = np.flatnonzero(m.distance(p) < g.margin)
        assert all((int(index[k]), i) in listed for k in near), f"member {i} is near an unlisted cell"


def test_compiling_never_writes_into_the_scene_nor_moves_its_twin():
    # 20 instances: code by default, data with grid_min=8 or over a small code budget, whose
    # cap lowers the field far from the spheres: the twin must not follow either compile
    rng = np.random.default_rng(7)
    s = sg.union(*[sg.sphere(0.2).translate(rng.uniform(-2, 2, 3)) for _ in range(20)])
    pts = rng.uniform(-5, 5, (2000, 3))
    runs = ({}, {"grid_min": 8}, {"grid_min": 20, "code_budget": 1000}, {"grid_min": 8, "grid": "bvh"})
    for kw in runs:  # every cache a compile fills is filled once
        sg.compile(s, **kw)
    twin = s.distance(pts)
    state = dict(vars(s))
    assert s.grid is None  # the scene's own answer: a union of 20 is code
    np.testing.assert_array_equal(twin, np.min([c.distance(pts) for c in s.children], axis=0))
    for kw in runs[::-1] + runs:
        src = sg.compile(s, **kw)
        assert ("g0Dist(" in src) == bool(kw), kw  # the compiles differ ...
        np.testing.assert_array_equal(s.distance(pts), twin)  # ... the twin does not
        assert vars(s).keys() == state.keys() and all(vars(s)[k] is v for k, v in state.items()), kw
