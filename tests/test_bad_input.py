"""Every public function meets bad values (strings for vectors, NaN, None, wrong shapes,
objects) with an sdfgl error, never a raw ValueError/TypeError/AttributeError from inside."""
import inspect
import warnings

import pytest

import sdfgl as sg

BAD = ["x", float("nan"), float("inf"), None, [1, 2], {"a": 1}, -1, object(), (1, "a", 3), True, [[1, 2, 3]]]
VALID = {"radius": 0.5, "size": 1.0, "node": sg.sphere(1), "shape": sg.circle(0.3), "expr": "x**2 + y**2 + z**2 - 1",
         "x": "s", "y": "t", "z": "s*t", "points": [(0, 0), (1, 0), (0, 1)], "height": 1.0, "amplitude": 0.1,
         "rate": 10, "period": 1.0, "count": 3, "thickness": 0.1, "length": 0.2, "levels": 2, "offset": 0.5, "string": "Sg"}
SKIP = {"show", "render", "compile", "evaluate", "save_scene", "load_scene", "from_dict", "param"}
FACTORIES = [n for n in sg.__all__ if inspect.isfunction(getattr(sg, n)) and n not in SKIP]
METHODS = ["translate", "rotate", "orient", "scale", "twist", "bend", "repeat", "mirror", "symmetric",
           "repeat_polar", "elongate", "round", "shell", "displace", "color"]


# Values in BAD that are valid input for some parameters, and why (each case is refused elsewhere):
SIGNED = {"center", "normal", "point", "a", "b", "c", "offset", "rate", "taper", "twist", "angle", "start", "yaw",
          "pitch", "turns", "target", "direction", "position", "x0", "x1", "y0", "y1", "z0", "z1"}
"""Parameters where -1 is a value: any sign is meaningful, and a number is broadcast to a vector."""
STRINGS = {"axis", "axes", "expr", "code", "string"}
"""Parameters where "x" is a value: an axis name, an expression of x, GLSL source (the driver checks it), text."""
PLANE = {("circle", "center"), ("rectangle", "size"), ("ellipse", "radii"), ("capsule2", "a"), ("capsule2", "b"),
         ("tube", "points")}
"""Parameters of 2D shapes, where [1, 2] is a 2-vector (and a tube's points may be numbers, broadcast)."""
EXPRESSIONS = {"x", "y", "z", "expr"}
"""Parameters that take an expression, of which a number (-1) is the constant one."""
FUNCTIONS = {n for n in sg.__all__ if getattr(getattr(sg, n), "__module__", "") == "sdfgl.functions"}
"""sg.sin, sg.mix, ...: math over numbers, where nan, inf and -1 are numbers (nan propagates, as in numpy)."""


def _valid(fn_name, p, bad):
    """True if ``bad`` is a value parameter ``p`` of ``fn_name`` accepts (see the sets above)."""
    if bad is None and p.default is None:
        return True  # an optional parameter left out
    if bad is True and (isinstance(p.default, bool) or p.name == "shadow"):
        return True  # a flag
    if isinstance(bad, (int, float)) and not isinstance(bad, bool) and fn_name in FUNCTIONS:
        return True
    if isinstance(bad, int) and not isinstance(bad, bool) and bad == -1 and (p.name in SIGNED or
                                                                             p.name in EXPRESSIONS):
        return True
    if bad == "x" and p.name in STRINGS:
        return True
    if bad == {"a": 1} and p.name == "params":
        return True  # named parameters: one called "a", of value 1
    return bad == [1, 2] and (fn_name, p.name) in PLANE


def _cases(fn):
    # **options are not a parameter to pass by that name (their keys are the function's own)
    params = [p for p in inspect.signature(fn).parameters.values() if p.kind != p.VAR_KEYWORD]
    base = {p.name: VALID.get(p.name, 1.0) for p in params
            if p.kind != p.VAR_POSITIONAL and p.default is inspect.Parameter.empty}
    varpos = any(p.kind == p.VAR_POSITIONAL for p in params)
    for p in params:
        for bad in BAD:
            if _valid(fn.__name__, p, bad):
                continue
            if p.kind == p.VAR_POSITIONAL:
                yield p.name, bad, [sg.sphere(1), bad], base
            else:
                yield p.name, bad, [sg.sphere(1), sg.box(1)] if varpos else [], {**base, p.name: bad}


def _refused(call, what):
    """``call()`` must raise an sdfgl error: not a raw one from inside, and not nothing."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            warnings.simplefilter("ignore", DeprecationWarning)  # star(inner=...) is an old keyword
            call()
    except sg.SdfglError:
        return
    except Exception as exc:  # noqa: BLE001 - the point of the test
        pytest.fail(f"{what}: raw {type(exc).__name__}: {exc}")
    pytest.fail(f"{what}: accepted, not refused")


def test_refused_fails_when_nothing_is_refused():
    with pytest.raises(pytest.fail.Exception, match="accepted, not refused"):
        _refused(lambda: sg.sphere(1), "sphere(1)")
    with pytest.raises(pytest.fail.Exception, match="raw ValueError"):
        _refused(lambda: int("x"), "int('x')")


@pytest.mark.parametrize("name", FACTORIES)
def test_factories_refuse_bad_values_clearly(name):
    fn = getattr(sg, name)
    for pname, bad, args, kw in _cases(fn):
        _refused(lambda: fn(*args, **kw), f"sg.{name}({pname}={bad!r})")


# per call, the values of BAD that are valid input there (see SIGNED and STRINGS)
METHOD_VALID = {"translate": [-1], "rotate": [-1], "orient": [-1, "x"], "twist": [-1], "bend": [-1],
                "mirror": [-1], "symmetric": ["x"]}
CAMERA_VALID = {"target": [-1], "yaw": [-1], "pitch": [-1]}
COMPILE_VALID = {"shadows": [None, True], "debug": [None], "omega": [None]}


def _in(bad, values):
    """``bad`` is one of ``values`` (by equality and type: True is not 1, nor -1 a float)."""
    return any(type(bad) is type(x) and bad == x for x in values)


def test_methods_cameras_params_settings_and_points():
    s = sg.sphere(1)
    for bad in BAD:
        for m in METHODS:
            if not _in(bad, METHOD_VALID.get(m, [])):
                _refused(lambda: getattr(s, m)(bad), f"node.{m}({bad!r})")
        for kw in ("target", "distance", "yaw", "pitch", "fov"):
            if not _in(bad, CAMERA_VALID.get(kw, [])):
                _refused(lambda: sg.OrbitCamera(**{kw: bad}), f"OrbitCamera({kw}={bad!r})")
        if not _in(bad, [-1]):  # the eye (-1, -1, -1)
            _refused(lambda: sg.Camera(bad), f"Camera(eye={bad!r})")
        if not _in(bad, [-1]):
            _refused(lambda: sg.param(bad), f"param({bad!r})")
        for kw in ("aa", "shadows", "method", "max_steps", "outputs", "hit_scale", "debug", "omega", "max_dist"):
            if not _in(bad, COMPILE_VALID.get(kw, [])):
                _refused(lambda: sg.compile(s, **{kw: bad}), f"compile({kw}={bad!r})")
        if not _in(bad, [[[1, 2, 3]]]):  # one point, shape (1, 3)
            _refused(lambda: s.distance(bad), f"distance({bad!r})")
        if bad is not None:  # no bounds: found by sampling
            _refused(lambda: sg.implicit("x - 1", bounds=bad), f"implicit(bounds={bad!r})")
        _refused(lambda: sg.parametric("s", "t", "s*t", timeout=bad), f"parametric(timeout={bad!r})")
    with pytest.raises(sg.ParameterError, match="translate: the operand must be an sdfgl node, got str"):
        sg.Node.translate("not a node", (1, 2, 3))
    with pytest.raises(sg.ParameterError, match="'timeout' must be a number of seconds"):
        sg.parametric("s", "t", "s*t", timeout=float("nan"))
    with pytest.raises(sg.ParameterError, match=r"'bounds' must be two 3-vectors \(lo, hi\) with lo < hi"):
        sg.implicit("x - 1", bounds=((0, 0, 0), (1, float("nan"), 1)))


def test_functions_refuse_none_and_bools():
    """sg.sin(None) was nan and sg.min(True, 2) was 1.0: neither is a number."""
    for bad in (None, True, False):
        with pytest.raises(sg.ParameterError, match="sg.sin: parameter 'x' must be a number"):
            sg.sin(bad)
        with pytest.raises(sg.ParameterError, match="sg.min: parameter 'a' must be a number"):
            sg.min(bad, 2.0)


def test_turntable_checks_its_field_of_view_when_made():
    """turntable(fov=-1) was accepted and failed only when a frame's camera was made."""
    with pytest.raises(sg.ParameterError, match=r"turntable: parameter 'fov' must be in \[1e-4, 179\]"):
        sg.turntable(fov=-1)
    assert sg.turntable(fov=30).fov == 30.0


def test_gpu_side_inputs(renderer):
    s = sg.sphere(1)
    for bad in ("x", {"a": 1}, [[1, 2]], None):
        _refused(lambda: sg.evaluate(s, bad), f"evaluate({bad!r})")
        _refused(lambda: renderer.render(s, size=bad), f"render(size={bad!r})")
        if bad is not None:  # no camera: one that frames the scene
            _refused(lambda: renderer.render(s, camera=bad, size=(8, 8)), f"render(camera={bad!r})")
        _refused(lambda: renderer.render(bad, size=(8, 8)), f"render({bad!r})")
