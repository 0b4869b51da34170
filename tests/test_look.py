"""Lights, materials, background, transparency and fog."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.look import DEFAULT_LIGHTS, MAX_LIGHTS
from sdfgl.values.colors import parse, srgb_to_linear

FLAT = dict(lights=[], ambient="black", ao=False, shadows=False)  # colour = emission exactly
CAM = sg.Camera((0, 0, 6), (0, 0, 0), fov=40)


def enc(c):
    """Linear -> the 8-bit value the shader writes (gamma 2.2)."""
    return np.round(255 * np.asarray(c) ** (1 / 2.2))


def test_default_rig_is_the_original_look_and_absent_lights_have_no_code():
    s = sg.sphere(1) - sg.box(1.2)
    assert sg.compile(s) == sg.compile(s, lights=list(DEFAULT_LIGHTS))
    none = sg.compile(s, lights=[], shadows="soft")
    assert "Visibility(" not in none and "// light 0" not in none
    both = sg.compile(s, lights=[sg.directional_light((1, 1, 0), shadow="hard"),
                                 sg.point_light((0, 3, 0), shadow="soft"), sg.directional_light((0, 1, 0), shadow=False)])
    assert "float shadowHard(" not in both  # renamed by #define, so the source names shadow()
    assert both.count("#define shadow shadowHard") == 1 and both.count("#define shadow shadowSoft") == 1
    assert "// light 2" in both and "// light 3" not in both
    unshadowed = sg.compile(s, lights=[sg.directional_light((1, 1, 0), shadow=False)], shadows="soft")
    assert "#define shadow " not in unshadowed


def test_colours_in_every_form():
    assert parse("n", "c", "#ffffff") == (1.0, 1.0, 1.0)
    assert parse("n", "c", "white") == (1.0, 1.0, 1.0)
    assert parse("n", "c", (255, 0, 0)) == (1.0, 0.0, 0.0)
    assert np.allclose(parse("n", "c", "#808080"), srgb_to_linear(np.full(3, 128 / 255)))
    assert parse("n", "c", (0.2, 0.4, 0.6)) == (0.2, 0.4, 0.6)
    assert parse("n", "c", (1, 0, 1)) == (1.0, 0.0, 1.0)  # 0/1 integers are 0..1 values
    for bad, msg in [("nocolour", "not a colour"), ((300, 0, 0), "0..255"), ((1.5, 0, 0), "0..255 integers"),
                     ((0.1, 0.2), "3 components"), ("", "not a colour")]:
        with pytest.raises(sg.ParameterError, match=msg):
            parse("n", "c", bad)
    assert sg.sphere(1).color("steelblue").rgb == parse("x", "c", "steelblue")
    with pytest.raises(sg.ParameterError, match="color: parameter 'color' is not a colour"):
        sg.sphere(1).color("bluish")


def test_material_validation_names_the_parameter():
    with pytest.raises(sg.ParameterError, match="'roughness' or 'shininess', not both"):
        sg.sphere(1).material(roughness=0.5, shininess=10)
    with pytest.raises(sg.ParameterError, match="material: parameter 'metallic' must lie in"):
        sg.sphere(1).material(metallic=2)
    with pytest.raises(sg.ParameterError, match="roughness"):
        sg.sphere(1).material(roughness=0)
    with pytest.raises(sg.ParameterError, match="at least one"):
        sg.sphere(1).material()
    m = sg.sphere(1).material("red", roughness=1.0)
    assert m.fields["shininess"] == 1.0 and m.fields["albedo"] == (1.0, 0.0, 0.0)


def _pixel(res, x, y):
    return res.color[y, x, :3].astype(float)


def test_materials_carry_through_booleans_and_blend_smoothly():
    red, blue = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)
    a = sg.sphere(1).translate((-0.7, 0, 0)).material((0, 0, 0), emission=red)
    b = sg.sphere(1).translate((0.7, 0, 0)).material((0, 0, 0), emission=blue)
    w, h = 96, 64
    res = sg.render(sg.union(a, b, k=0.6), CAM, (w, h), background="black", **FLAT)
    row = res.color[h // 2, :, :3].astype(float)
    hit = np.flatnonzero(row.sum(axis=1) > 0)
    assert np.allclose(row[hit[0] + 2], enc(red), atol=1)
    assert np.allclose(row[hit[-1] - 2], enc(blue), atol=1)
    # across the seam red falls and blue rises monotonically: no jump
    r, bl = row[hit[2]:hit[-2], 0], row[hit[2]:hit[-2], 2]
    assert np.all(np.diff(r) <= 1) and np.all(np.diff(bl) >= -1)
    assert np.max(np.abs(np.diff(r))) < 60
    mid = row[w // 2]
    assert 0 < mid[0] < 255 and 0 < mid[2] < 255
    # a difference shows the cutter's material on the cut face, like colour
    cut = sg.sphere(1).material((0, 0, 0), emission=red) - sg.box(1.2).translate((0, 0, 1.0)).material(
        (0, 0, 0), emission=blue)
    res = sg.render(cut, CAM, (w, h), **FLAT)
    assert np.allclose(_pixel(res, w // 2, h // 2), enc(blue), atol=1)
    # outer fields fill what inner nodes leave out; innermost wins
    nested = sg.sphere(1).material(emission=(0.0, 1.0, 0.0)).material((0, 0, 0), emission=red)
    res = sg.render(nested, CAM, (w, h), **FLAT)
    assert np.allclose(_pixel(res, w // 2, h // 2), enc((0, 1, 0)), atol=1)


def test_surface_fields_change_the_highlight():
    light = [sg.directional_light((0, 0, 1), shadow=False)]
    base = dict(lights=light, ambient="black", ao=False)
    matte = sg.render(sg.sphere(1).material("gray", specular=0.0), CAM, (64, 64), **base).color.astype(int)
    shiny = sg.render(sg.sphere(1).material("gray", specular=1.0, shininess=50), CAM, (64, 64), **base).color.astype(int)
    assert shiny[32, 32].sum() > matte[32, 32].sum() + 30        # the highlight faces the camera
    assert abs(int(shiny[32, 55].sum()) - int(matte[32, 55].sum())) <= 6   # away from it, little changes
    gold = sg.render(sg.sphere(1).material("gold", metallic=1.0, shininess=50), CAM, (64, 64), **base).color
    assert gold[32, 32, 0] > gold[32, 32, 2] + 40                 # a metal's highlight takes its colour
    # with no light at all, a metal shows its surroundings (the background along the mirror ray)
    dark = dict(lights=[], ambient="black", ao=False)
    metal = sg.sphere(1).material("white", metallic=1.0)
    on_white = sg.render(metal, CAM, (32, 32), background="white", **dark).color[16, 16].astype(int)
    on_black = sg.render(metal, CAM, (32, 32), background="black", **dark).color[16, 16].astype(int)
    assert on_white.min() > 200 and on_black.max() < 10


def test_lights_colour_intensity_and_falloff():
    s = sg.plane((0, 0, 1))
    def lum(**kw):
        return sg.render(s, CAM, (32, 32), ambient="black", ao=False, **kw).color[16, 16].astype(int)
    red = lum(lights=[sg.directional_light((0, 0, 1), "red", shadow=False)])
    assert red[0] > 200 and red[1] == 0 and red[2] == 0
    dim = lum(lights=[sg.directional_light((0, 0, 1), "white", 0.2, shadow=False)])
    bright = lum(lights=[sg.directional_light((0, 0, 1), "white", 0.8, shadow=False)])
    assert bright[1] > dim[1] + 50
    near = lum(lights=[sg.point_light((0, 0, 1), "white", 1.0, range=1.0, shadow=False)])
    far = lum(lights=[sg.point_light((0, 0, 3), "white", 1.0, range=1.0, shadow=False)])
    assert near[1] > far[1] + 50
    with pytest.raises(sg.ParameterError, match=f"at most {MAX_LIGHTS}"):
        sg.render(s, CAM, (8, 8), lights=[sg.directional_light()] * (MAX_LIGHTS + 1))
    with pytest.raises(sg.ParameterError, match="lights\\[0\\]"):
        sg.render(s, CAM, (8, 8), lights=["sun"])
    with pytest.raises(sg.ParameterError, match="point_light: parameter 'shadow'"):
        sg.point_light((0, 1, 0), shadow="blurry")


def test_per_light_shadow_kinds():
    """A sphere above a plane: a shadowed light darkens the plane under it, an unshadowed one does not."""
    s = sg.sphere(0.5).translate((0, 0, 1)) | sg.plane((0, 0, 1))
    cam = sg.Camera((0, -0.01, 6), (0, 0, 0), fov=30)
    def centre(shadow):
        r = sg.render(s, cam, (48, 48), ambient="black", ao=False,
                      lights=[sg.directional_light((1, 0, 1), shadow=shadow)])
        return r.color[24, 8].astype(int)   # the plane beside the sphere, in its shadow
    hard, soft, lit = centre("hard"), centre("soft"), centre(False)
    assert lit.sum() > hard.sum() + 100 and lit.sum() > soft.sum() + 100


def test_background_colour_gradient_and_fog():
    s = sg.sphere(0.2)
    flat = sg.render(s, CAM, (32, 32), background="#ff0000")
    assert tuple(flat.color[0, 0]) == (255, 0, 0)
    grad = sg.render(s, CAM, (32, 64), background=("white", "black"))
    assert grad.color[0, 0, 0] > 245 and grad.color[-1, 0, 0] < 40
    assert np.all(np.diff(grad.color[:, 0, 0].astype(int)) <= 0)
    with pytest.raises(sg.ParameterError, match="background"):
        sg.render(s, CAM, (8, 8), background="sky-ish")
    with pytest.raises(sg.ParameterError, match="fog"):
        sg.render(s, CAM, (8, 8), fog=-1)
    # fog: the farther of two equal spheres is closer to the background colour
    two = sg.sphere(0.5).translate((-1, 0, 2)) | sg.sphere(0.5).translate((1, 0, -6))
    cam = sg.Camera((0, 0, 8), (0, 0, 0), fov=50)
    r = sg.render(two, cam, (96, 48), background="white", fog=10.0, **FLAT, outputs=("color", "depth"))
    d = np.where(np.isfinite(r.depth), r.depth, np.nan)
    iy, ix = np.unravel_index(np.nanargmin(d), d.shape)
    jy, jx = np.unravel_index(np.nanargmax(d), d.shape)
    assert d[jy, jx] > d[iy, ix] + 5
    near, far = r.color[iy, ix].astype(int), r.color[jy, jx].astype(int)
    assert far.sum() > near.sum() + 100 and near.sum() < 600


def test_transparent_png_has_no_halo(tmp_path):
    """Edge pixels keep the surface's colour (alpha carries coverage), so compositing over
    white and over black gives no fringe of the render's background."""
    c = (0.2, 0.6, 0.3)
    s = sg.sphere(1).material((0, 0, 0), emission=c)
    res = sg.render(s, CAM, (64, 64), aa=3, alpha=True, background="magenta", **FLAT)
    rgba = res.color.astype(float)
    a = rgba[..., 3] / 255
    edge = (a > 0.05) & (a < 0.95)
    assert edge.sum() > 20
    assert np.allclose(rgba[edge][:, :3], enc(c), atol=1)       # straight colour: no magenta, no darkening
    assert np.all(rgba[a == 0][:, :3] == 0)
    for page in (0.0, 255.0):
        comp = rgba[..., :3] * a[..., None] + page * (1 - a[..., None])
        lo, hi = np.minimum(enc(c), page) - 1, np.maximum(enc(c), page) + 1
        assert np.all((comp[edge] >= lo) & (comp[edge] <= hi))
    # the demo scene: the background setting does not leak into any pixel
    one = sg.render(demo_scene(), demo_camera(), (80, 60), aa=2, alpha=True, background="white")
    two = sg.render(demo_scene(), demo_camera(), (80, 60), aa=2, alpha=True, background="black")
    assert np.array_equal(one.color, two.color)
    alpha = one.color[..., 3]
    assert ((alpha > 0) & (alpha < 255)).sum() > 30 and (alpha == 0).sum() > 1000
    p = one.save(tmp_path / "demo.png")
    from PIL import Image
    assert Image.open(p).mode == "RGBA"
