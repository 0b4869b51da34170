"""The coarse pass: the depth each tile of pixels starts marching from lies before every hit
of every ray in the tile, a tile proven empty has no hits, and the image does not change."""
import moderngl
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.errors import ParameterError
from sdfgl.hardcases import case
from sdfgl.reference import trace

SIZE = (64, 48)
EMPTY_START = 1e37  # a start at or past this: the tile's cone crossed the scene without meeting it
LIT_START = 1.5e38  # ... from this on: its ground is lit and unoccluded
SKY_START = 2.5e38  # ... from this on: no ray of the tile meets the ground


def tile_of(starts: np.ndarray, size: tuple[int, int], tile: int, sub: int) -> np.ndarray:
    """Each ray of an image ``sub`` times as fine as ``size`` (row 0 on top): its tile's start."""
    w, h = size
    rows = np.arange(h * sub) // sub           # the pixel's row, from the top
    gl_rows = (h - 1 - rows) // tile             # its tile's row, from the bottom (GL's)
    cols = (np.arange(w * sub) // sub) // tile
    return starts[starts.shape[0] - 1 - gl_rows][:, cols]


@pytest.mark.parametrize("name", ["box_frame", "thin_shell", "horizon_plane", "grazing_face_0.5", "small_spheres",
                                  "five_spheres", "tunnel", "small_beside_big_1e4", "twist_720"])
@pytest.mark.parametrize("tile", [4, 8])
def test_starts_lie_before_every_hit(renderer, name, tile):
    """No ray through any part of a tile's pixels (the reference at twice the resolution) meets
    a surface before the tile's start; thin bars, a shell 1e-3 thick and planes seen at a
    grazing angle included."""
    c = case(name)
    scene, cam = c.build()
    settings = {**c.settings, "analytic": False, "coarse": tile}
    starts = renderer.coarse_starts(scene, cam, SIZE, **settings)
    assert starts is not None and starts.shape == (-(-SIZE[1] // tile), -(-SIZE[0] // tile))
    ref = trace(scene, cam, (2 * SIZE[0], 2 * SIZE[1]), max_dist=c.max_dist)
    start = tile_of(starts, SIZE, tile, 2).astype(np.float64)
    hit = ref.hit & ~ref.undecided
    assert hit.any()
    late = hit & (start > ref.t * (1 + 1e-6))
    assert not late.any(), f"{late.sum()} rays hit before their tile's start, by up to " \
                           f"{np.max((start - ref.t)[late]):.3g}"
    assert np.all(start[hit & (start >= EMPTY_START)] < 0), "a tile proven empty has hits"
    assert (starts[starts < EMPTY_START] > 0).any(), "the pass proves nothing: every start at the eye"


def test_orthographic_starts(renderer):
    """Parallel rays: the cone is a cylinder as wide as the tile."""
    scene = sg.box_frame(2.0, 0.02) | sg.sphere(0.3)
    cam = sg.OrbitCamera(distance=6, yaw=30, pitch=25, projection="orthographic", ortho_height=3.0)
    starts = renderer.coarse_starts(scene, cam, SIZE, coarse=4)
    ref = trace(scene, cam, (2 * SIZE[0], 2 * SIZE[1]))
    start = tile_of(starts, SIZE, 4, 2)
    hit = ref.hit & ~ref.undecided
    assert hit.any() and (starts >= EMPTY_START).any() and (starts[starts < EMPTY_START] > 3).any()
    assert not (hit & (start > ref.t * (1 + 1e-6))).any()


def low_scene() -> tuple[sg.Node, sg.Camera, dict]:
    """Objects on a ground plane (a plane of the scene, marched), seen low."""
    parts = [sg.box(0.4).translate((x, 0.4, z)) for x in (-3, 0, 3) for z in (-3, 0, 3)]
    scene = sg.union(sg.plane(), *parts, sg.sphere(0.6).translate((1.5, 0.6, 1.5)),
                     sg.box_frame(1.0, 0.02).translate((-1.5, 0.5, 1.5)))
    return scene, sg.OrbitCamera(target=(0, 0.3, 0), distance=8, yaw=20, pitch=4), {}


@pytest.mark.parametrize("build", [low_scene, lambda: (demo_scene(), demo_camera(), {"ground": True})],
                         ids=["low", "demo"])
def test_image_unchanged(renderer, build):
    """With and without the pass, under 0.1% of the pixels differ by more than 8/255, the pass
    saves map() calls, and the hits agree."""
    scene, cam, extra = build()
    look = dict(outputs=("color", "depth", "steps"), **extra)
    off = renderer.render(scene, cam, (160, 90), coarse=False, **look)
    on = renderer.render(scene, cam, (160, 90), **look)
    diff = np.abs(on.color.astype(int) - off.color.astype(int)).max(axis=-1)
    assert np.mean(diff > 8) < 1e-3
    assert on.steps.sum() < 0.9 * off.steps.sum()
    both = np.isfinite(on.depth) & np.isfinite(off.depth)
    assert np.mean(np.isfinite(on.depth) != np.isfinite(off.depth)) < 1e-3
    assert np.median(np.abs(on.depth[both] - off.depth[both]) / on.depth[both]) < 1e-4


def test_shader_without_the_pass():
    """coarse=False: the image's shader has no code of the pass (its hook in the primary trace
    is under #ifdef COARSE_TILE, like the raster meshes'); where a scene cannot use it (a
    closed form, an implicit field, Newton marching, WebGL) it is absent too."""
    scene = sg.box(1) | sg.sphere(0.7).translate((1, 0, 0))
    words = ("#define COARSE_TILE", "float coarseStart()", "uniform sampler2D uCoarseStart", "#define LIPSCHITZ")
    on = sg.compile(scene)
    assert all(w in on for w in words)
    for src in (sg.compile(scene, coarse=False), sg.compile(sg.sphere(1)),
                sg.compile(sg.product(sg.sphere(1), sg.box(1))),
                sg.compile(scene, method="newton")):
        assert not any(w in src for w in words)
    from sdfgl.compiler.generate import generate
    from sdfgl.settings import Settings
    assert not any(w in generate(scene, Settings(), dialect="webgl2").text for w in words)
    assert generate(scene, Settings(coarse=4)).coarse_tile == 4


def test_coarse_setting():
    from sdfgl.settings import Settings
    assert Settings().coarse == 8 and Settings(coarse=True).coarse == 8 and Settings(coarse=16).coarse == 16
    for bad in (3, 8.0, "8", None):
        with pytest.raises(ParameterError, match="coarse"):
            Settings(coarse=bad)


@pytest.mark.parametrize("tile", [4, 16])
@pytest.mark.parametrize("ground", [False, True])
def test_each_tile_drawn_once_by_its_kind(renderer, tile, ground):
    """After the pass the image is drawn tile by tile, each tile by the program of its kind: the
    image's on the open tiles, without the march on the tiles proven empty, without the ground's
    shadows and AO where the pass proved them lit and unoccluded, without the ground where none
    of their rays meets it (partial tiles at the edges included); together they give render()'s
    image, and that is the image without the pass."""
    from sdfgl.compiler.generate import generate
    from sdfgl.gl.coarse_pass import EMPTY, LIT, OPEN, SKY, TILES_VERTEX, tile_sources
    from sdfgl.render import bind_image, coarse_source, draw_image, image_draws, shader_origin
    from sdfgl.settings import Settings
    side = 0.4 + 0.01 * tile + 0.001 * ground  # a scene of its own: no program of it is cached yet
    scene = sg.union(*[sg.box(side).translate((x, 0.4, z)) for x in (-1.2, 0, 1.2) for z in (-1.2, 0, 1.2)])
    cam = sg.OrbitCamera(target=(0, 0.3, 0), distance=9, yaw=20, pitch=12)
    size = (101, 67)  # neither side a multiple of a tile
    st = Settings(coarse=tile, ground=ground).resolved(scene.exactness)
    origin = shader_origin(scene, cam.eye)
    source = generate(scene, st, origin, projection=cam.projection)
    assert [k for _, k in tile_sources(source)] == ([OPEN, EMPTY, LIT, SKY] if ground else [OPEN, SKY])
    assert "#define EMPTY_TILES" not in sg.compile(scene, coarse=tile)
    coarse = coarse_source(scene, source, st, origin, cam.projection)
    starts = renderer.coarse_starts(scene, cam, size, coarse=tile, ground=ground)
    kind = np.select([starts < EMPTY_START, starts < LIT_START, starts < SKY_START], [OPEN, EMPTY, LIT], SKY)
    kind = np.repeat(np.repeat(kind, tile, axis=0), tile, axis=1)[-size[1]:, :size[0]]
    assert np.any(kind == OPEN) and np.any(kind == SKY)
    assert np.any(kind == EMPTY) == ground and np.any(kind == LIT) == ground

    # the first frame links the image's program alone and draws every pixel with it; the next, the rest
    first = renderer.render(scene, cam, size, coarse=tile, ground=ground).color
    assert not any(renderer.programs.cached(src, TILES_VERTEX) for src, k in tile_sources(source) if k != OPEN)
    full = renderer.render(scene, cam, size, coarse=tile, ground=ground).color
    assert all(renderer.programs.cached(src, TILES_VERTEX) for src, _ in tile_sources(source))
    assert np.array_equal(first, full)

    def draw(kinds, added=False):
        """The image drawn by the programs of ``kinds``; ``added``: into a float target with
        additive blending, as the viewer accumulates (a pixel drawn twice would count twice)."""
        ctx = renderer.ctx
        tiles = renderer.coarse_pass(scene, cam, size, coarse, origin)
        tex = ctx.texture(size, 4, dtype="f4" if added else "f1")
        fbo = ctx.framebuffer(color_attachments=[tex])
        try:
            draws = [d for d in image_draws(renderer.programs, source, True)[0] if d.kind in kinds]
            bind_image(draws, scene, cam, size, origin, renderer.data, starts=tiles)
            fbo.use()
            fbo.clear(0.0, 0.0, 0.0, 0.0)
            if added:
                ctx.enable(moderngl.BLEND)
                ctx.blend_func = moderngl.ONE, moderngl.ONE
            draw_image(ctx, draws, size)
            ctx.disable(moderngl.BLEND)
            if added:
                return np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32).reshape(size[1], size[0], 4)[::-1]
            return np.frombuffer(fbo.read(components=4), np.uint8).reshape(size[1], size[0], 4)[::-1]
        finally:
            fbo.release()
            tex.release()
            tiles.release()

    for k in (OPEN, EMPTY, LIT, SKY):
        assert np.array_equal(renderer.run(draw, {k})[..., 3] > 0, kind == k), k
    both = renderer.run(draw, {OPEN, EMPTY, LIT, SKY})
    assert np.array_equal(both[..., :3], full) and np.all(both[..., 3] == 255)
    assert np.all(renderer.run(draw, {OPEN, EMPTY, LIT, SKY}, True)[..., 3] == 1.0)  # each pixel once
    off = renderer.render(scene, cam, size, coarse=False, ground=ground).color
    assert np.mean(np.abs(full.astype(int) - off.astype(int)).max(axis=-1) > 8) < 1e-3
    if ground:  # the lit tiles' pixels, shaded with shadows and AO, are what they show without
        assert np.abs(full[kind == LIT].astype(int) - off[kind == LIT].astype(int)).max() <= 2


def test_tile_programs_share_the_image_data_upload(renderer):
    """The tile programs of an image with data tables (a union kept as data) read the image's
    uploaded textures: frames after the first upload nothing."""
    scene = sg.union(*[sg.sphere(0.1).translate((0.3 * i, 0.1 * (i % 3), 0.2 * (i % 5))) for i in range(60)])
    assert sg.compile(scene).count("uniform sampler") >= 1
    for _ in range(3):
        renderer.render(scene, size=(64, 48), shadows=False, ao=False)
    entries = len(renderer.data)
    for _ in range(3):
        renderer.render(scene, size=(64, 48), shadows=False, ao=False)
    assert len(renderer.data) == entries


def test_an_image_and_its_coarse_pass_share_one_data_upload():
    """The coarse pass's source is generated apart from the image's, with the same tables: it
    holds the same array, so one upload serves both; the table is freed with its sources."""
    import gc
    import weakref

    from sdfgl.render import Renderer, coarse_source, shader_origin
    from sdfgl.settings import Settings
    scene = sg.union(*[sg.sphere(0.12).translate((0.3 * i, 0.1 * (i % 4), 0.2 * (i % 5))) for i in range(70)])
    r = Renderer()
    r.render(scene, size=(64, 48), shadows=False, ao=False)
    assert len(r.data) == 1  # one upload, for the coarse pass and the image
    res = r.render(scene, size=(64, 48), shadows=False, ao=False)
    image = res.source
    table = weakref.ref(image.data[0][1])
    st = Settings.build(shadows=False, ao=False).resolved(scene.exactness)
    coarse = coarse_source(scene, image, st, shader_origin(scene, res.camera.eye))
    assert coarse is not None and coarse.data[0][1] is image.data[0][1]
    r.release()
    del r, res, image, coarse, scene
    gc.collect()
    assert table() is None  # nothing but its sources keeps it
