"""sg.glsl: a node whose GLSL the user writes (parity, slopes and bounds: the zoo's 'glsl' rows)."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.reference import trace

CAM = sg.Camera((0, 1, 3), (0, 0, 0), fov=45)


def test_compile_error_points_at_the_users_line(renderer):
    bad = sg.glsl("float r = length(p.xz) - 0.6;\nreturn lenght(vec2(r, p.y)) - 0.2;", bounds=((-1, -1, -1), (1, 1, 1)))
    with pytest.raises(sg.ShaderCompileError) as e:
        renderer.render(bad | sg.sphere(0.2), CAM, (16, 16))
    msg = str(e.value)
    assert "lenght" in msg and "line 2 of its code" in msg and "glsl('float r = length(p.xz) - 0.6;...')" in msg


@pytest.mark.parametrize("code, msg", [
    ("#define X 1\nreturn length(p) - X;", "line 1 of the code uses '#'"),
    ("return length(p) - 1.0; }\nvoid evil() {", "closes a brace"),
    ("if (p.x > 0.0) { return 1.0;", "brace\\(s\\) open"),
    ("uniform float r;\nreturn length(p) - r;", "'uniform'"),
    ("", "must be GLSL text"),
])
def test_code_that_would_break_the_shader_is_refused(code, msg):
    with pytest.raises(sg.ParameterError, match=msg):
        sg.glsl(code)


def test_without_a_twin_the_accuracy_tools_say_they_cannot_check(renderer):
    n = sg.glsl("length(p) - 0.5", bounds=((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)), exact=True)
    res = renderer.render(n, CAM, (32, 32), outputs=("color", "depth"))
    assert np.isfinite(res.depth).sum() > 100                 # it renders
    d = sg.evaluate(n, np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]))   # and runs on the GPU
    assert np.allclose(d, [-0.5, 0.5], atol=1e-6)
    with pytest.raises(sg.SdfglError, match="no float64 twin.*cannot check"):
        n.distance(np.zeros((1, 3)))
    with pytest.raises(sg.SdfglError, match="cannot check"):
        trace(n | sg.sphere(0.1), CAM, (8, 8))


def test_twin_errors_and_declared_factor():
    n = sg.glsl("length(p) - 0.5", twin=lambda p: np.zeros(3))
    with pytest.raises(sg.SdfglError, match="one value per point"):
        n.distance(np.zeros((5, 3)))
    boom = sg.glsl("length(p) - 0.5", twin=lambda p: 1 / 0)
    with pytest.raises(sg.SdfglError, match="ZeroDivisionError"):
        boom.distance(np.zeros((2, 3)))
    steep = sg.glsl("4.0 * (length(p) - 0.5)", twin=lambda p: 4 * (np.linalg.norm(p, axis=-1) - 0.5), lipschitz=4)
    assert steep.lipschitz == 1.0 and steep.exactness == sg.BOUND
    assert steep.distance(np.array([[1.0, 0, 0]]))[0] == pytest.approx(0.5)   # divided by its own factor only
    src = sg.compile(steep | sg.sphere(0.3).translate((2, 0, 0)))
    assert src.count("0.25") >= 1 and "userGlsl_" in src
    with pytest.raises(sg.ParameterError, match="exact field"):
        sg.glsl("length(p) - 1.0", exact=True, lipschitz=2)
    with pytest.raises(sg.ParameterError, match="bounds"):
        sg.glsl("length(p) - 1.0", bounds=((1, 1, 1), (0, 0, 0)))
