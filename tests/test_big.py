"""Big scenes: deep chains, shared subtrees, instances of any type, polygons and the code budget.

Sizes are kept small enough for CI; the full-size figures are in `sdfgl bench` (bench_big).
"""
import pickle
import sys

import numpy as np
import pytest

import sdfgl as sg
from .conftest import all_primitives
from sdfgl import bench_big
from sdfgl.compiler.data.grid import GRID_MIN

DEEP = 3 * sys.getrecursionlimit()  # deeper than any recursive walk could go


def _parity(scene, renderer, pts):
    err = np.abs(sg.evaluate(scene, pts, renderer=renderer) - scene.distance(pts))
    return float(err.max())


def test_chains_of_one_operator_stay_flat():
    s = sg.sphere(0.1)
    for i in range(DEEP):
        s = s | sg.sphere(0.01).translate((i * 1e-3, 0, 0))
    assert isinstance(s, sg.nodes.booleans.Union) and len(s.children) == DEEP + 1
    r = sg.sphere(0.1)  # right-deep: x | s (hard union and intersection only: min and max are associative)
    for i in range(DEEP):
        r = sg.sphere(0.01).translate((i * 1e-3, 0, 0)) | r
    assert isinstance(r, sg.nodes.booleans.Union) and len(r.children) == DEEP + 1
    assert repr(r.children[-1]) == "sphere(radius=0.1, center=(0, 0, 0))"
    pts = np.random.default_rng(0).uniform(-1, 1, (200, 3))
    np.testing.assert_array_equal(r.distance(pts), s.distance(pts))
    c = sg.sphere(1).color(0.9, 0.1, 0.1)  # colours: the innermost wins, so an outer one over it is dropped
    for i in range(DEEP):
        c = c.color(0.1, (i % 10) / 10, 0.1)
    assert repr(c) == "color(rgb=(0.9, 0.1, 0.1))[sphere(radius=1, center=(0, 0, 0))]"
    assert sg.sphere(1).color("red").material(specular=0.5).kind == "material"  # sets a field the inner does not
    i = sg.box(1) & (sg.sphere(1.2) & sg.cylinder(0.5, 2))
    assert len(i.children) == 3
    smooth = sg.box(1) | sg.union(sg.sphere(1), sg.box(0.5), k=0.1)  # not associative: stays nested
    assert len(smooth.children) == 2 and (sg.box(1) - (sg.sphere(1) - sg.box(0.5))).children[1].kind == "difference"
    t = sg.box(1)
    for _ in range(DEEP):
        t = t.translate((1e-3, 0, 0)).rotate(0.1, (0, 1, 0)).scale(1.0001)
    assert repr(t).count("[") == 3  # translate(rotate(scale(box)))
    np.testing.assert_allclose(t.distance([[0.3, 0.2, 0.1]]), _unfolded(DEEP).distance([[0.3, 0.2, 0.1]]),
                               rtol=1e-9)


def _unfolded(n):
    """The same moves as test_chains_of_one_operator_stay_flat, applied to the point."""
    from sdfgl.nodes.transforms import Rotate, Scale, Translate
    s = sg.box(1)
    for _ in range(n):
        s = Scale(Rotate.axis_angle(Translate(s, (1e-3, 0, 0)), 0.1, (0, 1, 0)), 1.0001)
    return s


@pytest.mark.slow
def test_a_deep_graph_that_cannot_be_flattened_works_everywhere(renderer):
    s = sg.sphere(0.5)
    for _ in range(DEEP):
        s = sg.difference(s.translate((0, 1e-5, 0)) | sg.sphere(0.02).translate((0.6, 0, 0)), sg.box(0.01))
    assert s.bounds[0][1] < 0 and s.exactness == sg.BOUND
    assert len(repr(s)) > DEEP
    assert pickle.loads(pickle.dumps(s)).key == s.key
    d = s.distance([[0.0, 0.2, 0.0], [3.0, 0.0, 0.0]])
    assert d[0] < 0 < d[1]
    src = sg.compile(s, code_budget=10 ** 8)  # straight-line code, generated without recursion limits
    assert src.count("opSmin") == 0 and src.count("max(") > DEEP


def test_code_past_the_hard_limit_is_refused_with_a_message(monkeypatch):
    import sdfgl.compiler.generate as generate_module
    monkeypatch.setattr(generate_module, "MAX_CODE_SIZE", 100)
    with pytest.raises(sg.ParameterError, match="over the limit of 100"):
        sg.compile(sg.sphere(1) | sg.box(1))


def test_a_dag_of_2_to_the_30_paths_costs_its_distinct_nodes(renderer):
    s, cam = bench_big.dag(30)
    assert s.is_dag and len(repr(s)) < 2000 and "@" in repr(s)
    pts = np.random.default_rng(0).uniform(-1.5, 1.5, (500, 3))
    assert _parity(s, renderer, pts) < 1e-5
    res = renderer.render(s, cam, (48, 36), shadows=False, ao=False, outputs=("color", "depth"))
    assert np.isfinite(res.depth).any()
    copy = pickle.loads(pickle.dumps(s))
    assert copy.is_dag and copy.key == s.key  # sharing survives pickling


def test_instances_of_every_primitive_type_are_data_with_parity(renderer):
    rng = np.random.default_rng(2)
    prims = [p for name, p in all_primitives().items() if name != "plane"]
    parts = []
    for i in range(4 * len(prims)):
        axis = rng.normal(size=3)
        parts.append(prims[i % len(prims)].scale(float(rng.uniform(0.2, 0.4))).rotate(float(rng.uniform(0, 360)), axis)
                     .translate(tuple(rng.uniform(-3, 3, 3))))
    s = sg.union(*parts)
    assert s.grid is not None and len(s.grid.children) == len(parts)
    assert {t.key[0] for t in s.grid.types} == {"prim"} and len(s.grid.types) == len(prims)
    pts = np.random.default_rng(3).uniform(-4, 4, (4000, 3))
    assert _parity(s, renderer, pts) < 1e-5
    src = sg.compile(s)
    assert "sdSphere(q" in src and "mat3(" not in src.split("float map(")[0].split("g0Dist")[1]


def test_moved_copies_of_a_subtree_are_one_function_and_data(renderer):
    s, cam = bench_big.instances(GRID_MIN + 8)
    grid = s.grid
    assert grid is not None and len(grid.types) == 1 and grid.types[0].slots is None
    src = sg.compile(s)
    assert src.count("sdRoundBox(") == 2  # the library function and the one subtree function
    pts = np.random.default_rng(4).uniform(-4, 4, (3000, 3))
    assert _parity(s, renderer, pts) < 1e-5
    rot = sg.union(*[bench_big.twenty_nodes().rotate(17 * i, (0, 1, 1)).translate((i % 6, i // 6, 0))
                     for i in range(GRID_MIN)])
    assert rot.grid.types[0].affine and _parity(rot, renderer, pts) < 1e-5


def test_grid_union_images_match_code(renderer):
    s, cam = bench_big.mixed(60, seed=1)
    a = renderer.render(s, cam, (64, 48), outputs=("color", "depth"), shadows="soft", ao=True)
    b = renderer.render(s, cam, (64, 48), outputs=("color", "depth"), shadows="soft", ao=True, grid=False)
    hit = np.isfinite(a.depth)
    assert hit.sum() > 100 and (hit != np.isfinite(b.depth)).sum() <= 0.03 * hit.sum()
    assert np.mean(np.abs(a.color.astype(int) - b.color.astype(int)) > 12) < 0.03


def test_big_polygons_are_data(renderer):
    small, _ = bench_big.polygon(20)
    big, cam = bench_big.polygon(500)
    assert "vec2[500]" not in sg.compile(big) and "sdPolygonGrid" in sg.compile(big)
    assert "vec2[20]" in sg.compile(small) and big.exactness == sg.BOUND and small.exactness == sg.EXACT
    pts = np.random.default_rng(5).uniform(-1.5, 1.5, (3000, 3))
    assert _parity(big, renderer, pts) < 1e-5
    res = renderer.render(big, cam, (32, 24), shadows=False, ao=False, outputs=("color", "depth"))
    assert np.isfinite(res.depth).any()


def test_over_the_code_budget_unions_become_data(renderer):
    rng = np.random.default_rng(6)
    groups = [sg.union(*[sg.sphere(0.1).translate(rng.uniform(-1, 1, 3)) for _ in range(20)]).rotate(20 * i, (0, 1, 0))
              for i in range(6)]
    s = sg.union(*groups)
    code = renderer.render(s, size=(32, 24), shadows=False, ao=False, code_budget=10 ** 7)
    assert code.source.choice == "code" and code.settings.grid_min == GRID_MIN
    data = renderer.render(s, size=(32, 24), shadows=False, ao=False, code_budget=1000)
    assert data.source.choice.startswith("data") and data.settings.grid_min == 8
    assert data.source.code_size < code.source.code_size
    pts = rng.uniform(-2, 2, (2000, 3))
    assert _parity(s, renderer, pts) < 1e-5
    with pytest.raises(sg.ParameterError, match="code_budget"):
        sg.compile(s, code_budget=10)



def test_a_compile_leaves_no_state_on_nodes_shared_into_other_scenes(renderer):
    rng = np.random.default_rng(7)
    groups = [sg.union(*[sg.sphere(0.1).translate(rng.uniform(-1, 1, 3)) for _ in range(20)]).rotate(20 * i, (0, 1, 0))
              for i in range(6)]
    s = sg.union(*groups)
    pts = rng.uniform(-2, 2, (1000, 3))
    exact = s.distance(pts)
    assert renderer.render(s, size=(16, 12), shadows=False, ao=False, code_budget=1000).source.data_unions == 6
    np.testing.assert_array_equal(s.distance(pts), exact)  # the twin is the scene's own, not its last compile's
    other = groups[0] | sg.box(0.2)  # a group of s, shared into another scene: compiled on its own terms
    src = renderer.render(other, size=(16, 12), shadows=False, ao=False).source
    assert src.choice == "code" and src.data_unions == 0
    np.testing.assert_array_equal(groups[0].distance(pts), groups[0].child.distance(pts @ groups[0].m))
    assert other.exactness == sg.EXACT
    again = renderer.render(s, size=(16, 12), shadows=False, ao=False, code_budget=10 ** 7).source
    assert again.choice == "code" and again.data_unions == 0  # a later compile of s is not changed either
    np.testing.assert_array_equal(s.distance(pts), exact)
    assert _parity(s, renderer, pts) < 1e-5
    # an explicit grid_min is the fewest instances kept as data, above the default too
    assert renderer.render(s, size=(16, 12), shadows=False, ao=False, grid_min=20).source.data_unions == 6
    assert renderer.render(s, size=(16, 12), shadows=False, ao=False, grid_min=21).source.data_unions == 0


def test_a_scene_without_material_nodes_has_a_constant_map_color(renderer):
    plain, cam = bench_big.growth(GRID_MIN + 8)
    src = sg.compile(plain, shadows=False, ao=False)
    body = src[src.index("vec3 mapColor(vec3 p)"):]
    body = body[:body.index("}")]
    assert "g0Color" not in src and "map" not in body.split("{", 1)[1]  # no second copy of the scene
    colored = sg.union(*plain.children[:-1], plain.children[-1].color(0.9, 0.1, 0.1))
    assert "g0Color" in sg.compile(colored, shadows=False, ao=False)
    # the same colour through the colour pass: the same image
    from sdfgl.compiler.emitter import DEFAULT_COLOR
    a = renderer.render(plain, cam, (48, 36), shadows=False, ao=False).color
    b = renderer.render(plain.color(*DEFAULT_COLOR), cam, (48, 36), shadows=False, ao=False).color
    assert a.std() > 0 and np.abs(a.astype(int) - b.astype(int)).max() <= 1



def test_a_wide_union_fills_its_caches_without_garbage_collections():
    """Bounds, grid and code of a union of thousands of children run with the cyclic
    collector paused (what they make outlives them, so collections would only rescan the
    graph); the collector is as it was afterwards, nested or not."""
    import gc

    from sdfgl.nodes.traverse import collector_paused
    s = sg.union(*[sg.sphere(0.1).translate((i % 40 * 0.3, i // 40 * 0.3, 0.0)) for i in range(4000)])
    starts = []

    def count(event, info):
        if event == "start":
            starts.append(info["generation"])
    gc.callbacks.append(count)
    try:
        s.bounds
        assert "g0Dist(" in sg.compile(s)
    finally:
        gc.callbacks.remove(count)
    assert len(starts) <= 2 and gc.isenabled()  # the one each pause put off (18 without pauses)
    with collector_paused():
        with collector_paused():
            assert not gc.isenabled()
        assert not gc.isenabled()
    assert gc.isenabled()
    gc.disable()
    try:
        with collector_paused():
            pass
        assert not gc.isenabled()  # a collector the caller paused stays paused
    finally:
        gc.enable()


def test_a_chain_step_leaves_four_objects_for_the_collector_and_rebuilds():
    # what the cyclic collector counts decides how often it runs while a loop builds a scene:
    # a sphere, its move and their two parameter dicts (6 before the moves and spheres were
    # rebuilt from their fields and the union step copied four attributes)
    import gc
    s = sg.sphere(0.5)
    for i in range(100):
        s = s | sg.sphere(0.02).translate((i * 1.0, 0.0, 0.0))
    was = gc.isenabled()
    gc.collect()
    gc.disable()
    try:
        before = gc.get_count()[0]
        for i in range(1000):
            s = s | sg.sphere(0.02).translate((i * 1.0, 1.0, 0.0))
        per_step = (gc.get_count()[0] - before) / 1000
    finally:
        if was:
            gc.enable()
    assert per_step <= 4.1
    live = sg.param(0.03, name="r")
    moved = sg.sphere(live).translate((1, 2, 3)).translate((0.5, 0, 0)) | s.children[5]
    assert moved.children[0].child.kind == "sphere"  # two moves folded, one node made for the second
    np.testing.assert_array_equal(moved.children[0].offset, [1.5, 2, 3])
    for back in (pickle.loads(pickle.dumps(moved)), sg.from_dict(moved.to_dict())):
        assert back.key[:2] == moved.key[:2] and repr(back) == repr(moved)
        np.testing.assert_array_equal(back.distance([[1.5, 2, 3.1]]), moved.distance([[1.5, 2, 3.1]]))


def test_a_wide_union_boxes_its_children_in_batches_equal_to_one_by_one():
    from sdfgl.nodes.base import box_of, boxes_of
    r = sg.param(0.1, name="r_live")
    move = sg.param((0.0, 0.0, 0.0), name="move_live")
    kids = [sg.sphere(0.02 + i * 1e-4, center=(0, i * 0.01, 0)).translate((i * 0.1, 0, 1)) for i in range(300)]
    kids += [sg.sphere(0.05).translate((0, -i * 0.1, 0)).translate((0, 0, -2)) for i in range(100)]  # folded
    kids += [sg.sphere(r).translate((40, 0, 0)), sg.box(0.3).translate((-3, 0, 0)), sg.sphere(0.2).translate(move)]
    expected = np.array([box_of(c) for c in kids])
    for c in kids:  # nothing cached: the batches compute every box
        for n in (c, c.child):
            n.__dict__.pop("_bounds_cache", None)
    np.testing.assert_array_equal(boxes_of(kids), expected)
    u = sg.union(*kids)
    np.testing.assert_array_equal(np.array(u.bounds), [expected[:, 0].min(axis=0), expected[:, 1].max(axis=0)])
    r.value, move.value = 0.5, (0.0, -30.0, 0.0)  # live values: the batches never keep a stale box
    lo, hi = u.bounds
    assert hi[0] == 40.5 and lo[1] == -30.2


def test_a_union_grown_by_a_loop_holds_what_the_constructor_sets():
    # _chained copies the attributes __init__ sets (booleans._STATE), not the whole __dict__:
    # an attribute added to __init__ and not to _STATE would be lost on every s = s | x step
    from sdfgl.nodes.base import CACHES
    parts = [sg.sphere(0.1).translate((i, 0, 0)) for i in range(4)]
    for k, blend in ((0.0, "quadratic"), (0.2, "circular")):
        grown = sg.union(parts[0], parts[1], k=k, blend=blend)
        for p in parts[2:]:
            grown = sg.union(grown, p, k=k, blend=blend)
        built = sg.nodes.booleans.Union(*parts, k=k, blend=blend)
        state = lambda n: {a: v for a, v in vars(n).items() if not a.startswith(CACHES + ("_ctor",))}  # noqa: E731
        assert state(grown) == state(built)
        assert grown.children == built.children and grown.key == built.key
