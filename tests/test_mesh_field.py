"""A triangle mesh as a field: GPU vs the libigl twin, repairs, bad files, and the mesh
under booleans, offsets, blends, export and every shader target."""
import pickle

import numpy as np
import pytest
import trimesh

import sdfgl as sg
from sdfgl.compiler.data.triangles import LEAF_SIZE, STACK_DEPTH, build
from sdfgl.compiler.generate import generate
from sdfgl.nodes.mesh_field import MAX_TRIANGLES, MeshField
from sdfgl.settings import Settings

pytest.importorskip("igl")


def torus() -> trimesh.Trimesh:
    """sg.torus(0.6, 0.2) as 2304 triangles (in the XZ plane, as sg.torus)."""
    m = trimesh.creation.torus(0.6, 0.2, major_sections=48, minor_sections=24)
    return m.apply_transform(trimesh.transformations.rotation_matrix(-np.pi / 2, (1, 0, 0)))


def bumpy(subdivisions: int = 4) -> trimesh.Trimesh:
    """A displaced sphere: concave and convex regions, closed."""
    m = trimesh.creation.icosphere(subdivisions)
    v = m.vertices
    r = 1.0 + 0.15 * np.sin(5 * v[:, 0]) * np.sin(5 * v[:, 1]) * np.sin(5 * v[:, 2])
    return trimesh.Trimesh(v * r[:, None], m.faces, process=False)


def figures(node: sg.Node, pts: np.ndarray, renderer) -> tuple[float, int]:
    """(max |gpu - twin| / bbox diagonal, sign disagreements farther than 1e-4 diagonals)."""
    lo, hi = node.bounds
    diag = float(np.linalg.norm(hi - lo))
    gpu = sg.evaluate(node, pts, renderer=renderer).astype(np.float64)
    ref = node.distance(pts)
    far = np.abs(ref) > 1e-4 * diag
    return float(np.abs(gpu - ref).max()) / diag, int(np.count_nonzero(np.sign(gpu[far]) != np.sign(ref[far])))


@pytest.mark.parametrize("make", [torus, bumpy])
def test_gpu_distance_matches_libigl(renderer, make):
    node = sg.from_mesh(make())
    lo, hi = node.bounds
    rng = np.random.default_rng(5)
    pts = rng.uniform(lo - 0.3, hi + 0.3, (20000, 3))
    near = node.vertices[rng.integers(0, len(node.vertices), 5000)] + rng.normal(scale=0.01, size=(5000, 3))
    err, flips = figures(node, np.concatenate([pts, near]), renderer)
    assert err <= 1e-5 and flips == 0


def test_many_points_go_in_spatial_order_and_come_back_in_theirs(renderer):
    from sdfgl.evaluate import SORT_MIN, spatial_order
    rng = np.random.default_rng(2)
    pts = rng.uniform(-1, 1, (3 * SORT_MIN, 3))
    order = spatial_order(pts)
    assert np.array_equal(np.sort(order), np.arange(len(pts)))
    walk = np.linalg.norm(np.diff(pts[order], axis=0), axis=1).mean()
    assert walk < 0.2 * np.linalg.norm(np.diff(pts, axis=0), axis=1).mean()
    node = sg.from_mesh(torus())
    together = sg.evaluate(node, pts.reshape(3, SORT_MIN, 3), renderer=renderer)  # sorted on the GPU
    apart = [sg.evaluate(node, pts[k:k + SORT_MIN // 2], renderer=renderer) for k in range(0, len(pts), SORT_MIN // 2)]
    assert together.shape == (3, SORT_MIN)
    assert np.array_equal(together.reshape(-1), np.concatenate(apart))


def test_two_meshes_in_one_scene_keep_their_own_distances(renderer):
    # the walk starts from the last call's closest triangle; the other mesh's must not count
    a, b = sg.from_mesh(torus(), name="torus"), sg.from_mesh(bumpy(3), name="ball")
    scene = sg.union(a, b.translate((0.9, 0.3, 0)), k=0.05) - b.scale(0.5)
    rng = np.random.default_rng(8)
    lo, hi = scene.bounds
    err, flips = figures(scene, rng.uniform(lo - 0.2, hi + 0.2, (6000, 3)), renderer)
    assert err <= 1e-5 and flips == 0
    cam = sg.OrbitCamera.framing(*scene.bounds, aspect=48 / 36)
    res = renderer.render(scene, cam, (48, 36), outputs=("depth",), shadows=False, ao=False)
    o, d = cam.rays(48, 36)
    hit = np.isfinite(res.depth)
    p = o[hit] + d[hit] * res.depth[hit][:, None].astype(np.float64)
    assert hit.mean() > 0.1 and np.abs(scene.distance(p)).max() < 1e-3


def test_hierarchy_is_balanced_and_lists_every_triangle_once():
    m = bumpy(5)
    bvh = build(np.asarray(m.vertices), np.asarray(m.faces))
    assert bvh.depth < STACK_DEPTH and bvh.depth <= np.ceil(np.log2(len(m.faces) / LEAF_SIZE)) + 2
    codes = bvh.nodes.reshape(-1, 4, 4)[:, :2, 3].ravel().astype(int)
    leaves = -codes[codes < 0]
    counts = leaves & 7
    assert counts.max() <= LEAF_SIZE and counts.sum() == len(m.faces) == bvh.count
    assert len(np.unique(leaves >> 3)) == len(leaves)


def test_inward_winding_is_turned_outward(renderer):
    cube = trimesh.creation.box((1, 1, 1))
    inward = MeshField(cube.vertices, cube.faces[:, ::-1])
    assert np.array_equal(inward.faces, cube.faces)
    pts = np.array([[0, 0, 0], [1, 0, 0], [0.2, 0.4, 0.1]])
    assert np.allclose(sg.evaluate(inward, pts, renderer=renderer), [-0.5, 0.5, -0.1], atol=1e-6)
    assert np.allclose(inward.distance(pts), [-0.5, 0.5, -0.1])
    assert inward.exactness == sg.EXACT and inward.lipschitz == 1.0
    assert np.allclose(inward.bounds[0], -0.5) and np.allclose(inward.bounds[1], 0.5)


def test_flipped_faces_are_turned_and_small_holes_filled(renderer):
    m = trimesh.creation.icosphere(3)
    faces = m.faces.copy()
    faces[[3, 10, 50]] = faces[[3, 10, 50]][:, ::-1]  # three faces wound the wrong way
    with pytest.raises(sg.MeshError, match="mesh 'flipped'.*not a closed, consistently oriented"):
        MeshField(m.vertices, faces, name="flipped")
    fixed = sg.from_mesh(trimesh.Trimesh(m.vertices, faces, process=False), name="flipped")
    holed = sg.from_mesh(trimesh.Trimesh(m.vertices, np.delete(m.faces, [7], axis=0), process=False))
    pts = np.array([[0, 0, 0], [0.5, 0.1, 0], [2, 0, 0]])
    for node in (fixed, holed):
        assert np.allclose(sg.evaluate(node, pts, renderer=renderer), [-1, -0.49, 1], atol=0.02)


def test_what_cannot_be_signed_is_refused_naming_the_mesh():
    m = trimesh.creation.icosphere(2)
    with pytest.raises(sg.MeshError, match="mesh 'open': .*border a hole"):
        sg.from_mesh(trimesh.Trimesh(m.vertices, m.faces[m.vertices[m.faces].mean(1)[:, 1] < 0.3]), name="open")
    a, b = trimesh.creation.box((1, 1, 1)), trimesh.creation.box((1, 1, 1))
    v = np.concatenate([a.vertices, b.vertices + [1, 1, 0]])  # two cubes sharing one edge: non-manifold
    f = np.concatenate([a.faces, b.faces + len(a.vertices)])
    with pytest.raises(sg.MeshError, match="mesh 'pair'"):
        sg.from_mesh(trimesh.Trimesh(v, f), name="pair")
    bad = m.vertices.copy()
    bad[4] = np.nan
    with pytest.raises(sg.MeshError, match="mesh 'nan': 1 vertices are not finite"):
        sg.from_mesh(trimesh.Trimesh(bad, m.faces, process=False), name="nan")
    with pytest.raises(sg.MeshError, match=f"over the limit of {MAX_TRIANGLES}"):
        MeshField(m.vertices, np.zeros((MAX_TRIANGLES + 1, 3), dtype=np.int32), name="huge")
    with pytest.raises(sg.MeshError, match="has no triangles"):
        MeshField(m.vertices, np.zeros((0, 3), dtype=int))
    with pytest.raises(sg.MeshError, match="outside 0..161"):
        MeshField(m.vertices, m.faces + 1)


@pytest.mark.parametrize("ext", ["stl", "obj", "ply", "glb", "3mf", "off"])
def test_every_format_loads(tmp_path, ext):
    path = tmp_path / f"t.{ext}"
    torus().export(str(path))
    node = sg.load_mesh(path)
    assert len(node.faces) == 2304 and node.name == str(path)
    assert float(node.distance((0.6, 0, 0))) == pytest.approx(-0.2, abs=0.01)


def test_units_and_scale(tmp_path):
    path = tmp_path / "t.stl"
    path.write_bytes(torus().export(file_type="stl"))
    assert sg.load_mesh(path).bounds[1][0] == pytest.approx(0.8)
    assert sg.load_mesh(path, units="cm").bounds[1][0] == pytest.approx(8.0)
    assert sg.load_mesh(path, units="in", scene_units="cm", scale=2).bounds[1][0] == pytest.approx(0.8 * 2.54 * 2)
    with pytest.raises(sg.ParameterError, match="unknown unit 'parsec'"):
        sg.load_mesh(path, units="parsec")


def test_bad_files_name_the_file(tmp_path):
    empty = tmp_path / "empty.stl"
    empty.write_bytes(b"")
    with pytest.raises(sg.MeshError, match="empty.stl': is empty"):
        sg.load_mesh(empty)
    junk = tmp_path / "junk.ply"
    junk.write_bytes(b"ply\nformat nonsense\n\x00\x01garbage")
    with pytest.raises(sg.MeshError, match="junk.ply': cannot be read"):
        sg.load_mesh(junk)
    with pytest.raises(sg.MeshError, match="nowhere.stl': no such file"):
        sg.load_mesh(tmp_path / "nowhere.stl")
    with pytest.raises(sg.MeshError, match="unknown format '.xyz'"):
        (tmp_path / "a.xyz").write_text("1 2 3")
        sg.load_mesh(tmp_path / "a.xyz")
    nan = tmp_path / "nan.obj"
    nan.write_text("v 0 0 0\nv 1 0 0\nv 0 nan 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n")
    with pytest.raises(sg.MeshError, match="nan.obj': 1 vertices are not finite"):
        sg.load_mesh(nan)


def test_mesh_under_booleans_offsets_and_blends(renderer):
    part = sg.from_mesh(bumpy(3))
    scenes = [part - sg.cylinder(0.3, 3), part.round(0.05), part.shell(0.05) & sg.box((3, 3, 0.5)),
              sg.union(part, sg.sphere(0.5).translate((1.1, 0, 0)), k=0.2),
              part.scale(0.5).rotate(30, (1, 0, 0)).translate((0.2, 0, 0))]
    rng = np.random.default_rng(2)
    pts = rng.uniform(-1.5, 1.5, (8000, 3))
    for s in scenes:
        gpu = sg.evaluate(s, pts, renderer=renderer)
        assert np.abs(gpu - s.distance(pts)).max() < 1e-5, s.label()


@pytest.mark.slow
def test_drilled_mesh_exports_watertight_with_the_twins_volume(tmp_path):
    part = sg.from_mesh(trimesh.creation.icosphere(4))
    drilled = part - sg.cylinder(0.3, 3)
    drilled.save(str(tmp_path / "drilled.stl"), step=0.02)
    tm = trimesh.load(tmp_path / "drilled.stl")
    assert tm.is_watertight
    # the twin's volume: the cells of an 80^3 lattice over [-1, 1]^3 whose centres it puts inside
    c = (np.arange(80) + 0.5) / 40 - 1
    pts = np.stack(np.meshgrid(c, c, c, indexing="ij"), axis=-1).reshape(-1, 3)
    twin = 8.0 * np.mean(drilled.distance(pts) < 0)
    assert abs(tm.volume - twin) <= 0.005 * twin


def test_compiles_for_every_target_and_pickles(renderer):
    part = sg.from_mesh(torus(), name="torus")
    for dialect in ("desktop", "webgl2"):
        src = generate(part.color(0.8, 0.2, 0.1), Settings(), dialect=dialect)
        renderer.programs.get(src)
    assert "sdMeshBVH" in sg.compile(part)
    copy = pickle.loads(pickle.dumps(part))
    assert sg.compile(copy) == sg.compile(part) and copy.label() == "mesh(torus, 2304 triangles)"
    assert sg.compile(sg.from_dict(part.to_dict())) == sg.compile(part)  # saved inline (test_scene_io_mesh.py)


def ray_mesh(o: np.ndarray, d: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """float64 ray-triangle intersection (Moller-Trumbore), every ray against every triangle:
    the nearest t >= 0 of each ray (unit directions), inf on a miss."""
    a, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    out = np.full(len(o), np.inf)
    for s in range(0, len(o), 256):
        oo, dd = o[s:s + 256, None], d[s:s + 256, None]
        pv = np.cross(dd, e2)
        det = (e1 * pv).sum(-1)
        inv = 1.0 / np.where(np.abs(det) > 1e-300, det, np.nan)
        tv = oo - a
        u = (tv * pv).sum(-1) * inv
        qv = np.cross(tv, e1)
        v = (dd * qv).sum(-1) * inv
        t = (e2 * qv).sum(-1) * inv
        ok = (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= 0)
        out[s:s + 256] = np.where(ok, t, np.inf).min(axis=1)
    return out


TURN = trimesh.transformations.rotation_matrix(0.7, (1, 2, 0.5))


@pytest.mark.parametrize("moved, free_way", [(False, True), (False, False), (True, True)])
def test_render_hits_the_mesh_where_float64_rays_do(renderer, moved, free_way):
    # with the free way the march steps to where the ray meets the triangles (a cast through
    # the hierarchy); moved: the mesh node under a rotation and a translation (the way is cast
    # in the mesh's frame)
    m = torus()
    node = sg.from_mesh(m)
    if moved:
        node = node.rotate(np.degrees(0.7), (1, 2, 0.5)).translate((0.3, -0.2, 0.1))
        m = m.copy().apply_transform(TURN)
        m.apply_translation((0.3, -0.2, 0.1))
    res = renderer.render(node, size=(64, 48), outputs=("color", "depth", "steps"), shadows=False, ao=False,
                          free_way=free_way)
    assert ("gFree = meshRayFree(" in res.source.text) == free_way
    o, d = res.camera.rays(64, 48)
    o, d = np.broadcast_to(o, d.shape).reshape(-1, 3), d.reshape(-1, 3)
    ref = ray_mesh(o, d / np.linalg.norm(d, axis=-1, keepdims=True), np.asarray(m.triangles))
    got = res.depth.reshape(-1).astype(np.float64)
    hit = np.isfinite(ref)
    assert hit.mean() > 0.05 and np.mean(np.isfinite(got) == hit) >= 0.99  # silhouette pixels may differ
    both = hit & np.isfinite(got)
    off = np.abs(got[both] - ref[both]) / res.camera.footprint(ref[both], 48)
    assert np.mean(off <= 0.01) >= 0.99, np.quantile(off, [0.5, 0.99])
    if free_way:  # the cast is the march: one map() call, which walks nothing
        assert np.all(res.steps[both.reshape(48, 64)] == 1)
        assert "(gCastOnly ? 0.0 : sdMeshBVH(" in res.source.text
        plain = renderer.render(node, size=(64, 48), outputs=("steps",), shadows=False, ao=False, free_way=False)
        assert plain.steps[both.reshape(48, 64)].mean() > 3


def test_a_lone_mesh_has_a_coarse_pass_only_for_its_lit_ground(renderer):
    # its rays are cast, so cones walking the mesh buy them nothing; on a shadowed ground the
    # pass's proof that tiles of ground need no shadow or AO does pay
    node = sg.from_mesh(torus()).translate((0.1, 0, 0))
    assert renderer.coarse_starts(node, size=(64, 48)) is None
    assert renderer.coarse_starts(node, size=(64, 48), ground=True, shadows=False, ao=False) is None
    assert renderer.coarse_starts(node, size=(64, 48), ground=True) is not None
    assert renderer.coarse_starts(node, size=(64, 48), free_way=False) is not None  # marched: cones pay
    assert renderer.coarse_starts(node - sg.sphere(0.2), size=(64, 48)) is not None


@pytest.mark.parametrize("moved", [False, True])
def test_normals_of_a_lone_mesh_are_its_fields_gradient(renderer, moved):
    # one map() call at the hit: the closest triangle's normal, turned into the world, against
    # the central differences the renderer takes for any other scene (the mesh beside a far speck)
    node = sg.from_mesh(torus())
    if moved:
        node = node.rotate(40, (1, 2, 0.5)).translate((0.3, -0.2, 0.1))
    cam = sg.OrbitCamera.framing(*node.bounds, aspect=4 / 3)
    kw = dict(outputs=("normal", "depth"), shadows=False, ao=False)
    own = renderer.render(node, cam, (96, 72), **kw)
    diff = renderer.render(node | sg.sphere(0.01).translate((50, 0, 0)), cam, (96, 72), **kw)
    assert "#define MESH_NORMAL" in own.source.text and "#define MESH_NORMAL" not in diff.source.text
    hit = np.isfinite(own.depth) & np.isfinite(diff.depth)
    cos = (own.normal[hit][:, :3] * diff.normal[hit][:, :3]).sum(-1)
    angle = np.degrees(np.arccos(np.clip(cos, -1, 1)))
    assert hit.sum() > 500 and np.mean(angle < 1.0) > 0.97 and angle.max() < 20


def test_hard_shadows_of_a_lone_mesh_cast_once_and_look_the_same(renderer):
    ball = sg.from_mesh(bumpy(3))
    scene = sg.union(ball, ball.translate((1.4, 0.2, 0.3)))  # a union of meshes: no cast
    kw = dict(size=(96, 72), shadows="hard", ao=False, ground=True)
    cast = renderer.render(ball, **kw)
    plain = renderer.render(ball, free_way=False, **kw)
    assert "#define RAY_FREE_HIT" in cast.source.text and "#define RAY_FREE" not in plain.source.text
    assert "#define RAY_FREE_HIT" not in renderer.render(scene, **kw).source.text
    differ = np.abs(cast.color.astype(int) - plain.color.astype(int)).max(axis=-1) > 8
    assert differ.mean() <= 0.002
    grid = sg.union(*[sg.sphere(0.1).translate((i % 8 * 0.3, 0, i // 8 * 0.3)) for i in range(64)])
    src = sg.compile(grid)  # a grid's way is a bound: its hard shadows march as before
    assert "#define RAY_FREE" in src and "#define RAY_FREE_HIT" not in src


def test_only_the_scenes_own_mesh_casts_the_free_way():
    part = sg.from_mesh(torus())
    assert "gFree = meshRayFree(" in sg.compile(part.translate((1, 0, 0)).color("red"))
    for scene in (part - sg.sphere(0.3), part.scale(2), sg.union(part, sg.sphere(0.1))):
        assert "gFree = meshRayFree(" not in sg.compile(scene)
    assert "gFree = meshRayFree(" not in sg.compile(part, method="newton")


def test_the_twin_names_the_missing_extra(monkeypatch):
    from sdfgl import extras
    from sdfgl.extras import MissingExtraError
    part = sg.from_mesh(torus())
    monkeypatch.setattr(extras, "installed", lambda module: module != "igl")
    with pytest.raises(MissingExtraError, match=r"needs igl.*pip install 'sdfgl\[meshin\]'"):
        part.distance((0, 0, 0))


def test_costly_pixels_keep_the_field(renderer):
    # llvmpipe ends a shader invocation's loops after 65535 rounds in all: nine AA samples of
    # rays grazing the base's edges must not run the mesh's walk out of them (dark speckles;
    # 129 pixels with a loop over each leaf's triangles)
    base = sg.rounded_box((2.6, 0.3, 2.6), 0.1).translate((0, -1.0, 0))
    cam = sg.OrbitCamera(distance=5.2, yaw=35, pitch=25, target=(0, -0.2, 0))
    st = {"aa": 3, "shadows": False, "ao": False, "analytic": False}
    mesh = renderer.render(sg.from_mesh(trimesh.creation.icosphere(4)) | base, cam, (120, 80), **st).color
    ball = renderer.render(sg.sphere(1) | base, cam, (120, 80), **st).color
    assert np.count_nonzero(np.abs(mesh.astype(int) - ball).sum(-1) > 40) <= 10
