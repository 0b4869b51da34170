"""Mesh export (sdfgl.mesh): sampling, extraction, topology, accuracy, colours, files, CLI."""
import subprocess
import sys

import numpy as np
import pytest

import sdfgl as sg
import sdfgl.mesh.sparse as sparse
from sdfgl.mesh.geometry import distance_to_mesh, volume
from sdfgl.mesh.lattice import make_lattice
from sdfgl.mesh.report import Twin
from sdfgl.mesh.sample import GPUField
from sdfgl.mesh.topology import edge_use

trimesh = pytest.importorskip("trimesh")


def csg():
    """fogleman/sdf's CSG example."""
    c = sg.cylinder(0.5, 4)
    return (sg.sphere(1) & sg.box(1.5)) - (c.orient(sg.X) | c | c.orient(sg.Z))


def closed(m) -> tuple[bool, bool]:
    counts, twice = edge_use(m.faces)
    return bool(np.all(counts == 2)), twice == 0


# -- API and errors ----------------------------------------------------------------------------

def test_mesh_api_arrays():
    m = sg.mesh(sg.sphere(1), resolution=24)
    assert isinstance(m, sg.Mesh) and m.mode == "mc"
    assert m.vertices.shape[1] == 3 and m.vertices.dtype == np.float64
    assert m.faces.shape[1] == 3 and m.faces.min() >= 0 and m.faces.max() < len(m.vertices)
    assert m.normals.shape == m.vertices.shape
    assert np.allclose(np.linalg.norm(m.normals, axis=1), 1, atol=1e-3)
    # normals point outwards: along the position on a sphere
    assert np.all(np.einsum("ij,ij->i", m.normals, m.vertices) > 0.99)
    assert m.colors.shape == m.vertices.shape
    assert abs(m.step - 2 / 22) < 1e-9


def test_step_and_bounds_set_the_lattice():
    lat = make_lattice(sg.sphere(1), step=0.1)
    assert lat.step == 0.1
    assert np.allclose(lat.box[0], -1.1) and np.allclose(lat.box[1], 1.1)
    assert all(c % 8 == 0 for c in lat.cells)
    assert np.all(lat.start + np.asarray(lat.cells) * lat.step >= lat.box[1])
    lat = make_lattice(sg.sphere(1), step=0.05, bounds=((-2, -1, -1), (2, 1, 0)))
    assert np.allclose(lat.box[0], (-2, -1, -1)) and np.allclose(lat.box[1], (2, 1, 0))


@pytest.mark.parametrize("kwargs, words", [
    (dict(step=0.1, resolution=32), "one of step"),
    (dict(step=-1.0), "step"),
    (dict(resolution=3), "resolution"),
    (dict(mode="fancy"), "mode"),
    (dict(bounds=((0, 0, 0), (1, 1, -1))), "bounds"),
    (dict(step=1e-5), "larger step"),
])
def test_bad_arguments_are_clear_errors(kwargs, words):
    with pytest.raises(sg.ParameterError, match=words):
        sg.mesh(sg.sphere(1), **kwargs)


def test_unbounded_scene_asks_for_bounds():
    with pytest.raises(sg.ParameterError, match="unbounded.*bounds="):
        sg.mesh(sg.plane(), resolution=16)
    m = sg.mesh(sg.sphere(0.4).repeat((1.0, 0, 0)), resolution=48, bounds=((-1.2, -0.6, -0.6), (1.2, 0.6, 0.6)))
    assert closed(m) == (True, True)
    # the box cuts the spheres at x = +-1: one whole sphere and two closed caps
    assert len(trimesh.Trimesh(m.vertices, m.faces, process=False).split(only_watertight=True)) == 3
    ball = 4 / 3 * np.pi * 0.4 ** 3
    assert ball * 1.5 < volume(m.vertices, m.faces) < ball * 3


def test_missing_extra_says_how_to_install(monkeypatch):
    from sdfgl.mesh.deps import require
    monkeypatch.setitem(sys.modules, "trimesh", None)
    with pytest.raises(sg.SdfglError, match=r"sdfgl\[mesh\]"):
        require("trimesh")


# -- sampling ----------------------------------------------------------------------------------

def test_gpu_lattice_matches_the_twin():
    s = csg()
    f = GPUField(s, np.full(3, -2.0), np.full(3, 2.0))
    corners = np.array([[0, 0, 0], [20, 13, 23]])
    v = f.blocks(np.full(3, -1.1), corners, 9, 0.07)
    i = np.arange(9)
    for b, c in enumerate(corners):
        p = -1.1 + (c + np.stack(np.meshgrid(i, i, i, indexing="ij"), -1)) * 0.07
        assert np.abs(v[b] - s.distance(p)).max() < 1e-5
    # more blocks than one texture row holds (4096), 5^3 samples each (not a multiple of 4 a texel)
    corners = np.random.default_rng(1).integers(0, 40, (5000, 3))
    v = f.blocks(np.full(3, -1.1), corners, 5, 0.05)
    i = np.arange(5)
    grid = np.stack(np.meshgrid(i, i, i, indexing="ij"), -1)
    p = -1.1 + (corners[:, None, None, None, :] + grid) * 0.05
    assert np.abs(v - s.distance(p.reshape(-1, 3)).reshape(v.shape)).max() < 1e-5
    pts = np.array([[0.8, 0.6, 0.1], [0.2, -0.1, 0.3]])
    val, grad, _ = f.gradient_bend(pts, 1e-3)
    assert np.allclose(val, s.distance(pts), atol=1e-5)
    assert np.allclose(grad[0], (1, 0, 0), atol=1e-3)  # off the box face


def test_gpu_projection_moves_points_onto_the_surface():
    s = sg.sphere(1)
    f = GPUField(s, np.full(3, -2.0), np.full(3, 2.0))
    d = np.random.default_rng(2).normal(size=(300, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    r = np.random.default_rng(3).uniform(0.97, 1.03, (300, 1))  # up to 0.3 cell of 0.1 off
    move, normal, value = f.project(d * r, 1e-3, 1e-5, 0.05, 4)
    assert np.abs(np.linalg.norm(d * r + move, axis=1) - 1).max() < 2e-5
    assert np.allclose(normal, d, atol=1e-3)
    assert np.allclose(value, s.distance(d * r + move), atol=2e-6)  # the field where each point ends
    # each step moves at most max_move; no step leaves the point where it is
    move, _, value = f.project(d * 1.3, 1e-3, 1e-5, 0.05, 2)
    assert np.allclose(np.linalg.norm(move, axis=1), 0.1, atol=1e-5)
    assert np.allclose(value, 0.2, atol=1e-5)
    move, normal, value = f.project(d * r, 1e-3, 1e-5, 0.05, 0)
    assert not move.any() and np.allclose(normal, d, atol=1e-3) and np.allclose(value, r[:, 0] - 1, atol=1e-6)
    before = f.point_samples
    f.project(d[:1], 1e-3, 1e-5, 0.05, 4)  # on the surface already: one gradient, 5 map() calls
    assert f.point_samples - before == 5


def _canonical(m) -> tuple[np.ndarray, np.ndarray]:
    """Vertices in lexicographic order and the triangles over them (each rotated to start at
    its smallest vertex, so winding counts), sorted: equal for the same mesh numbered otherwise."""
    order = np.lexsort(m.vertices.T[::-1])
    rank = np.empty(len(order), np.int64)
    rank[order] = np.arange(len(order))
    f = rank[m.faces]
    f = np.take_along_axis(f, (np.argmin(f, 1)[:, None] + np.arange(3)) % 3, 1)
    return m.vertices[order], f[np.lexsort(f.T[::-1])]


def test_sparse_equals_dense_and_samples_less(monkeypatch):
    s = csg()
    m = sg.mesh(s, resolution=96)
    monkeypatch.setattr(sparse, "skip_radius", lambda lipschitz, step, cells=8: float("inf"))
    d = sg.mesh(s, resolution=96)
    (mv, mf), (dv, df) = _canonical(m), _canonical(d)
    assert np.array_equal(mf, df) and np.allclose(mv, dv)
    assert d.samples >= m.lattice.samples and m.samples < 0.65 * d.samples
    # cost follows the surface: at twice the resolution the sparse share nearly halves (measured
    # 0.57 -> 0.34 with blocks refined to 4^3 cubes; 0.70 -> 0.48 with 8^3 blocks)
    monkeypatch.undo()
    lat = make_lattice(s, resolution=192)
    field = GPUField(s, *lat.box)
    for _ in sparse.chunks(field, lat, s.lipschitz):
        pass
    assert field.samples < 0.40 * lat.samples


def test_chunk_seams_join():
    # 136 cells a side: 2 x 2 x 2 chunks; the surface crosses every seam. Seam vertices are
    # shared (no doubled positions) and the mesh is closed across them.
    m = sg.mesh(sg.sphere(1).translate((0.05, -0.03, 0.02)), resolution=130, colors=False)
    assert m.lattice.cells[0] > 128
    assert closed(m) == (True, True)
    assert len(np.unique(m.vertices, axis=0)) == len(m.vertices)


def test_marching_cubes_drops_repeated_triangles_only():
    from sdfgl.mesh.extract_mc import ON_FACE, _first_copies
    assert 0 < ON_FACE.sum() < 40  # only a few table triangles lie on one cell face
    faces = np.array([[0, 1, 2], [2, 3, 4], [2, 0, 1], [5, 6, 7], [1, 0, 2]])
    assert _first_copies(faces, np.array([0, 2, 4])).tolist() == [True, True, False, True, False]
    assert _first_copies(faces, np.array([1, 3])).all()


def test_implicit_fields_skip_nothing():
    s = sg.implicit("x**2 + y**2/0.5 + z**2 - 1", bounds=((-1.2, -1, -1.2), (1.2, 1, 1.2)))
    assert sparse.skip_radius(s.lipschitz, 0.1) == float("inf")
    m = sg.mesh(s, resolution=32)
    assert closed(m) == (True, True)
    assert m.samples >= m.lattice.samples  # every block sampled


# -- topology and volume over every node kind --------------------------------------------------

def _zoo():
    from .nodes_zoo import all_nodes
    out = []
    for name, node in all_nodes().items():
        lo, hi = node.bounds
        if np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)):
            out.append(pytest.param(node, id=name))
    return out


# Volumes are held against the twin's adaptive integral (48^3 cells, those the surface may cross
# halved once: 96^3 effective; kept cheap for CI).
# Marching cubes at 48 cells misses it by > 1 % on these (measured): it cuts
# every sharp edge (a chamfer ~ cell^2 per unit of edge length), which on thin bars, small
# copies and bent slabs is > 1 % of the solid; the sharp mode keeps those edges. (symmetric is
# on the edge: -0.45 % against this cheap reference, -1.13 % against the 384^3-effective one.)
MC_OVER_1PC = {"box_frame", "bend", "repeat_finite", "repeat_finite_cheap", "difference_circular", "repeat_polar",
               "elongate", "sierpinski", "tree", "noise_field", "extrude_scale2d_axes",
               "extrude_round_onion2d", "extrude_arc", "extrude_star", "extrude_twist", "bend_x", "bend_y", "tube",
               "bezier_tube", "capped_torus"}
# still > 1 % in the sharp mode at 48 cells: features about a cell thin or thinner (tree twigs of
# radius 0.02 in a 0.125 cell: its bounds are loose; sierpinski's smallest tetrahedra; a sliver
# left by the circular blend; the cheap repeat's copies; the elongated torus's 0.1 tube; thin tubes;
# box_frame's bars, -1.1 % since the crossings are bracketed: -0.17 % before, open work)
SHARP_OVER_1PC = {"repeat_finite_cheap", "difference_circular", "elongate", "sierpinski", "tree", "tube", "bezier_tube",
                  "box_frame"}


def edge_and_vertex_manifold(m) -> bool:
    """Every edge on two faces, one winding, and the faces around each vertex one fan."""
    if closed(m) != (True, True):
        return False
    f = m.faces
    link = np.concatenate([f, np.roll(f, -1, axis=1), np.roll(f, -2, axis=1)])
    link = link[np.argsort(link[:, 0], kind="stable")]
    starts = np.searchsorted(link[:, 0], np.arange(len(m.vertices) + 1))
    for v in range(len(m.vertices)):
        ring = link[starts[v]:starts[v + 1], 1:]
        nxt = dict(ring.tolist())
        x, steps = ring[0, 0], 0
        while steps <= len(ring):
            x, steps = nxt.get(x, -1), steps + 1
            if x == ring[0, 0] or x == -1:
                break
        if len(nxt) != len(ring) or x != ring[0, 0] or steps != len(ring):
            return False
    return True


_ZOO: dict = {}
_TWIN_VOLUME: dict = {}


def _zoo_mesh(node, name: str, mode: str) -> tuple[int, tuple[bool, bool], float, float]:
    """(faces, closed(), volume, the twin's volume) of one kind's mesh at 48 cells, made once for
    the topology and the volume tests (the twin's volume once for both modes: their box is the same)."""
    if (name, mode) not in _ZOO:
        m = sg.mesh(node, resolution=48, colors=False, mode=mode)
        box = tuple(map(tuple, m.lattice.box))
        if (name, box) not in _TWIN_VOLUME:
            _TWIN_VOLUME[name, box] = Twin(node, m.lattice.box).integrate(48, levels=1)
        _ZOO[name, mode] = (len(m.faces), closed(m), volume(m.vertices, m.faces), _TWIN_VOLUME[name, box])
    return _ZOO[name, mode]


def _zoo_modes():
    return [pytest.param(p.values[0], "mc", id=f"mc-{p.id}") for p in _zoo()] + [
        pytest.param(p.values[0], "sharp", id=f"sharp-{p.id}") for p in _zoo() if p.id in MC_OVER_1PC]


@pytest.mark.parametrize("node, mode", _zoo_modes())
@pytest.mark.slow
def test_every_bounded_node_kind_meshes_closed(node, mode, request):
    faces, topology, _, _ = _zoo_mesh(node, request.node.callspec.id.split("-", 1)[1], mode)
    assert faces > 0
    assert topology == (True, True), "not watertight / winding inconsistent"


@pytest.mark.slow
@pytest.mark.parametrize("node, mode", _zoo_modes())
def test_every_bounded_node_kind_has_the_twins_volume(node, mode, request):
    name = request.node.callspec.id.split("-", 1)[1]
    if name in (MC_OVER_1PC if mode == "mc" else SHARP_OVER_1PC):
        request.applymarker(pytest.mark.xfail(strict=True, reason="features thinner than a cell at 48 cells"))
    _, _, mesh_volume, twin_volume = _zoo_mesh(node, name, mode)
    assert abs(mesh_volume - twin_volume) < 0.01 * twin_volume


def test_volume_error_estimate_follows_the_twin():
    # the estimate from the field at edge midpoints (sdfgl.mesh.deficit) against the twin's
    # integral: a tube 2 cells thick loses ~8 %, a sphere 20 cells wide ~0.1 %
    from sdfgl.mesh.deficit import volume_error
    for node, res in ((sg.sphere(0.2).repeat((0, 0, 1.0), count=(0, 0, 2)), 48), (sg.sphere(1), 40)):
        m = sg.mesh(node, resolution=res, colors=False)
        field = GPUField(node, *m.lattice.box)
        actual = volume(m.vertices, m.faces) / Twin(node, m.lattice.box).integrate(48, levels=2) - 1
        estimate = volume_error(field, m.vertices, m.faces, m.step)
        assert actual < -1e-3 and 0.6 * actual > estimate > 1.5 * actual, (actual, estimate)


@pytest.mark.slow
def test_default_step_is_refined_where_the_volume_would_be_off():
    # thin parts at the default 2^22 samples (a tree's twigs 2 cells thick, a Sierpinski
    # tetrahedron's smallest pieces 1 cell, a sliver left by a blend) are meshed again finer,
    # to within 1 % of the twin's volume; a sphere keeps the default step
    from tests.nodes_zoo import all_nodes
    nodes = all_nodes()
    for name in ("tree", "sierpinski", "difference_circular"):
        m = sg.mesh(nodes[name], colors=False)
        assert m.default_step is not None and m.step < 0.5 * m.default_step, name
        twin = Twin(nodes[name], m.lattice.box).integrate(48, levels=3)
        assert abs(volume(m.vertices, m.faces) - twin) < 0.01 * twin, name
    plain = sg.mesh(sg.sphere(1), colors=False)
    assert plain.default_step is None and plain.step == make_lattice(sg.sphere(1)).step
    fixed = sg.mesh(nodes["tree"], samples=2 ** 22, colors=False)  # a size given: no refinement
    assert fixed.default_step is None


def test_twin_volume_integral_is_accurate():
    lat = make_lattice(sg.torus(0.8, 0.03), resolution=48)
    exact = 2 * np.pi ** 2 * 0.8 * 0.03 ** 2      # a tube 0.6 cells thick at 48 cells
    assert abs(Twin(sg.torus(0.8, 0.03), lat.box).integrate(48, levels=2) - exact) < 0.01 * exact
    s = sg.implicit("x**2 + y**2/0.5 + z**2 - 1", bounds=((-1.2, -1, -1.2), (1.2, 1, 1.2)))  # no Lipschitz bound
    lat = make_lattice(s, resolution=32)
    exact = 4 / 3 * np.pi * np.sqrt(0.5)
    assert abs(Twin(s, lat.box).integrate(32, levels=2) - exact) < 1e-3 * exact


def test_sharp_mode_is_manifold_where_two_cells_share_an_ambiguous_face():
    # sierpinski at 48 cells has ~80 faces whose two cells each join both segments of the face
    # into one piece; plain per-piece dual contouring puts four quads on one edge there
    m = sg.mesh(sg.sierpinski(4, 1.0), resolution=48, mode="sharp", colors=False)
    assert edge_and_vertex_manifold(m)


def test_sampling_box_closes_a_cut_solid():
    m = sg.mesh(sg.sphere(1), resolution=40, bounds=((-1.2, -1.2, -1.2), (1.2, 0.0, 1.2)))
    assert closed(m) == (True, True)
    assert abs(volume(m.vertices, m.faces) - 2 / 3 * np.pi) < 0.01 * 2 / 3 * np.pi
    assert m.vertices[:, 1].max() < 1e-6  # the cap lies on the box face


# -- accuracy ----------------------------------------------------------------------------------

@pytest.mark.parametrize("mode", ["mc", "sharp"])
def test_vertices_lie_on_the_surface(mode):
    m = sg.mesh(csg(), resolution=48, mode=mode)
    f = np.abs(Twin(m.scene, m.lattice.box)(m.vertices))
    assert f.max() <= 0.05 * m.step


@pytest.mark.slow
def test_smooth_parts_within_half_a_cell_both_ways():
    for s in (sg.sphere(1), sg.torus(0.8, 0.3)):
        r = sg.mesh(s, resolution=48).report(twin_samples=3000)
        assert r.hausdorff <= 0.5 * r.step
        assert r.watertight and r.winding_consistent and r.volume_error < 0.01
        assert r.max_field <= 0.05 * r.step and r.p99_field <= r.max_field


SIGNS = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T


def box_features(half, n: int = 5):
    """(corners (8, 3), points on the 12 edges (12 n, 3)) of the box with half sizes ``half``."""
    corners = SIGNS * np.asarray(half, float)
    t = np.linspace(0, 1, n + 2)[1:-1, None]
    edges = np.concatenate([corners[a] + t * (corners[b] - corners[a]) for a in range(8) for b in range(a + 1, 8)
                            if np.sum(SIGNS[a] != SIGNS[b]) == 1])
    return corners, edges


def test_sharp_mode_keeps_box_edges_and_corners():
    box = sg.box((1.0, 0.8, 0.6)).rotate(27, (1, 2, 3)).translate((0.013, -0.021, 0.007))
    m = sg.mesh(box, resolution=32, mode="sharp")
    assert closed(m) == (True, True)
    rot = box.children[0]  # Translate(Rotate(box)): corners and edges of the rotated box
    corners, edges = box_features((0.5, 0.4, 0.3))
    to_world = lambda p: p @ rot.m.T + np.array([0.013, -0.021, 0.007])  # noqa: E731
    assert np.allclose(box.distance(to_world(corners)), 0, atol=1e-9)
    d_corner = distance_to_mesh(to_world(corners), m.vertices, m.faces) / m.step
    d_edge = distance_to_mesh(to_world(edges), m.vertices, m.faces) / m.step
    # measured: edges max 0.005, corners max 0.003 cell (0.047 / 0.022 before crease crossings got
    # their faces' normals; 0.13 / 0.17 before the crossings were refined inside their bracket)
    assert np.median(d_edge) <= 0.01 and d_edge.max() <= 0.1 and d_corner.max() <= 0.1
    # marching cubes cuts edges and corners: the sharp mode is what keeps them
    mc = sg.mesh(box, resolution=32)
    assert np.median(distance_to_mesh(to_world(edges), mc.vertices, mc.faces)) > 0.2 * mc.step
    assert distance_to_mesh(to_world(corners), mc.vertices, mc.faces).max() > 0.4 * mc.step


def _random_parts(rng, slots: int = 8, spacing: float = 1.6):
    """Disjoint randomly rotated boxes (and, in two slots, a box with a smaller box cut out of
    one corner) on a 2x2x2 grid: (scene, corners, edge points) in world coordinates."""
    parts, corners, edges = [], [], []
    for k in range(slots):
        centre = spacing * (np.array([k & 1, (k >> 1) & 1, (k >> 2) & 1]) - 0.5) + rng.uniform(-0.05, 0.05, 3)
        half = np.array([0.5, 0.4, 0.3]) * rng.uniform(0.8, 1.2, 3)
        if k < slots - 2:
            part = sg.box(tuple(2 * half))
            c, e = box_features(half)
        else:  # the concave corner where three cut faces meet, and the three cut edges
            corner = half * rng.uniform(0.3, 0.7, 3)
            part = sg.box(tuple(2 * half)) - sg.box(tuple(2 * half)).translate(tuple(corner + half))
            t = np.linspace(0, 1, 7)[1:-1, None]
            ends = [np.where(np.arange(3) == a, half, corner) for a in range(3)]
            c, e = corner[None], np.concatenate([corner + t * (q - corner) for q in ends])
        rot = part.rotate(rng.uniform(0, 90), tuple(rng.normal(size=3)))
        parts.append(rot.translate(tuple(centre)))
        corners.append(c @ rot.m.T + centre)
        edges.append(e @ rot.m.T + centre)
    return sg.union(*parts), np.concatenate(corners), np.concatenate(edges)


def test_sharp_mode_keeps_corners_and_edges_of_random_boxes():
    # 18 boxes and 6 concave CSG corners at random rotations and offsets, ~32 cells a box. Before
    # crossings on a crease got their faces' normals (sdfgl.mesh.creases), about 1 box in 6 had
    # a corner 0.1-0.4 cell off (a crossing within the gradient stencil of a box edge took a mixed
    # normal; here 0.23 cell); measured since: corners max 0.022, edges max 0.010 cell here, and
    # 0.033 / 0.012 over 250 single boxes and 30 CSG corners at 24-64 cells
    rng = np.random.default_rng(14)
    for _ in range(3):
        scene, corners, edges = _random_parts(rng)
        assert np.allclose(scene.distance(corners), 0, atol=1e-9)
        assert np.allclose(scene.distance(edges), 0, atol=1e-9)
        m = sg.mesh(scene, step=1.2 / 32, mode="sharp", colors=False)
        assert closed(m) == (True, True)
        assert distance_to_mesh(corners, m.vertices, m.faces).max() <= 0.1 * m.step
        assert distance_to_mesh(edges, m.vertices, m.faces).max() <= 0.1 * m.step


# -- colours and files -------------------------------------------------------------------------

def two_colours():
    return sg.sphere(0.6).color(1, 0, 0) | sg.box(0.8).translate((1.0, 0, 0)).color(0, 0, 1)


def test_vertex_colours_come_from_the_scene():
    m = sg.mesh(two_colours(), resolution=32)
    left, right = m.vertices[:, 0] < 0.3, m.vertices[:, 0] > 0.75
    assert np.allclose(m.colors[left], (1, 0, 0), atol=1e-3)
    assert np.allclose(m.colors[right], (0, 0, 1), atol=1e-3)


def test_a_scene_without_colours_gets_the_colour_its_shader_draws():
    scene = sg.sphere(1) & sg.box(1.5)  # no material node: no colour pass, the one colour
    m = sg.mesh(scene, resolution=24)
    drawn = GPUField(scene, *m.lattice.box).colors(m.vertices)
    assert m.colors.dtype == np.float32 and m.colors.shape == (len(m.vertices), 3)
    assert np.array_equal(m.colors, drawn)


@pytest.mark.parametrize("suffix", [".stl", ".obj", ".ply", ".glb", ".gltf", ".3mf"])
def test_every_format_reads_back_in_trimesh(tmp_path, suffix):
    m = sg.mesh(two_colours(), resolution=24)
    path = m.save(tmp_path / f"part{suffix}")
    t = trimesh.load(str(path), force="mesh", process=True)
    t.merge_vertices(merge_tex=True, merge_norm=True)
    assert len(t.faces) == len(m.faces) and len(t.vertices) == len(m.vertices)
    assert t.is_watertight and t.is_winding_consistent
    assert abs(t.volume - volume(m.vertices, m.faces)) < 1e-4 * abs(t.volume)
    if suffix in (".ply", ".glb", ".gltf"):
        vc = np.asarray(t.visual.vertex_colors)[:, :3]
        assert {(255, 0, 0), (0, 0, 255)} <= {tuple(c) for c in vc}
    if suffix == ".obj":
        mtl = (tmp_path / "part.mtl").read_text()
        assert "Kd 1.0000 0.0000 0.0000" in mtl and "Kd 0.0000 0.0000 1.0000" in mtl


def test_more_than_65535_vertices_do_not_wrap(tmp_path):
    m = sg.mesh(sg.sphere(1), resolution=128, colors=False)
    assert len(m.vertices) > 70000
    for suffix in (".glb", ".ply", ".obj"):
        t = trimesh.load(str(m.save(tmp_path / f"big{suffix}")), force="mesh", process=False)
        assert len(t.vertices) == len(m.vertices) and t.faces.max() == len(m.vertices) - 1
        assert np.array_equal(np.asarray(t.faces), m.faces)


def test_unknown_format_is_a_clear_error(tmp_path):
    with pytest.raises(sg.SdfglError, match="unknown format"):
        sg.mesh(sg.sphere(1), resolution=16).save(tmp_path / "part.xyz")


def test_node_save_like_fogleman(tmp_path):
    m = sg.sphere(1).save(str(tmp_path / "s.stl"), resolution=16)
    assert isinstance(m, sg.Mesh)
    assert len(trimesh.load(str(tmp_path / "s.stl")).faces) == len(m.faces)


def test_live_parameters_and_far_scenes():
    r = sg.param(0.5)
    m = sg.mesh(sg.sphere(r), resolution=24)
    r.value = 0.8
    m2 = sg.mesh(sg.sphere(r), resolution=24)
    assert abs(np.linalg.norm(m.vertices, axis=1).mean() - 0.5) < 1e-3
    assert abs(np.linalg.norm(m2.vertices, axis=1).mean() - 0.8) < 1e-3
    far = sg.mesh(sg.sphere(1).translate((2e4, 0, 0)), resolution=24)
    assert np.abs(np.linalg.norm(far.vertices - (2e4, 0, 0), axis=1) - 1).max() < 0.05 * far.step


# -- command line ------------------------------------------------------------------------------

@pytest.mark.slow
def test_cli_writes_mesh_and_report(tmp_path):
    scene = tmp_path / "scene.py"
    scene.write_text("import sdfgl as sg\nscene = sg.sphere(1) - sg.box(0.8)\n")
    out = subprocess.run([sys.executable, "-m", "sdfgl.cli", "mesh", str(scene), "-o", str(tmp_path / "p.stl"),
                          "--resolution", "24", "--sharp", "--report"], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "wrote" in out.stdout and "Hausdorff" in out.stdout and "watertight" in out.stdout
    assert trimesh.load(str(tmp_path / "p.stl")).is_watertight
    scene.write_text("import sdfgl as sg\nscene = sg.plane()\n")
    out = subprocess.run([sys.executable, "-m", "sdfgl.cli", "mesh", str(scene), "-o", str(tmp_path / "q.stl")],
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 2 and "--bounds" in out.stderr and "Traceback" not in out.stderr


def test_progress_line(capsys):
    p = sparse.Progress(sys.stderr, after=0.0)
    p(1, 4)
    p(4, 4)
    err = capsys.readouterr().err
    assert "meshing:  25% (1 of 4 chunks" in err and "100%" in err
