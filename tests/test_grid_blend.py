"""Smooth unions kept as data: exact per-cell lists of the ordered fold (the field is
min(the code version's, cap)), parity with the twin and with the code version, the grid
chosen over nested blends."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.compiler.data.blend_lists import Blend, cap
from sdfgl.compiler.generate import generate
from sdfgl.evaluate import evaluate_channel
from sdfgl.nodes.grid_scope import grid_min_as
from sdfgl.nodes.booleans import BLEND_SUPPORT
from sdfgl.settings import Settings

KINDS = ("quadratic", "circular", "chamfer")


def blob(n, k=0.1, blend="quadratic", seed=0, colored=False):
    rng = np.random.default_rng(seed)
    pts = rng.uniform((-2, -0.4, -2), (2, 0.4, 2), (n, 3))
    parts = []
    for p in pts:
        s = sg.sphere(float(rng.uniform(0.08, 0.2)))
        if colored:
            s = s.color(*rng.uniform(0, 1, 3))
        parts.append(s.translate(p))
    return sg.union(*parts, k=k, blend=blend)


def inside_grid(g, n, seed=1):
    return np.random.default_rng(seed).uniform(g.lo, g.lo + g.dims * g.cell, (n, 3))


def capped(s, p):
    """The grid's field by the twin: min(the full fold, cap) inside the grid box."""
    return np.minimum(s.distance(p), cap(s.grid))


def test_a_smooth_union_of_many_spheres_is_one_grid_loop_not_nested_blends():
    s = blob(1000)
    assert s.grid is not None and s.grid.blend == Blend.of(0.1, "quadratic")
    src = sg.compile(s)
    assert "g0Dist(" in src and "g0Cell(vec3 p, out float away" in src  # shaders/templates/grid_blend.glsl
    assert src.count("opSmin(") < 6  # the library function and one fold a loop, not 1000 nested calls
    scene_code = lambda **kw: generate(s, Settings(**kw), np.zeros(3)).code_size  # noqa: E731 - map() and the like
    assert scene_code() < 0.05 * scene_code(grid=False)
    assert "g0Cell(vec3 p, out float away" in sg.compile(s, grid="bvh")  # a hierarchy would reorder the fold


@pytest.mark.parametrize("kind", KINDS)
def test_the_cells_fold_equals_the_full_fold_of_the_twin_bit_for_bit(kind):
    s = blob(300, k=0.15, blend=kind, seed=2)
    g = s.grid
    p = inside_grid(g, 100_000)
    assert np.array_equal(g.field(p), capped(s, p))  # skipped and dropped steps change nothing
    assert (s.distance(p) < cap(g)).mean() > 0.5  # most of the box is below the cap
    cells, _ = g.entries()
    assert len(cells) < 0.25 * len(s.children) * np.prod(g.dims)  # and the lists are short


def test_the_fold_order_is_kept_where_it_matters_most():
    # spheres met far to near along a line of points: every step blends with the one before
    # (smin is not associative: any other order gives other values)
    rng = np.random.default_rng(4)
    at = rng.uniform((-2, -0.3, -2), (2, 0.3, 2), (400, 3))
    at = at[np.argsort(-np.linalg.norm(at, axis=1))]
    s = sg.union(*[sg.sphere(0.12).translate(tuple(p)) for p in at], k=0.2)
    g = s.grid
    p = inside_grid(g, 50_000, seed=5)
    assert np.array_equal(g.field(p), capped(s, p))
    shuffled = sg.union(*[sg.sphere(0.12).translate(tuple(p)) for p in at[rng.permutation(len(at))]], k=0.2)
    assert np.abs(shuffled.distance(p) - s.distance(p)).max() > 1e-4  # the order is worth keeping


def _probe_union(probe_x, first):
    """32 far-apart spheres on a line and a probe sphere beside sphere 0, first or last."""
    row = [sg.sphere(0.5).translate((3.0 * i, 0, 0)) for i in range(32)]
    probe = sg.sphere(0.2).translate((probe_x, 0, 0))
    return sg.union(*([probe] + row if first else row + [probe]), k=0.1)


@pytest.mark.parametrize("first", [False, True])
def test_a_child_just_beyond_the_blend_reach_is_left_out_and_one_just_inside_kept(first):
    base = _probe_union(1.5, first)
    g = base.grid
    cell = np.floor((np.array([0.5, 0.0, 0.0]) - g.lo) / g.cell).astype(int)  # the cell at sphere 0's +x pole
    lo_c = g.lo + cell * g.cell
    index = (cell[2] * g.dims[1] + cell[1]) * g.dims[0] + cell[0]
    far_corner = np.where(np.abs(lo_c) > np.abs(lo_c + g.cell), lo_c, lo_c + g.cell)
    hi0 = float(np.linalg.norm(far_corner)) - 0.5  # sphere 0's largest value over the cell
    support = BLEND_SUPPORT["quadratic"] * 0.1
    probe_index = 0 if first else 32
    kept = {}
    for label, delta in (("beyond", 5e-3), ("inside", -5e-3)):
        # first, the probe is dropped once sphere 0 lies R below it all over the cell; last,
        # it is skipped where it lies R above sphere 0 all over the cell: the same threshold
        x = lo_c[0] + g.cell + 0.2 + hi0 + support + delta  # the probe's least value over the cell is hi0 + R + delta
        u = _probe_union(x, first)
        assert np.array_equal(u.grid.lo, g.lo) and u.grid.cell == g.cell
        cells, child = u.grid.entries()
        kept[label] = probe_index in set(child[cells == index].tolist())
        p = lo_c + np.random.default_rng(6).uniform(0, g.cell, (5000, 3))
        assert np.array_equal(u.grid.field(p), capped(u, p))
    assert kept == {"beyond": False, "inside": True}


@pytest.mark.parametrize("kind", KINDS)
def test_the_grid_on_the_gpu_matches_the_twin_and_the_code_version(renderer, kind):
    s = blob(48, k=0.12, blend=kind, seed=7, colored=True)
    g = s.grid
    p = inside_grid(g, 100_000, seed=8)
    grid = sg.evaluate(s, p, renderer=renderer)
    with grid_min_as(10 ** 9):  # the same union as code: 48 nested blends
        code = sg.evaluate(s, p, renderer=renderer)
    twin = s.distance(p)
    near = twin < cap(g)  # where the code version is below the cap the grid is the code version
    assert near.mean() > 0.5
    assert np.abs(grid - np.minimum(twin, cap(g))).max() < 2e-6
    assert np.abs(grid[near] - code[near]).max() < 2e-6
    assert np.abs(grid[~near] - code[~near]).max() > 1e-3  # the code version did run: it has no cap
    assert np.all(grid[~near] >= cap(g) - 2e-6)
    q = p[near][:20000]
    colour = evaluate_channel(s, q, renderer=renderer)
    with grid_min_as(10 ** 9):
        colour_code = evaluate_channel(s, q, renderer=renderer)
    assert np.abs(colour - colour_code).max() < 1e-4


def test_outside_the_grid_box_the_field_stays_below_the_fold_and_positive(renderer):
    s = blob(100, seed=9)
    g = s.grid
    p = np.random.default_rng(10).uniform(g.lo - 3, g.lo + g.dims * g.cell + 3, (50_000, 3))
    out = np.any((p < g.lo) | (p > g.lo + g.dims * g.cell), axis=1)
    twin = s.distance(p[out])
    mine = g.field(p[out])
    assert np.all(mine <= twin + 1e-12) and np.all(mine > 0)
    assert np.abs(sg.evaluate(s, p[out], renderer=renderer) - mine).max() < 2e-6


def test_bounds_lipschitz_and_exactness_are_the_code_versions():
    s = blob(200)
    with grid_min_as(10 ** 9):
        code = (s.exactness, s.lipschitz)
        assert s.grid is None
    assert s.grid is not None
    assert (s.exactness, s.lipschitz) == code == (sg.BOUND, 1.0)
    assert np.allclose(s.bounds, blob(200).bounds)


def test_mixed_trees_keep_their_structure(renderer):
    # a smooth union of moved copies of a hard union; a hard union of smooth blobs
    pair = sg.union(sg.sphere(0.15), sg.sphere(0.1).translate((0.2, 0, 0)))
    rng = np.random.default_rng(11)
    smooth_of_hard = sg.union(*[pair.translate(tuple(rng.uniform(-2, 2, 3))) for _ in range(64)], k=0.1)
    g = smooth_of_hard.grid
    assert g is not None and len(g.types) == 1 and g.types[0].slots is None
    p = inside_grid(g, 30_000, seed=12)
    assert np.array_equal(g.field(p), capped(smooth_of_hard, p))
    assert np.abs(sg.evaluate(smooth_of_hard, p, renderer=renderer) - capped(smooth_of_hard, p)).max() < 2e-6
    blobs = [blob(40, seed=i).translate((6.0 * i, 0, 0)) for i in range(3)]
    hard_of_smooth = sg.union(*blobs, sg.sphere(0.5).translate((0, 3, 0)))
    src = sg.compile(hard_of_smooth)
    assert src.count("Cell(vec3 p, out float away") == 3  # each blob its own grid inside the hard union


def test_smooth_unions_that_cannot_be_data_stay_code():
    spheres = [sg.sphere(0.3).translate((i, 0, 0)) for i in range(40)]
    assert sg.union(*spheres, sg.box(0.3), k=0.1).grid is None  # two types: two loops would reorder the fold
    assert sg.union(*spheres, sg.plane(), k=0.1).grid is None   # a child as code beside would too
    bound = [sg.sphere(0.3).translate((i, 0, 0)) | sg.sphere(0.2).translate((i, 0.3, 0)) for i in range(40)]
    assert sg.union(*[b.union(sg.box(0.1), k=0.05) for b in bound], k=0.1).grid is None  # not exact
    assert sg.union(*spheres, k=3.0).grid is None  # a blend over most of them: every cell would list all
    assert sg.union(*spheres, k=0.5).grid is not None


def test_cells_whose_fold_lies_above_the_cap_list_nothing():
    # two blobs far apart: the cells between them hold only the cap
    a = [sg.sphere(0.2).translate((float(x), 0, 0)) for x in np.linspace(0, 1, 20)]
    b = [sg.sphere(0.2).translate((float(x), 0, 0)) for x in np.linspace(6, 7, 20)]
    s = sg.union(*a, *b, k=0.1)
    g = s.grid
    cells, _ = g.entries()
    listed = np.zeros(int(np.prod(g.dims)), dtype=bool)
    listed[cells] = True
    p = np.stack([np.linspace(2.5, 4.5, 200), np.zeros(200), np.zeros(200)], axis=1)
    ijk = np.floor((p - g.lo) / g.cell).astype(int)
    assert not listed[(ijk[:, 2] * g.dims[1] + ijk[:, 1]) * g.dims[0] + ijk[:, 0]].any()
    assert np.all(g.field(p) == cap(g)) and np.all(s.distance(p) > cap(g))


def test_points_on_cell_faces_are_inside_the_grid_box(renderer):
    # float32 rounding may put a point beside the cell floor() gives it: it is still inside
    s = blob(300, seed=13)
    g = s.grid
    rng = np.random.default_rng(14)
    ijk = rng.integers(1, g.dims, (50_000, 3))
    p = g.lo + ijk * g.cell + rng.uniform(0, g.cell, (50_000, 3)) * (rng.random((50_000, 3)) < 0.5)
    assert np.abs(sg.evaluate(s, p, renderer=renderer) - capped(s, p)).max() < 2e-6


def test_the_benchmark_scenes_keep_their_blends_as_data():
    from sdfgl import bench_big
    molecule, _ = bench_big.molecule(300)
    assert molecule.grid is not None and molecule.grid.blend is not None
    forest, _ = bench_big.trees(62)  # 62 trees of 3 boxes: a hard grid of four kinds of smooth subtree
    assert forest.grid is not None and forest.grid.blend is None and len(forest.grid.types) == 4
    slab, _ = bench_big.blend_slab(100)
    assert slab.grid.blend == Blend.of(0.1, "quadratic") and bench_big.blend_slab(100, 0.0)[0].grid.blend is None


def test_neighbour_counts_of_many_boxes_are_exact_or_a_superset(monkeypatch):
    from sdfgl.nodes import blend_reach
    rng = np.random.default_rng(4)
    n = blend_reach.PAIRWISE_MAX + 500
    centre = np.concatenate([rng.uniform(0, 4, (n - 200, 3)), rng.uniform(0, 0.3, (200, 3))])  # a dense cluster too
    half = rng.uniform(0.01, 0.1, n)[:, None] * np.array([1.0, 0.5, 2.0])
    lo, hi = centre - half, centre + half
    reach = rng.uniform(0, 0.4, n)
    radius = reach + np.linalg.norm(hi - lo, axis=1) / 2 + (np.linalg.norm(hi - lo, axis=1) / 2).max()
    apart = np.linalg.norm(centre[:, None] - centre[None], axis=-1)
    exact = (apart <= radius[:, None]).sum(axis=1)
    rows = rng.choice(n, 300, replace=False)  # some boxes' counts: theirs of the full count

    def agree(counts_of):
        assert np.array_equal(counts_of(lo, hi, reach), exact)
        assert np.array_equal(counts_of(lo, hi, reach[rows], rows), exact[rows])
    agree(blend_reach._neighbour_counts)
    monkeypatch.setattr(blend_reach, "PAIRS_PER_PASS", 1000)  # many passes: the same counts
    agree(blend_reach._neighbour_counts)
    monkeypatch.setattr(blend_reach, "PAIRS_MOST", 1000)  # too many pairs: the 27 cells' boxes
    assert np.all(blend_reach._neighbour_counts(lo, hi, reach) >= exact)
    assert np.all(blend_reach._neighbour_counts(lo, hi, reach[rows], rows) >= exact[rows])
    monkeypatch.setattr(blend_reach, "PAIRS_MOST", 1 << 23)
    few = rng.choice(n, blend_reach.PAIRWISE_MAX, replace=False)  # the pairwise count, all and some
    gap = np.maximum(0.0, np.maximum(lo[few][None] - hi[few][:, None], lo[few][:, None] - hi[few][None]))
    sub = (np.sqrt((gap * gap).sum(-1)) < reach[few][:, None]).sum(axis=1)
    assert np.array_equal(blend_reach._neighbour_counts(lo[few], hi[few], reach[few][:50], np.arange(50)), sub[:50])
    pytest.importorskip("scipy")
    monkeypatch.setattr(blend_reach, "KDTREE_FROM", n)  # scipy's k-d tree: the same counts
    agree(blend_reach._neighbour_counts)


def test_a_big_smooth_union_needs_no_scipy(monkeypatch):
    import sys
    monkeypatch.setitem(sys.modules, "scipy", None)  # the core install has no scipy
    monkeypatch.setitem(sys.modules, "scipy.spatial", None)
    s = blob(2000, k=0.05)
    lo, hi = s.bounds
    assert np.all(lo >= -2.6) and np.all(hi <= 2.6) and np.all(hi - lo > 0.5)
