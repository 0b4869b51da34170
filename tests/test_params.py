"""Live parameters: uniforms instead of constants, changed without a recompile."""
import numpy as np
import pytest

import sdfgl as sg

from .test_parity import assert_parity


def live_nodes():
    """Every node type that takes live parameters, with all of them live; and the params."""
    P = sg.param
    ps = {}

    def p(name, value):
        ps[name] = P(value, name)
        return ps[name]

    nodes = {
        "sphere": sg.sphere(p("sphere.r", 0.7), p("sphere.c", (0.1, 0.0, -0.1))),
        "box": sg.box(p("box.size", (1.0, 0.6, 0.8))),
        "rounded_box": sg.rounded_box(p("rbox.size", 1.0), p("rbox.r", 0.2)),
        "plane": sg.plane(p("plane.n", (0.1, 1.0, 0.0)), p("plane.o", (0.0, -0.3, 0.0))),
        "torus": sg.torus(p("torus.r1", 0.7), p("torus.r2", 0.2)),
        "capsule": sg.capsule(p("cap.a", (-0.5, 0, 0)), p("cap.b", (0.4, 0.3, 0)), p("cap.r", 0.2)),
        "cylinder": sg.cylinder(p("cyl.r", 0.4), p("cyl.h", 1.2)),
        "cone": sg.cone(p("cone.h", 1.2), p("cone.r1", 0.5), p("cone.r2", 0.1)),
        "ellipsoid": sg.ellipsoid(p("ell.r", (0.9, 0.4, 0.6))),
        "octahedron": sg.octahedron(p("oct.s", 0.8)),
        "hex_prism": sg.hex_prism(p("hex.r", 0.5), p("hex.h", 1.0)),
        "box_frame": sg.box_frame(p("frame.size", 1.2), p("frame.t", 0.1)),
        "smooth_union": sg.union(sg.box(0.8), sg.sphere(0.5).translate((0.5, 0, 0)), k=p("union.k", 0.2)),
        "smooth_difference": sg.difference(sg.box(0.8), sg.sphere(0.5).translate((0.4, 0, 0)), k=p("diff.k", 0.1)),
        "translate": sg.torus(0.6, 0.2).translate(p("tr.off", (0.2, 0.1, 0))),
        "rotate": sg.box((1.2, 0.3, 0.4)).rotate(p("rot.deg", 30.0), (1, 1, 0)),
        "scale": sg.octahedron(0.5).scale(p("scale.s", 1.5)),
        "scale_axes": sg.sphere(0.5).scale(p("scale.v", (1.5, 0.6, 1.0))),
        "color": sg.sphere(0.5).color(p("color.rgb", (0.2, 0.4, 0.6))),
    }
    return nodes, ps


NEW = {"sphere.r": 0.9, "sphere.c": (0.3, 0.2, 0.0), "box.size": (0.7, 1.2, 0.5), "rbox.size": 1.4,
       "rbox.r": 0.3, "plane.n": (0.0, 1.0, 0.5), "plane.o": (0.0, 0.2, 0.0), "torus.r1": 0.5, "torus.r2": 0.3,
       "cap.a": (0, -0.5, 0), "cap.b": (0, 0.5, 0.2), "cap.r": 0.3, "cyl.r": 0.6, "cyl.h": 0.8, "cone.h": 0.8,
       "cone.r1": 0.2, "cone.r2": 0.5, "ell.r": (0.5, 0.8, 0.3), "oct.s": 1.1, "hex.r": 0.7, "hex.h": 0.5,
       "frame.size": 1.6, "frame.t": 0.2, "union.k": 0.5, "diff.k": 0.3, "tr.off": (-0.3, 0.2, 0.1),
       "rot.deg": 75.0, "scale.s": 0.8, "scale.v": (0.7, 1.4, 1.1), "color.rgb": (0.9, 0.1, 0.1)}


@pytest.mark.parametrize("name", sorted(live_nodes()[0]))
def test_live_node_parity_before_and_after_a_change(renderer, name):
    nodes, ps = live_nodes()
    node = nodes[name]
    assert node.live_params(), "the node must really read a live parameter"
    rng = np.random.default_rng(5)
    pts = rng.uniform(-1.5, 1.5, (3000, 3))
    src = sg.compile(node)
    # a live translation is summed with the moving shader origin on the CPU (uniform uOrgN)
    assert "uniform" in src and ("uP0" in src or "uOrg0" in src)
    assert_parity(node, pts, renderer)
    compiles = renderer.programs.compiles
    for prm in node.live_params():
        prm.value = NEW[prm.name]
    assert sg.compile(node) == src  # the source does not depend on the values
    assert_parity(node, pts, renderer)
    assert renderer.programs.compiles == compiles  # evaluate() reused the program


def test_render_follows_a_live_radius_without_recompiling(renderer):
    r = sg.param(0.5, "radius")
    s = sg.sphere(r)
    cam = sg.OrbitCamera(distance=4, yaw=0, pitch=0, fov=40)
    renderer.render(s, cam, (33, 33), outputs=("color", "depth"))
    a = renderer.render(s, cam, (33, 33), outputs=("color", "depth"))  # a second frame links the other tile programs
    compiles = renderer.programs.compiles
    r.value = 1.2  # grows past the bounds the first program saw: the box is a uniform too
    b = renderer.render(s, cam, (33, 33), outputs=("color", "depth"))
    assert renderer.programs.compiles == compiles
    assert abs(float(a.depth[16, 16]) - 3.5) < 1e-4 and abs(float(b.depth[16, 16]) - 2.8) < 1e-4
    assert np.isfinite(b.depth).sum() > 2 * np.isfinite(a.depth).sum()


def test_moving_the_camera_never_recompiles(renderer):
    s = sg.box(1) - sg.sphere(0.6)
    for _ in range(2):  # a second frame links the other tile programs
        renderer.render(s, sg.OrbitCamera(distance=4, yaw=10), (16, 16))
    compiles = renderer.programs.compiles
    for yaw in (20, 40, 80):
        renderer.render(s, sg.OrbitCamera(distance=3 + yaw / 40, yaw=yaw), (16, 16))
    assert renderer.programs.compiles == compiles


def test_setting_a_bad_value_names_the_node_and_keeps_the_old_value():
    r = sg.param(0.5, "radius")
    s = sg.sphere(r)  # checks live as long as their node (a discarded node checks nothing)
    with pytest.raises(sg.ParameterError, match=r"sphere: parameter 'radius' must be > 0, got -1"):
        r.value = -1
    assert r.value == 0.5
    size, rad = sg.param(1.0), sg.param(0.2)
    b = sg.rounded_box(size, rad)
    with pytest.raises(sg.ParameterError, match=r"rounded_box: parameter 'radius' \(0.6\) must be at most half"):
        rad.value = 0.6
    with pytest.raises(sg.ParameterError, match="a scalar parameter cannot take"):
        size.value = (1, 2, 3)
    k = sg.param(0.2)
    u = sg.union(sg.sphere(1), sg.box(1), k=k)
    with pytest.raises(sg.ParameterError, match="live parameter 'k' must stay >= 1e-30"):
        k.value = 0.0
    assert s is not None and b is not None and u is not None


def test_params_that_shape_the_code_are_refused():
    with pytest.raises(sg.ParameterError, match="'rate' cannot be a live parameter"):
        sg.box(1).twist(sg.param(30.0))
    with pytest.raises(sg.ParameterError, match="'period' and 'count' cannot be live"):
        sg.sphere(0.3).repeat(sg.param(1.0))
    with pytest.raises(sg.ParameterError, match="the axis cannot be a live parameter"):
        sg.box(1).rotate(sg.param(10.0), sg.param((0, 1, 0)))
