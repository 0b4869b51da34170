"""More solids and operators: closed-form checks, live morphing, validation (parity, slopes
and bounds of every node are in test_parity / test_shapes2d)."""
import math

import numpy as np
import pytest

import sdfgl as sg


def test_solids_against_closed_forms():
    pts = np.array([[0.0, 0.0, 0.0], [0.0, 3.0, 0.0]])
    for solid, r in [(sg.tetrahedron(0.5), 0.5), (sg.dodecahedron(0.7), 0.7), (sg.icosahedron(0.7), 0.7)]:
        d = solid.distance(pts)
        assert d[0] == pytest.approx(-r) and d[1] > 0          # faces at the inradius
    # pyramid: exact on the axis above the apex and below the base
    p = sg.pyramid(2.0, 1.0)
    assert p.distance(np.array([[0, 3.0, 0]]))[0] == pytest.approx(1.0)
    assert p.distance(np.array([[0, -0.5, 0], [1.0, -0.5, 0]])) == pytest.approx([0.5, math.hypot(0.5, 0.5)])
    assert p.distance(np.array([[0, 0.01, 0]]))[0] == pytest.approx(-0.01)   # just above the base, inside
    # tube: distance to the polyline minus the radius
    t = sg.tube([(0, 0, 0), (1, 0, 0), (1, 1, 0)], 0.1)
    assert t.distance(np.array([[0.5, 0.5, 0], [2, 1, 0]])) == pytest.approx([0.4, 0.9])
    # bezier: the curve passes through its ends and its midpoint (a + 2b + c) / 4
    a, b, c = np.array([-1.0, 0, 0]), np.array([0.0, 2.0, 0]), np.array([1.0, 0, 0])
    bz = sg.bezier_tube(a, b, c, 0.1)
    assert bz.distance(np.array([a, c, (a + 2 * b + c) / 4])) == pytest.approx([-0.1] * 3, abs=1e-9)
    assert bz.distance(np.array([[0, 1.5, 0]]))[0] == pytest.approx(0.5 - 0.1, abs=1e-9)
    ct = sg.capped_torus(1.0, 0.2, 180)
    assert ct.distance(np.array([[0, 1.0, 0], [0, -1.0, 0]])) == pytest.approx([-0.2, math.hypot(1, 1) - 0.2])
    g = sg.gyroid(2 * math.pi, 0.1)
    assert g.distance(np.zeros((1, 3)))[0] == pytest.approx(-0.05)       # the origin lies on the sheet
    s = sg.slab(x0=-1, x1=1)
    assert s.distance(np.array([[0.0, 5, 5], [3, 0, 0]])) == pytest.approx([-1.0, 2.0])


def test_operators():
    b = sg.box(1.0)
    pts = np.random.default_rng(0).uniform(-1, 1, (200, 3))
    assert np.allclose(b.erode(0.1).distance(pts), b.distance(pts) + 0.1)
    assert np.allclose(b.dilate(0.1).distance(pts), b.distance(pts) - 0.1)
    m = sg.morph(sg.sphere(0.5), b, 0.25)
    assert np.allclose(m.distance(pts), 0.75 * sg.sphere(0.5).distance(pts) + 0.25 * b.distance(pts))
    sh = b.shear(1.0, "x", "y")
    assert sh.stretch == pytest.approx((1 + math.sqrt(5)) / 2)
    assert sh.distance(np.array([[0.6, 0.4, 0.0]]))[0] < 0 < sh.distance(np.array([[-0.6, 0.4, 0.0]]))[0]
    with pytest.raises(sg.ParameterError, match="morph: parameter 't' must lie in"):
        sg.morph(b, b, 1.5)
    with pytest.raises(sg.ParameterError, match="two different axes"):
        b.shear(1.0, "x", "x")
    with pytest.raises(sg.ParameterError, match="y0"):
        sg.slab(y0=1, y1=0)
    with pytest.raises(sg.ParameterError, match="coincide"):
        sg.tube([(0, 0, 0), (0, 0, 0)], 0.1)
    with pytest.raises(sg.ParameterError, match="straight tube"):
        sg.bezier_tube((0, 0, 0), (1, 0, 0), (2, 0, 0), 0.1)


def test_live_morph_renders_without_recompiling(renderer):
    t = sg.param(0.0)
    scene = sg.morph(sg.box(1.2), sg.sphere(0.5), t)
    cam = sg.Camera((0, 0, 4), fov=40)
    renderer.render(scene, cam, (48, 48), outputs=("color", "depth"))
    first = renderer.render(scene, cam, (48, 48), outputs=("color", "depth"))  # a second frame links the other tile programs
    compiles = renderer.programs.compiles
    t.value = 1.0
    second = renderer.render(scene, cam, (48, 48), outputs=("color", "depth"))
    assert renderer.programs.compiles == compiles
    assert np.isfinite(first.depth).sum() > np.isfinite(second.depth).sum() * 1.5  # the box covers more
    with pytest.raises(sg.ParameterError, match="morph"):
        t.value = 2.0
