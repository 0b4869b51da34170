"""Costly children of hard unions and differences are evaluated only where their box says
they can change the result (sdfgl.compiler.guards): the field, colours and images are those
of the code without the test."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.compiler.generate import generate
from sdfgl.evaluate import evaluate_channel
from sdfgl.nodes import shapes2d
from sdfgl.settings import Settings

pytest.importorskip("fontTools")


def label() -> sg.Node:
    return sg.extrude(sg.text("sdfgl", size=0.3, align="center"), 0.05)


def engraved() -> sg.Node:
    return sg.rounded_box((1.2, 0.5, 0.1), 0.02) - label().translate((0, -0.1, 0.05))


def long_engraved() -> sg.Node:
    """A text long enough for the glyph grid (sdfgl.compiler.data.textgrid), engraved."""
    words = sg.text("abcdefghij klmnopqrst\nuvwxyz ABCDEFGHIJ\nKLMNOPQRSTUV 0123456789", size=0.08)
    lo, hi = words.bounds2
    plate = sg.box((float(hi[0] - lo[0]) + 0.2, float(hi[1] - lo[1]) + 0.2, 0.1)).translate(
        (float(lo[0] + hi[0]) / 2, float(lo[1] + hi[1]) / 2, 0))
    return plate - sg.extrude(words, 0.04).translate((0, 0, 0.05))


def raised() -> sg.Node:
    """An engraved plate and raised, turned, moved and rounded text above it (the cap passes
    the 2D moves and adds the rounding's radius)."""
    words = sg.text("Hello, wörld!", size=0.3, align="center").rotate(8).translate((0.05, 0)).round(0.01)
    return engraved() | sg.extrude(words, 0.12).color(0.9, 0.6, 0.2).translate((0, 0.45, 0))


def blended() -> sg.Node:
    """Smooth unions and a smooth difference with a costly child (its box test adds the blend's
    support: beyond it the smooth minimum is the minimum)."""
    words = sg.extrude(sg.text("Blend", size=0.3, align="center"), 0.1)
    base = sg.rounded_box((1.4, 0.2, 0.6), 0.03).color("#888888")
    return (sg.union(base, words.translate((0, 0.15, 0)).color("orange"), k=0.04)
            | sg.difference(sg.box((1.4, 0.3, 0.2)).translate((0, 0, 0.6)),
                            words.translate((0, -0.1, 0.7)), k=0.02, blend="circular"))


def beside() -> sg.Node:
    """A union whose costly child (red text, a 40-gon) is the nearer one in places."""
    a = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    gon = sg.extrude(sg.polygon(np.stack([0.3 * np.cos(a), 0.3 * np.sin(a)], 1)), 0.2)
    return (sg.sphere(0.4).color("#3366cc") | label().translate((0.5, 0.2, 0)).color("red")
            | gon.translate((-0.6, 0, 0.3)).color("green"))


def map_code(scene: sg.Node) -> str:
    text = generate(scene, Settings(shadows=False, ao=False), np.zeros(3)).text
    return text[text.index("float map(vec3 p)"):text.index("vec3 mapColor")]


def points(scene: sg.Node, n: int = 20000) -> np.ndarray:
    """Points all over the scene's box and beyond it, and points close to its surface."""
    lo, hi = scene.bounds
    rng = np.random.default_rng(1)
    wide = rng.uniform(lo - 0.3, hi + 0.3, (n, 3))
    d = scene.distance(wide)
    near = wide[np.abs(d) < 0.05]
    return np.concatenate([wide, near])


def unguarded(make, monkeypatch):  # noqa: ANN001, ANN201
    """The same scene, built anew and compiled with the box test switched off."""
    monkeypatch.setattr(type(sg.text("a")), "costly", False)
    monkeypatch.setattr(shapes2d, "COSTLY_VERTICES", 10 ** 9)
    return make()


def test_only_costly_children_get_a_box_test():
    assert map_code(engraved()).count("opBoxGap(") == 1
    assert "sd2TextGrid(" in map_code(long_engraved()) and map_code(long_engraved()).count("opBoxGap(") == 1
    assert map_code(beside()).count("opBoxGap(") == 2  # the text and the 40-gon, not the sphere
    assert map_code(raised()).count("opBoxGap(") == 2 and map_code(raised()).count("sd2Text(") == 2
    assert map_code(blended()).count("opBoxGap(") == 3  # the text twice, and the difference holding one
    cheap = sg.sphere(1) | sg.box(0.5).translate((1, 0, 0)) | sg.torus(0.5, 0.1)
    assert "opBoxGap(" not in map_code(cheap)
    # a big subtree of plain primitives has no loop for the test to skip: no test either
    group = sg.union(*[sg.box(0.1).rotate(9 * i, (0, 1, 0)).translate((0.2 * i, 0, 0)) for i in range(12)])
    assert "opBoxGap(" not in map_code(sg.sphere(0.5) | group.translate((3, 0, 0)))
    assert "opBoxGap(" not in map_code(sg.sphere(1) & label())  # an intersection needs every value


@pytest.mark.parametrize("make", [engraved, long_engraved, raised, blended, beside])
def test_the_field_and_colours_are_those_without_the_test(make, monkeypatch):
    scene = make()
    pts = points(scene)
    got = sg.evaluate(scene, pts)
    got_color = evaluate_channel(scene, pts)
    twin = scene.distance(pts)
    assert np.abs(got - twin).max() < 2e-5
    plain = unguarded(make, monkeypatch)
    assert "opBoxGap(" not in map_code(plain)
    assert np.abs(got - sg.evaluate(plain, pts)).max() < 1e-6
    ref_color = evaluate_channel(plain, pts)
    assert np.abs(got_color[:, :3] - ref_color[:, :3]).max() < 1e-5  # a wrong skip picks another part's colour


def test_images_are_those_without_the_test(monkeypatch):
    cam = sg.OrbitCamera(distance=2.2, yaw=20, pitch=25)
    a = sg.render(engraved(), cam, (160, 120)).color
    b = sg.render(unguarded(engraved, monkeypatch), cam, (160, 120)).color
    assert np.abs(a.astype(int) - b.astype(int)).max() <= 1


@pytest.mark.parametrize("kind", ["text", "polygon"])
def test_a_capped_2d_field_is_at_least_the_distance_to_its_bounds(kind):
    """The box test's premise for the 2D shapes whose grid caps their field (a long text, a
    polygon of many vertices): outside their bounds the field is at least the distance to them."""
    if kind == "text":
        shape = sg.text("abcdefghij klmnopqrst\nuvwxyz ABCDEFGHIJ\nKLMNOPQRSTUV 0123456789", size=0.08)
        assert shape.grid is not None
    else:
        a = np.linspace(0, 2 * np.pi, 2000, endpoint=False)
        r = 1 + 0.3 * np.cos(12 * a)
        shape = sg.polygon(np.stack([r * np.cos(a), r * np.sin(a)], 1))
        assert shape.grid is not None
    lo, hi = shape.bounds2
    pts = np.random.default_rng(2).uniform(lo - 0.3 * (hi - lo), hi + 0.3 * (hi - lo), (50000, 2))
    outside = np.linalg.norm(np.maximum(np.maximum(lo - pts, pts - hi), 0.0), axis=1)
    d = shape.distance2(pts)
    assert np.all(d[outside > 0] >= outside[outside > 0] - 1e-12)
