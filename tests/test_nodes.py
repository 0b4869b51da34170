"""Node construction: validation messages, exactness classes, bounds, operators."""
import math

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.errors import ParameterError

from .conftest import all_primitives


@pytest.mark.parametrize("make, match", [
    (lambda: sg.sphere(-1), r"sphere: parameter 'radius' must be > 0"),
    (lambda: sg.sphere(float("nan")), r"sphere: parameter 'radius' must be finite"),
    (lambda: sg.sphere("1"), r"sphere: parameter 'radius' must be a number, got str"),
    (lambda: sg.box((1, 2)), r"box: parameter 'size' must have 3 components"),
    (lambda: sg.box((1, 0, 1)), r"box: parameter 'size\[1\]' must be > 0"),
    (lambda: sg.rounded_box(1, 0.8), r"rounded_box: parameter 'radius' \(0.8\) must be at most half"),
    (lambda: sg.torus(1, None), r"torus: parameter 'r2' must be a number, got NoneType"),
    (lambda: sg.capsule((0, 0, 0), (0, 0, 0), 0.2), r"capsule: end points 'a' and 'b' coincide"),
    (lambda: sg.cone(1, 0, 0), r"cone: radii 'r1' and 'r2' are both 0"),
    (lambda: sg.plane((0, 0, 0)), r"plane: parameter 'normal' must not be the zero vector"),
    (lambda: sg.sphere(1).scale(0), r"scale: parameter 'factor' must be > 0"),
    (lambda: sg.sphere(1).scale((1, 0, 1)), r"scale: parameter 'factor\[1\]' must be > 0"),
    (lambda: sg.sphere(1).translate((0, math.inf, 0)), r"translate: parameter 'offset\[1\]' must be finite"),
    (lambda: sg.sphere(1).rotate(30, (0, 0, 0)), r"rotate: parameter 'axis' must not be the zero vector"),
    (lambda: sg.sphere(1).color(1.5, 0, 0), r"color: colour components must lie in \[0, 1\]"),
    (lambda: sg.sphere(1) | 3, r"union: operand 1 must be an sdfgl node, got int"),
    (lambda: sg.union(sg.sphere(1)), r"union: needs at least two operands"),
    (lambda: sg.union(sg.sphere(1), sg.box(1), k=-0.1), r"union: parameter 'k' must be >= 0"),
    (lambda: sg.sphere(True), r"sphere: parameter 'radius' must be a number, got bool"),
])
def test_bad_parameters_name_node_and_parameter(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_exactness_classes():
    assert sg.sphere(1).exactness == sg.EXACT
    assert sg.ellipsoid((1, 2, 3)).exactness == sg.BOUND
    assert (sg.sphere(1) | sg.box(1)).exactness == sg.EXACT
    assert sg.union(sg.sphere(1), sg.box(1), k=0.2).exactness == sg.BOUND
    assert (sg.sphere(1) & sg.box(1)).exactness == sg.BOUND
    assert (sg.sphere(1) - sg.box(1)).exactness == sg.BOUND
    assert sg.sphere(1).scale(2).exactness == sg.EXACT
    assert sg.sphere(1).scale((1, 2, 1)).exactness == sg.BOUND
    assert sg.sphere(1).translate((1, 2, 3)).rotate(40, (1, 1, 0)).exactness == sg.EXACT
    assert all(n.lipschitz == 1.0 for n in all_primitives().values())


def test_tiny_k_is_treated_as_hard():
    u = sg.union(sg.sphere(1), sg.box(1), k=1e-40)
    assert u.k == 0.0 and u.exactness == sg.EXACT
    assert "opSmin" not in sg.compile(u)


def test_bounds_hold_the_solid():
    rng = np.random.default_rng(1)
    for name, node in all_primitives().items():
        node = node.rotate(33, (1, 2, 3)).translate((0.3, -0.2, 0.1))
        lo, hi = node.bounds
        box = np.where(np.isfinite(lo), lo, -5), np.where(np.isfinite(hi), hi, 5)
        pts = rng.uniform(box[0] - 1, box[1] + 1, size=(20000, 3))
        inside = node.distance(pts) < 0
        held = np.all((pts >= lo - 1e-9) & (pts <= hi + 1e-9), axis=1)
        assert np.all(held[inside]), f"{name}: interior points outside its bounds"


def test_operators_and_rotation():
    s = sg.sphere(1)
    assert isinstance(s | sg.box(1), sg.nodes.booleans.Union)
    assert isinstance(s & sg.box(1), sg.nodes.booleans.Intersection)
    assert isinstance(s - sg.box(1), sg.nodes.booleans.Difference)
    # orient(X) turns the Y-axis cylinder onto X
    c = sg.cylinder(0.25, 4).orient(sg.X)
    assert c.distance([[1.9, 0, 0]])[0] < 0 and c.distance([[0, 1.9, 0]])[0] > 0
    # rotate 90 degrees about Z takes +X to +Y
    b = sg.box((4, 0.5, 0.5)).rotate(90, sg.Z)
    assert b.distance([[0, 1.9, 0]])[0] < 0 and b.distance([[1.9, 0, 0]])[0] > 0


def test_distance_values():
    assert sg.sphere(1).distance([[3, 0, 0]])[0] == pytest.approx(2)
    assert sg.box(2).distance([[0, 0, 0]])[0] == pytest.approx(-1)
    assert sg.box(2).distance([[2, 2, 1]])[0] == pytest.approx(math.sqrt(2))
    assert sg.torus(1, 0.25).distance([[1, 0, 0]])[0] == pytest.approx(-0.25)
    assert sg.sphere(1).scale(2).distance([[5, 0, 0]])[0] == pytest.approx(3)
    assert sg.plane().distance([[0, 2, 7]])[0] == pytest.approx(2)
    with pytest.raises(ParameterError, match=r"points must have shape \(\.\.\., 3\)"):
        sg.sphere(1).distance([[1, 2]])


def test_fluent_methods_are_their_family_functions():
    """Node's modelling methods are registered by the modules of their nodes, with their signatures."""
    import inspect

    from sdfgl.nodes.base import FLUENT, fluent
    assert set(FLUENT) == {"__or__", "__and__", "__sub__", "union", "intersection", "difference", "translate", "rotate",
                           "orient", "scale", "twist", "bend", "taper", "dilate", "erode", "shear", "repeat", "mirror",
                           "symmetric", "repeat_polar", "elongate", "round", "shell", "displace", "color", "material"}
    for name, fn in FLUENT.items():
        assert getattr(sg.Node, name) is fn and fn.__doc__, name
        assert next(iter(inspect.signature(fn).parameters)) in ("node", "nodes"), name
        assert fn.__module__.startswith("sdfgl.nodes.") and fn.__module__ != "sdfgl.nodes.base", name
    assert sg.Node.twist is sg.twist and sg.Node.__or__ is sg.union and sg.Node.dilate is sg.Node.round
    s = sg.sphere(1)
    assert s.union(sg.box(1), k=0.1).key == sg.union(s, sg.box(1), k=0.1).key  # the same node either way
    assert (s - sg.box(1)).key == sg.difference(s, sg.box(1)).key
    assert s.twist(90, "x").key == sg.twist(s, 90, "x").key
    with pytest.raises(TypeError, match="Node.twist is registered by sdfgl.nodes.deform.twist already"):
        fluent("twist")(lambda node: node)
