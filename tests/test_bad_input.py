"""Every public function meets bad values (strings for vectors, NaN, None, wrong shapes,
objects) with an sdfgl error, never a raw ValueError/TypeError/AttributeError from inside."""
import inspect
import warnings

import pytest

import sdfgl as sg

BAD = ["x", float("nan"), float("inf"), None, [1, 2], {"a": 1}, -1, object(), (1, "a", 3), True, [[1, 2, 3]]]
VALID = {"radius": 0.5, "size": 1.0, "node": sg.sphere(1), "shape": sg.circle(0.3), "expr": "x**2 + y**2 + z**2 - 1",
         "x": "s", "y": "t", "z": "s*t", "points": [(0, 0), (1, 0), (0, 1)], "height": 1.0, "amplitude": 0.1,
         "rate": 10, "period": 1.0, "count": 3, "thickness": 0.1, "length": 0.2, "levels": 2, "offset": 0.5}
SKIP = {"show", "render", "compile", "evaluate", "save_scene", "load_scene", "from_dict", "param"}
FACTORIES = [n for n in sg.__all__ if inspect.isfunction(getattr(sg, n)) and n not in SKIP]
METHODS = ["translate", "rotate", "orient", "scale", "twist", "bend", "repeat", "mirror", "symmetric",
           "repeat_polar", "elongate", "round", "shell", "displace", "color"]


def _cases(fn):
    params = list(inspect.signature(fn).parameters.values())
    base = {p.name: VALID.get(p.name, 1.0) for p in params
            if p.kind != p.VAR_POSITIONAL and p.default is inspect.Parameter.empty}
    varpos = any(p.kind == p.VAR_POSITIONAL for p in params)
    for p in params:
        for bad in BAD:
            if p.kind == p.VAR_POSITIONAL:
                yield p.name, bad, [sg.sphere(1), bad], base
            else:
                yield p.name, bad, [sg.sphere(1), sg.box(1)] if varpos else [], {**base, p.name: bad}


def _only_sdfgl_errors(call, what):
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            call()
    except sg.SdfglError:
        pass
    except Exception as exc:  # noqa: BLE001 - the point of the test
        pytest.fail(f"{what}: raw {type(exc).__name__}: {exc}")


@pytest.mark.parametrize("name", FACTORIES)
def test_factories_refuse_bad_values_clearly(name):
    fn = getattr(sg, name)
    for pname, bad, args, kw in _cases(fn):
        _only_sdfgl_errors(lambda: fn(*args, **kw), f"sg.{name}({pname}={bad!r})")


def test_methods_cameras_params_settings_and_points():
    s = sg.sphere(1)
    for bad in BAD:
        for m in METHODS:
            _only_sdfgl_errors(lambda: getattr(s, m)(bad), f"node.{m}({bad!r})")
        for kw in ("target", "distance", "yaw", "pitch", "fov"):
            _only_sdfgl_errors(lambda: sg.OrbitCamera(**{kw: bad}), f"OrbitCamera({kw}={bad!r})")
        _only_sdfgl_errors(lambda: sg.Camera(bad), f"Camera(eye={bad!r})")
        _only_sdfgl_errors(lambda: sg.param(bad), f"param({bad!r})")
        for kw in ("aa", "shadows", "method", "max_steps", "outputs", "hit_scale", "debug", "omega", "max_dist"):
            _only_sdfgl_errors(lambda: sg.compile(s, **{kw: bad}), f"compile({kw}={bad!r})")
        _only_sdfgl_errors(lambda: s.distance(bad), f"distance({bad!r})")
        _only_sdfgl_errors(lambda: sg.implicit("x - 1", bounds=bad), f"implicit(bounds={bad!r})")
        _only_sdfgl_errors(lambda: sg.parametric("s", "t", "s*t", timeout=bad), f"parametric(timeout={bad!r})")
    with pytest.raises(sg.ParameterError, match="translate: the operand must be an sdfgl node, got str"):
        sg.Node.translate("not a node", (1, 2, 3))
    with pytest.raises(sg.ParameterError, match="'timeout' must be a number of seconds"):
        sg.parametric("s", "t", "s*t", timeout=float("nan"))
    with pytest.raises(sg.ParameterError, match=r"'bounds' must be two 3-vectors \(lo, hi\) with lo < hi"):
        sg.implicit("x - 1", bounds=((0, 0, 0), (1, float("nan"), 1)))


def test_gpu_side_inputs(renderer):
    s = sg.sphere(1)
    for bad in ("x", {"a": 1}, [[1, 2]], None):
        _only_sdfgl_errors(lambda: sg.evaluate(s, bad), f"evaluate({bad!r})")
        _only_sdfgl_errors(lambda: renderer.render(s, size=bad), f"render(size={bad!r})")
        _only_sdfgl_errors(lambda: renderer.render(s, camera=bad, size=(8, 8)), f"render(camera={bad!r})")
        _only_sdfgl_errors(lambda: renderer.render(bad, size=(8, 8)), f"render({bad!r})")
