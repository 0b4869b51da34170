"""The free way along the ray (shaders/templates/grid_ray.glsl): where the scene is one union kept
as data, the marcher steps the way its lists prove empty. Checked against the float64
reference and against the same shader without it."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.reference import trace_rays


def _spheres(n: int, seed: int) -> sg.Node:
    """Spheres from a pixel wide to big ones, some rotated (a rotated sphere keeps its centre)."""
    rng = np.random.default_rng(seed)
    parts = [sg.sphere(float(rng.choice([0.01, 0.03, 0.1, 0.3]))).rotate(float(rng.uniform(0, 90)), (0, 1, 0))
             .translate(tuple(rng.uniform((-2, -0.5, -2), (2, 0.5, 2)))) for _ in range(n)]
    return sg.union(*parts)


def _mixed(n: int, seed: int) -> sg.Node:
    """Thin and round instances, rotated: spheres, capsules, tori, thin boxes."""
    rng = np.random.default_rng(seed)
    kinds = (lambda: sg.sphere(0.12), lambda: sg.capsule((-0.2, 0, 0), (0.2, 0, 0), 0.03),
             lambda: sg.torus(0.15, 0.02), lambda: sg.box((0.4, 0.02, 0.25)))
    parts = [kinds[i % 4]().rotate(float(rng.uniform(0, 180)), tuple(rng.normal(size=3)))
             .translate(tuple(rng.uniform((-2, -0.5, -2), (2, 0.5, 2)))) for i in range(n)]
    return sg.union(*parts)


def _moved(n: int, seed: int) -> sg.Node:
    """Translated copies of the benchmark's 20-node robot, turned copies of the robot with an
    antenna, boxes of many sizes, rotated capsules, spheres: every kind of free way (a
    subtree's box and parts, in the world's frame or turned, a primitive's distance, a
    sphere's entry)."""
    from sdfgl.bench_big import twenty_nodes
    rng = np.random.default_rng(seed)
    robot = twenty_nodes()
    antenna = robot | sg.sphere(0.05).translate((0, 0.62, 0))  # another type: turned copies
    kinds = (lambda: robot, lambda: sg.box(tuple(rng.uniform(0.02, 0.5, 3))),
             lambda: sg.capsule((-0.2, 0, 0), (0.2, 0.1, 0), float(rng.uniform(0.01, 0.06)))
             .rotate(float(rng.uniform(0, 180)), tuple(rng.normal(size=3))),
             lambda: sg.sphere(float(rng.choice([0.01, 0.1, 0.3]))),
             lambda: antenna.rotate(float(rng.uniform(0, 360)), tuple(rng.normal(size=3))))
    return sg.union(*[kinds[i % 5]().translate(tuple(rng.uniform((-2, -0.6, -2), (2, 0.6, 2)))) for i in range(n)])


def test_only_a_scene_whose_root_is_a_union_of_moved_instances_gets_the_free_way():
    scene = _spheres(64, 0)
    assert "#define RAY_FREE" in sg.compile(scene, shadows=False, ao=False)
    assert "#define RAY_FREE" in sg.compile(scene.translate((1, 2, 3)).color(1, 0, 0))
    # beside other geometry: its distance bounds the way
    floor = sg.compile(scene | sg.plane())
    assert "#define RAY_FREE" in floor and "gFree = min(gFree, " in floor
    # rotated: the ray's direction is turned into the union's frame
    turned = sg.compile(scene.rotate(30, (0, 1, 0)).translate((1, 0, 0)))
    assert "#define RAY_FREE_TURN mat3(" in turned
    assert "#define RAY_FREE_TURN" not in sg.compile(scene.translate((1, 0, 0)))
    # the setting off, Newton, no grid, no union kept as data: plain steps
    assert "#define RAY_FREE" not in sg.compile(scene, free_way=False)
    assert "#define RAY_FREE" not in sg.compile(scene, method="newton")
    assert "#define RAY_FREE" not in sg.compile(scene, grid=False)
    assert "#define RAY_FREE" not in sg.compile(sg.sphere(1) & sg.box(1.5))
    assert "#define RAY_FREE" in sg.compile(_mixed(64, 0))  # rotated instances: by their distance
    assert "RayBox(q, gRayInv" not in sg.compile(_mixed(64, 0))
    # translated subtrees: by their box, and the nearest one by its parts (the robot: body,
    # head, arms, two legs)
    from sdfgl.bench_big import instances
    moved = sg.compile(instances(40)[0])
    assert "RayBox(q, gRayInv" in moved and "max(enterNear, g0Enter0(qNear, gRayInv, gRayDir))" in moved
    # turned ones with the ray turned into their frame
    both = sg.compile(_moved(64, 0))
    assert "RayBox(q, invQ" in both and "(qNear, invNear, dirNear))" in both and "(qNear, gRayInv, gRayDir))" in both
    assert "enterNear" not in sg.compile(_mixed(64, 0))


def _held(node: sg.Node, found: list, offset=(0.0, 0.0, 0.0)) -> tuple[int, bool]:
    """(solid points among 20 000 samples of node's box, whether every one is in a piece)."""
    rng = np.random.default_rng(0)
    lo, hi = node.bounds
    pts = rng.uniform(lo, hi, (20000, 3))
    solid = pts[node.distance(pts) <= 0] + offset
    held = np.zeros(len(solid), bool)
    for p in found:
        held |= (np.linalg.norm(solid - p.centre, axis=1) <= p.radius) if p.kind == "ball" else \
            np.all((solid >= p.lo - 1e-12) & (solid <= p.hi + 1e-12), axis=1)
    return len(solid), bool(held.all())


def test_a_subtree_is_held_by_its_parts_balls_and_boxes():
    from sdfgl.bench_big import twenty_nodes
    from sdfgl.compiler.data.ray_entry import MAX_PIECES, pieces
    found = pieces(twenty_nodes().translate((1, 0, 0)))
    assert [p.kind for p in found] == ["box", "ball", "box", "box", "box"]  # the eyes only remove
    head = found[1]
    assert np.allclose(head.centre, (1, 0.38, 0)) and np.isclose(head.radius, 0.18)
    assert np.allclose(found[3].lo, (0.84, -0.5, -0.06)) and np.allclose(found[3].hi, (0.96, -0.2, 0.06))
    n, held = _held(twenty_nodes(), found, (1, 0, 0))
    assert n > 1000 and held
    # an intersection by its smaller operand, cut to the common box; moves, turns and
    # scales carry the pieces (a turned box becomes the box round it)
    cut = pieces((sg.sphere(1) & sg.box(1.5)) | sg.sphere(0.3).translate((2, 0, 0)))
    assert [p.kind for p in cut] == ["box", "ball"] and np.allclose(cut[0].hi, 0.75)
    moved = pieces((sg.box(1) | sg.sphere(0.5).translate((1, 0, 0))).rotate(90, (0, 0, 1)).scale(2))
    assert [p.kind for p in moved] == ["box", "ball"] and np.allclose(moved[1].centre, (0, 2, 0)) \
        and np.isclose(moved[1].radius, 1.0)
    mixed = (((sg.sphere(0.5) & sg.box(0.8)).translate((0.3, 0, 0)))
             | sg.capsule((0, -0.4, 0), (0, 0.4, 0), 0.1).rotate(30, (1, 0, 0)).translate((0, 0, 0.7))
             | (sg.box(0.2) | sg.sphere(0.15).translate((0, 0.2, 0))).rotate(45, (0, 1, 0)).scale(1.5)
             .translate((-0.6, 0, 0))) - sg.sphere(0.1)
    n, held = _held(mixed, pieces(mixed))
    assert n > 1000 and held and len(pieces(mixed)) == 4
    # what blends or warps is its box; a box inside another adds nothing
    assert pieces(sg.union(sg.box(1), sg.sphere(0.5).translate((2, 0, 0)), k=0.2)) is None
    assert pieces(sg.box(1) | sg.box(0.5)) is None
    turned = pieces(sg.box(1).rotate(45, (0, 0, 1)) | sg.sphere(0.2).translate((3, 0, 0)))
    assert [p.kind for p in turned] == ["box", "ball"] and np.allclose(turned[0].hi, (0.7071, 0.7071, 0.5), atol=1e-4)
    # more parts than MAX_PIECES: the split goes less deep (here: the two halves' boxes)
    row = [sg.sphere(0.1).translate((i, 0, 0)) for i in range(2 * MAX_PIECES)]
    halves = pieces(sg.union(sg.union(*row[:MAX_PIECES]).color(1, 0, 0),  # (a colour keeps the unions apart)
                             sg.union(*row[MAX_PIECES:]).translate((0, 1, 0))))
    assert [p.kind for p in halves] == ["box", "box"]
    assert pieces(sg.union(*row)) is None


def _against_reference(scene: sg.Node) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(hit, reference hit, error, plain marcher's error) on the decided pixels hit by both
    (errors in pixel footprints), after checking the free way took fewer steps."""
    cam = sg.OrbitCamera(distance=5.5, yaw=80, pitch=30, fov=45)
    size = (80, 60)
    got = sg.Renderer().render(scene, cam, size, shadows=False, ao=False, outputs=("color", "depth", "steps"))
    assert "#define RAY_FREE" in got.source.text
    plain = sg.Renderer().render(scene, cam, size, shadows=False, ao=False, outputs=("color", "depth", "steps"),
                                 free_way=False)
    assert "#define RAY_FREE" not in plain.source.text
    o, d = cam.rays(*size)
    t, undecided = trace_rays(scene, o.reshape(-1, 3), d.reshape(-1, 3))
    t, undecided = t.reshape(size[1], size[0]), undecided.reshape(size[1], size[0])
    fp = cam.pixel_angle(size[1]) * np.where(np.isfinite(t), t, 1.0)
    ref_hit, hit = np.isfinite(t), np.isfinite(got.depth)
    sure = ~undecided
    both = hit & ref_hit & sure
    assert got.steps.mean() < 0.9 * plain.steps.mean()
    return hit[sure], ref_hit[sure], np.abs(got.depth[both] - t[both]) / fp[both], \
        np.abs(plain.depth[both] - t[both]) / fp[both]


@pytest.mark.slow
def test_free_way_hits_what_the_reference_hits_in_fewer_steps():
    hit, ref_hit, err, plain_err = _against_reference(_spheres(250, 2))
    assert hit.sum() > 1000
    assert np.array_equal(hit, ref_hit)  # no surface stepped over, none made up
    assert np.percentile(err, 99) < 0.05
    # where it is off, the plain marcher is off the same way (a thin part both pass at a
    # silhouette: the near misses of the accuracy audit), never worse
    assert np.all(err <= plain_err + 0.05)


def test_the_nearest_subtree_entered_by_its_parts_takes_fewer_steps_to_the_same_hits(monkeypatch):
    # (the floor test below checks such a scene against the reference)
    from sdfgl.bench_big import twenty_nodes
    rng = np.random.default_rng(3)
    robot = twenty_nodes()
    scene = sg.union(*[robot.translate(tuple(rng.uniform((-2, -0.6, -2), (2, 0.6, 2)))) for _ in range(120)])
    cam = sg.OrbitCamera(distance=5.5, yaw=80, pitch=30, fov=45)
    refined = sg.Renderer().render(scene, cam, (96, 72), shadows=False, ao=False, outputs=("color", "depth", "steps"))
    assert "max(enterNear, g0Enter0(qNear, gRayInv, gRayDir))" in refined.source.text
    import sdfgl.compiler.data.ray_entry as ray_entry
    monkeypatch.setattr(ray_entry, "pieces", lambda node: None)  # the whole box for every instance
    boxed = sg.Renderer().render(sg.union(*scene.children), cam, (96, 72), shadows=False, ao=False,
                                 outputs=("color", "depth", "steps"))
    assert "enterNear" not in boxed.source.text
    assert refined.steps.mean() < 0.9 * boxed.steps.mean()
    hit = np.isfinite(refined.depth)
    assert hit.sum() > 1500 and np.array_equal(hit, np.isfinite(boxed.depth))
    assert np.percentile(np.abs(refined.depth[hit] - boxed.depth[hit]), 99) < 1e-3


@pytest.mark.slow
def test_free_way_into_subtree_boxes_beside_a_floor_turned_hits_what_the_reference_hits():
    scene = (_moved(64, 2) | sg.plane((0, 1, 0), (0, -0.7, 0))).rotate(35, (0.3, 1, 0.2))
    hit, ref_hit, err, plain_err = _against_reference(scene)
    assert hit.sum() > 1000
    assert np.array_equal(hit, ref_hit)
    assert np.percentile(err, 99) < 0.05
    # thin parts (a robot's arms, eyes) may settle elsewhere than the plain marcher does,
    # but no more often
    assert (err > 0.5).sum() <= (plain_err > 0.5).sum()
