"""2D modelling: booleans, blends, transforms, rounding, onion, new shapes, slices, and
extrusion with taper and twist (the GLSL/twin parity and slopes are in test_parity)."""
import math

import numpy as np
import pytest

import sdfgl as sg

from .nodes_zoo import all_nodes


def grid2(n=201, r=2.0):
    x = np.linspace(-r, r, n)
    return np.stack(np.meshgrid(x, x), axis=-1).reshape(-1, 2)


def test_circle_minus_rectangle_works_and_renders():
    s = sg.circle(1) - sg.rectangle(1)
    q = grid2()
    k = np.abs(q) - 0.5
    box = np.linalg.norm(np.maximum(k, 0), axis=1) + np.minimum(k.max(axis=1), 0)
    want = np.maximum(np.hypot(q[:, 0], q[:, 1]) - 1, -box)
    assert np.allclose(s.distance2(q), want)
    res = sg.render(sg.extrude(s, 0.2), sg.Camera((0, 0, 5), fov=40), (48, 48), outputs=("color", "depth"))
    assert not np.isfinite(res.depth[24, 24]) and np.isfinite(res.depth[24, 12])  # the hole and the ring
    assert isinstance(sg.circle(1) | sg.rectangle(1), sg.Shape2D)
    assert isinstance(sg.union(sg.circle(1), sg.rectangle(1), k=0.2), sg.Shape2D)
    with pytest.raises(sg.ParameterError, match="2D shapes"):
        sg.circle(1) | sg.sphere(1)
    with pytest.raises(sg.ParameterError, match="operand 1 must be a 2D shape|must be an sdfgl node"):
        sg.union(sg.circle(1), sg.sphere(1))


def test_smooth_blend_matches_3d_blend_on_the_plane():
    a, b = sg.circle(0.6).translate((-0.4, 0)), sg.circle(0.5).translate((0.4, 0.1))
    a3, b3 = sg.sphere(0.6).translate((-0.4, 0, 0)), sg.sphere(0.5).translate((0.4, 0.1, 0))
    q = grid2(61)
    p = np.concatenate([q, np.zeros((len(q), 1))], axis=1)
    for op in (sg.union, sg.intersection, sg.difference):
        assert np.allclose(op(a, b, k=0.3).distance2(q), op(a3, b3, k=0.3).distance(p), atol=1e-12)


def test_transforms_rounding_onion():
    r = sg.rectangle((1.0, 0.5))
    q = grid2(81)
    assert np.allclose(r.translate((0.3, -0.2)).distance2(q), r.distance2(q - (0.3, -0.2)))
    rot = r.rotate(90).distance2(q)
    assert np.allclose(rot, r.distance2(q[:, ::-1]))           # a quarter turn swaps the axes
    assert np.allclose(r.scale(2).distance2(q), 2 * r.distance2(q / 2))
    assert r.scale((2, 1)).exactness == sg.BOUND and r.scale(2).exactness == sg.EXACT
    assert np.allclose(r.round(0.1).distance2(q), r.distance2(q) - 0.1)
    assert np.allclose(r.onion(0.1).distance2(q), np.abs(r.distance2(q)) - 0.05)


def test_new_shapes_against_closed_forms():
    q = grid2(121)
    tri = sg.triangle((0, 0), (1, 0), (0, 1))
    assert tri.distance2(np.array([[0.25, 0.25]]))[0] == pytest.approx(-0.25)
    assert tri.distance2(np.array([[2.0, 0.0]]))[0] == pytest.approx(1.0)
    hexagon = sg.regular_polygon(6, 1.0)
    # a regular hexagon with corners at 1: its edges are cos(30) from the centre
    assert hexagon.distance2(np.array([[0.0, 0.0]]))[0] == pytest.approx(-math.cos(math.pi / 6))
    assert hexagon.distance2(np.array([[0.0, 1.0]]))[0] == pytest.approx(0.0, abs=1e-12)  # a corner on +Y
    rounded = sg.regular_polygon(6, 1.0, 0.2)
    assert rounded.distance2(np.array([[0.0, 1.0]]))[0] == pytest.approx(0.0, abs=1e-12)  # same outer size
    assert rounded.distance2(np.array([[0.0, -math.cos(math.pi / 6)]]))[0] < 0  # the flat side stays put
    cap = sg.capsule2((-1, 0), (1, 0), 0.25)
    assert np.allclose(cap.distance2(q), np.hypot(np.maximum(np.abs(q[:, 0]) - 1, 0), q[:, 1]) - 0.25)
    ell = sg.ellipse((1.0, 0.5))
    assert ell.distance2(np.array([[1.0, 0.0], [0.0, 0.5]])) == pytest.approx([0.0, 0.0], abs=1e-12)
    ring = sg.arc(1.0, 360, 0.2)
    assert np.allclose(ring.distance2(q), np.abs(np.hypot(q[:, 0], q[:, 1]) - 1) - 0.1, atol=1e-12)
    half = sg.arc(1.0, 180, 0.2)
    assert half.distance2(np.array([[0.0, 1.0]]))[0] < 0 and half.distance2(np.array([[0.0, -1.0]]))[0] > 0.5
    star = sg.star(5, 1.0, sharpness=3.0)
    assert star.distance2(np.array([[0.0, 1.0]]))[0] == pytest.approx(0.0, abs=1e-12)  # a tip on +Y
    with pytest.raises(sg.ParameterError, match="collinear"):
        sg.triangle((0, 0), (1, 1), (2, 2))
    with pytest.raises(sg.ParameterError, match="sharpness"):
        sg.star(5, 1.0, sharpness=6.0)


def test_star_inner_radius_places_the_notches():
    """The third argument is the notches' radius (star(5, 1, 0.3) was refused as a sharpness)."""
    an = math.pi / 5
    for inner in (0.0, 0.3, 0.6, math.cos(an)):
        s = sg.star(5, 1.0, inner)
        notch = np.array([[inner * math.sin(an), inner * math.cos(an)]])  # between the tips at +Y and 72 deg
        assert s.distance2(notch)[0] == pytest.approx(0.0, abs=1e-12)
        assert s.distance2(np.array([[0.0, 1.0]]))[0] == pytest.approx(0.0, abs=1e-12)
    assert sg.star(5, 1.0, math.cos(an)).m == pytest.approx(2.0, abs=1e-12)  # the pentagon
    assert sg.star(5, 1.0, 0.0).m == pytest.approx(5.0, abs=1e-12)
    with pytest.raises(sg.ParameterError, match="inner_radius.*sharpness="):
        sg.star(5, 1.0, 3.0)  # an old positional sharpness is refused, naming the keyword
    with pytest.raises(sg.ParameterError, match="not both"):
        sg.star(5, 1.0, 0.3, sharpness=3)


def test_star_old_inner_keyword_warns_and_means_sharpness():
    with pytest.warns(DeprecationWarning, match="sharpness"):
        old = sg.star(5, 1.0, inner=3.5)
    assert old.key() == sg.star(5, 1.0, sharpness=3.5).key()


def test_star_document_round_trip_and_old_documents():
    for s in (sg.star(5, 1.0, 0.3), sg.star(6, 0.8, sharpness=4), sg.star()):
        scene = sg.extrude(s, 0.2)
        assert sg.from_dict(scene.to_dict()).key == scene.key
    old = sg.extrude(sg.star(5, 1.0, sharpness=3), 0.2).to_dict()
    old["scene"]["shape"]["inner"] = old["scene"]["shape"].pop("sharpness")  # as documents were written
    with pytest.warns(DeprecationWarning):
        assert sg.from_dict(old).key == sg.extrude(sg.star(5, 1.0, sharpness=3), 0.2).key


def test_slice_of_a_3d_node():
    s = sg.slice(sg.sphere(1.0).translate((0.2, 0, 0.6)))  # cut at z = 0: radius 0.8
    q = grid2(61)
    inside = s.distance2(q) < 0
    assert np.array_equal(inside, np.hypot(q[:, 0] - 0.2, q[:, 1]) < 0.8)
    assert s.exactness == sg.BOUND
    with pytest.raises(sg.ParameterError, match="unbounded"):
        sg.slice(sg.plane((1, 0, 0)))
    with pytest.raises(sg.ParameterError, match="baked"):
        sg.slice(sg.sphere(sg.param(1.0, name="r")))


def test_extrude_taper_and_twist_shape_the_solid():
    top, bottom = np.array([[0.45, 0.0, 0.49]]), np.array([[0.45, 0.0, -0.49]])
    t = sg.extrude(sg.rectangle(1.0), 1.0, taper=0.5)   # top half the size
    assert t.distance(bottom)[0] < 0 < t.distance(top)[0]
    # 90 degrees over the height, counter-clockwise going up: -45 at the bottom, +45 at the top
    w = sg.extrude(sg.rectangle((1.0, 0.2)), 1.0, twist=90)
    d = w.distance(np.array([[0.4, 0, 0], [0.28, 0.28, 0.499], [0.28, -0.28, 0.499], [0.28, -0.28, -0.499],
                             [0.28, 0.28, -0.499]]))
    assert d[0] < 0 and d[1] < 0 < d[2] and d[3] < 0 < d[4]
    with pytest.raises(sg.ParameterError, match="taper"):
        sg.extrude(sg.circle(1), 1.0, taper=1.0)


@pytest.mark.parametrize("name", sorted(all_nodes()))
def test_bounds_hold_every_node(name):
    node = all_nodes()[name]
    lo, hi = node.bounds
    box = np.where(np.isfinite(lo), lo, -4.0), np.where(np.isfinite(hi), hi, 4.0)
    pts = np.random.default_rng(3).uniform(box[0] - 1, box[1] + 1, size=(20000, 3))
    inside = node.distance(pts) < 0
    held = np.all((pts >= lo - 1e-9) & (pts <= hi + 1e-9), axis=1)
    assert np.all(held[inside]), f"{name}: interior points outside its bounds"
