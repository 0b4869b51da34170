"""Hostile numbers, expressions and run lengths get a clear sdfgl error, fast, never a raw traceback.

Each refusal is checked with ``pytest.raises`` (so the test fails when nothing is raised),
for its message (the parameter, JSON path or expression at fault) and for its time.
"""
import copy
import inspect
import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg
from sdfgl import expr
from sdfgl.animate.animation import MAX_FRAMES
from sdfgl.animate.jobfile import MAX_JOBS, JobFileError, load_jobs, parse_jobs
from sdfgl.scene_io import loads, to_dict

FAST = 0.5  # seconds a refusal may take


def refused(call, error=sg.SdfglError, match=None, seconds=FAST):
    """``call()`` raises ``error`` (matching ``match``) within ``seconds`` (the fastest of up
    to three tries: the first may pay for sympy's caches or a loaded machine); the message."""
    best = math.inf
    for _ in range(3):
        t0 = time.perf_counter()
        with pytest.raises(error, match=match) as info:
            call()
        best = min(best, time.perf_counter() - t0)
        if best < seconds:
            break
    assert best < seconds, f"refused after {best:.2f} s: {info.value}"
    return str(info.value)


@pytest.fixture(scope="module", autouse=True)
def _sympy_loaded():
    sg.implicit("x**2 + y - 1")  # time the refusals, not sympy's first import
    yield


# -- expressions -----------------------------------------------------------------------

UNDEFINED = [
    ("sqrt(-1) + x", r"the constant sqrt\(-1\) is undefined or not a real number"),
    ("x + log(0)", r"the constant log\(0\) is undefined"),
    ("acos(2) + y", r"the constant acos\(2\) is undefined"),
    ("x**2 + (-1)**0.5", r"the constant \(-1\)\*\*0.5 is undefined"),
    ("x / 0", r"division by zero"),
    ("y + 1 / (x - x)", r"undefined \(a division by zero\?\)"),
    ("sqrt(-x**2) + y", r"not real-valued: y \+ I\*Abs\(x\)"),
    ("x + 1e400", r"the constant 1e400 is beyond 10\*\*300"),
    ("E**E**E**E + x", r"the constant E\*\*\(E\*\*\(E\*\*E\)\) is beyond 10\*\*300"),
    ("E**E**E**E**E**E", r"is beyond 10\*\*300"),
    ("exp(exp(exp(exp(exp(x)))))", r"a tower of 5 exponentials"),
    ("x**x**x**x**x**x", r"a tower of 5 exponentials"),
    ("cosh(sinh(exp(exp(exp(y)))))", r"a tower of 5 exponentials"),
    ("(x**60)**60 - y", r"exponent 3600 is larger than 64"),
    ("*".join(f"sin(x + {i})" for i in range(100)), r"the gradient of the expression would have about"),
]


@pytest.mark.parametrize("text, pattern", UNDEFINED, ids=[u[0][:30] for u in UNDEFINED])
@pytest.mark.parametrize("api", ["implicit", "displace_expr"])
def test_undefined_complex_and_explosive_expressions_are_refused_fast(api, text, pattern):
    call = {"implicit": lambda: sg.implicit(text),
            "displace_expr": lambda: sg.displace_expr(sg.sphere(1), text, lipschitz=1)}[api]
    msg = refused(call, sg.ParameterError, pattern)
    assert msg.startswith(api)


def test_sympy_expressions_given_directly_are_held_to_the_same_bounds():
    import sympy as sp
    x, y = sp.symbols("x y", real=True)
    refused(lambda: sg.implicit(sp.sqrt(-1) * x + y), sg.ParameterError, "not real-valued")
    refused(lambda: sg.implicit(sp.exp(sp.exp(sp.exp(sp.exp(sp.exp(x))))) - y), sg.ParameterError,
            "a tower of 5 exponentials")
    refused(lambda: sg.implicit(sp.Float("1e400") * x + y), sg.ParameterError, r"beyond 10\*\*300")


def test_towers_within_the_limit_and_large_polynomials_still_build():
    assert expr.MAX_TOWER == 4
    for text in ("exp(exp(exp(exp(x)))) - y", "x**x**x**x**x - 2", "x**y + z"):
        t0 = time.perf_counter()
        node = sg.implicit(text, bounds=((0.1,) * 3, (1,) * 3))
        assert "xfExp(" in sg.compile(node, method="newton")  # a variable exponent, in extended range
        assert time.perf_counter() - t0 < 5
    import sympy as sp
    poly = " + ".join(f"{1 + i % 7}*x**{i % 5}*y**{(i // 5) % 5}*z**{(i // 25) % 5}" for i in range(90))
    xyz = dict(zip("xyz", sp.symbols("x y z", real=True)))
    assert expr.derivative_size(expr.parse_sympy(poly, xyz)) < expr.MAX_GRADIENT
    sg.implicit(poly + " - 1")


def test_expressions_that_failed_to_print_now_compile(renderer):
    # a power with a variable exponent ("cannot write TypeError in GLSL") and the derivative
    # of a nested abs in extended range ("cannot write sign in extended range", a ValueError)
    plain = sg.displace_expr(sg.sphere(1), "0.01 * x**y", lipschitz=1)
    assert "pow(x, y)" in sg.compile(plain)
    nested = sg.implicit("abs(x - abs(y))**64 - 1", bounds=((-2,) * 3, (2,) * 3))
    assert nested.extended and "sign(" in sg.compile(nested, method="newton")
    for node in (plain, nested):
        renderer.render(node, size=(8, 6), method="newton" if node is nested else "auto")


def test_a_displacement_constant_past_float32_is_refused():
    refused(lambda: sg.displace_expr(sg.sphere(1), "1e39 * sin(x)", lipschitz=1), sg.ParameterError,
            "displace_expr: the constant 1e.39 does not fit in float32")
    refused(lambda: sg.displace_expr(sg.sphere(1), 10 ** 400, lipschitz=1), sg.ParameterError, "does not fit")
    refused(lambda: sg.displace_expr(sg.sphere(1), "sin(x)", lipschitz=10 ** 400), sg.ParameterError,
            "'lipschitz' must be a number in")


# -- numbers at the nodes ----------------------------------------------------------------

@pytest.mark.parametrize("bad", [1e39, -1e39, 10 ** 400, -(10 ** 400), math.inf, math.nan],
                         ids=["1e39", "-1e39", "10**400", "-10**400", "inf", "nan"])
def test_numbers_past_float32_are_refused_where_they_are_given(bad):
    refused(lambda: sg.sphere(bad), sg.ParameterError, "sphere: parameter 'radius'")
    refused(lambda: sg.sphere(1).translate((bad, 0, 0)), sg.ParameterError, r"translate: parameter 'offset\[0\]'")
    refused(lambda: sg.point_light((0, 1, 0), intensity=bad), sg.ParameterError, "point_light: parameter 'intensity'")
    refused(lambda: sg.param(bad), sg.ParameterError, "param: value must be finite")
    refused(lambda: sg.param((0, bad, 0)), sg.ParameterError, "param: value must be")
    p = sg.param(1.0, name="r")
    s = sg.sphere(p)
    refused(lambda: setattr(p, "value", bad), sg.ParameterError, "value must be finite and at most 3.4e.38")
    assert p.value == 1.0 and float(s.distance((0, 0, 0))) == -1.0  # the refused value was not taken


def test_sizes_and_mesh_resolutions_that_are_not_numbers_are_refused():
    for size in ((math.inf, 24), (math.nan, 24), (10 ** 400, 24), (0, 0)):
        refused(lambda: sg.render(sg.sphere(1), size=size), sg.ParameterError, "render: 'size'")
    for res in (math.nan, math.inf, "x", 10 ** 400):
        refused(lambda: sg.mesh(sg.sphere(1), resolution=res), sg.ParameterError, "mesh: 'resolution'")
    refused(lambda: sg.mesh(sg.sphere(1), step=10 ** 400), sg.ParameterError, "mesh: 'step'")


BASE = {  # a valid call of every public factory that takes numbers: (args, kwargs)
    "sphere": ((1.0,), {}), "box": (((1, 1, 1),), {}), "rounded_box": (((1, 1, 1), 0.1), {}), "plane": ((), {}),
    "torus": ((1.0, 0.25), {}), "capsule": (((0, 0, 0), (0, 1, 0), 0.2), {}), "cylinder": ((0.5, 1.0), {}),
    "cone": ((0.5, 1.0), {}), "ellipsoid": (((1, 0.5, 0.5),), {}), "octahedron": ((1.0,), {}),
    "hex_prism": ((0.5, 1.0), {}), "box_frame": (((1, 1, 1), 0.1), {}), "twist": (("S", 1.0), {}),
    "bend": (("S", 0.5), {}), "repeat": (("S", 3.0), {"count": 2}), "circle": ((1.0,), {}),
    "rectangle": (((1, 1),), {}), "extrude": (("C", 1.0), {}),
    "revolve": (("C",), {"offset": 1.0}), "repeat_polar": (("P", 6), {}), "elongate": (("S", (1, 0, 0)), {}),
    "rounded": (("S", 0.1), {}), "shell": (("S", 0.1), {}), "sierpinski": ((), {}), "tree": ((), {}),
    "displace": (("S", 0.1), {}), "noise": ((), {}), "arc": ((1.0, 0.5, 0.1), {}),
    "capsule2": (((0, 0), (1, 0), 0.2), {}), "ellipse": (((1, 0.5),), {}), "regular_polygon": ((6,), {}),
    "star": ((5, 1.0, 0.5), {}), "triangle": (((0, 0), (1, 0), (0, 1)), {}),
    "bezier_tube": (((0, 0, 0), (1, 1, 0), (2, 0, 0)), {}), "capped_torus": ((1.0, 0.2, 1.0), {}),
    "dodecahedron": ((1.0,), {}), "gyroid": ((), {}), "icosahedron": ((1.0,), {}), "pyramid": ((1.0,), {}),
    "slab": ((), {"x0": 0.0, "x1": 1.0}), "tetrahedron": ((1.0,), {}),
    "tube": (([(0, 0, 0), (1, 0, 0), (1, 1, 0)],), {}), "morph": (("S", "B", 0.5), {}), "taper": (("S", 0.2), {}),
    "directional_light": ((), {}), "point_light": (((0, 3, 0),), {}), "param": ((1.0,), {}),
    "displace_expr": (("S", "0.1*sin(x)"), {"lipschitz": 1.0}), "turntable": ((), {}), "OrbitCamera": ((), {}),
    "Camera": (((0, 0, 5),), {}), "union": (("S", "B"), {"k": 0.1}), "intersection": (("S", "B"), {"k": 0.1}),
    "difference": (("S", "B"), {"k": 0.1}),
}
NODES = {"S": lambda: sg.sphere(1), "B": lambda: sg.box(1), "C": lambda: sg.circle(0.3),
         "P": lambda: sg.sphere(0.2, center=(2, 0, 0))}
NOT_NUMBERS = {("param", "name"), ("star", "inner")}  # a label, and a deprecated spelling of star's sharpness
HUGE = [math.inf, -math.inf, math.nan, 1e39, -1e39, 10 ** 400, -(10 ** 400)]


def _concrete(values):
    return [NODES[x]() if isinstance(x, str) and x in NODES else x for x in values]


@pytest.mark.parametrize("name", sorted(BASE))
def test_every_factory_refuses_huge_and_undefined_numbers_naming_the_parameter(name):
    """Each numeric parameter (and the first component of each vector) of each public
    factory, given inf, NaN, 1e39 or a 400-digit integer: an SdfglError naming it comes out
    (at construction, or at compile for a node), and nothing else."""
    fn = getattr(sg, name)
    args, kwargs = BASE[name]
    fn(*_concrete(args), **kwargs)  # the base call is valid
    sig = inspect.signature(fn)
    base = sig.bind(*args, **kwargs)
    base.apply_defaults()
    tried = 0
    for pname, val in base.arguments.items():
        if isinstance(val, (list, tuple)) and val and all(type(x) in (int, float) for x in val):
            variants = [type(val)([bad, *val[1:]]) for bad in HUGE]
        elif (type(val) in (int, float) or val is None) and (name, pname) not in NOT_NUMBERS:
            variants = HUGE
        else:
            continue
        for bad in variants:
            tried += 1
            call = sig.bind_partial()
            call.arguments.update({**base.arguments, pname: bad})

            def build():
                out = fn(*_concrete(call.args), **call.kwargs)
                if isinstance(out, sg.Node):
                    sg.compile(out)
            msg = refused(build)
            assert pname in msg, f"{name}({pname}={bad!r:.30}): {msg}"
    assert tried, f"{name} has no numeric parameter to try"


# -- scene documents -------------------------------------------------------------------

def _doc(scene, **extra):
    return json.dumps({"format": "sdfgl-scene", "version": 1, "scene": scene, **extra})


SPHERE = {"kind": "sphere", "radius": 1}
DOCUMENTS = [
    ("huge int radius", _doc({"kind": "sphere", "radius": 10 ** 400}), r"^scene: sphere: parameter 'radius'"),
    ("1e39 radius", _doc({"kind": "sphere", "radius": 1e39}), r"^scene: sphere: parameter 'radius' must be at most"),
    ("huge int param", _doc({"kind": "sphere", "radius": {"param": "r"}}, params={"r": {"value": 10 ** 400}}),
     r"^params\.r\.value: expected a finite number"),
    ("1e39 param", _doc({"kind": "sphere", "radius": {"param": "r"}}, params={"r": {"value": 1e39}}),
     r"^params\.r\.value: expected a finite number of at most 3.4e\+38"),
    ("huge camera distance", _doc(SPHERE, camera={"type": "orbit", "distance": 10 ** 400}), r"^camera\.distance"),
    ("object camera type", _doc(SPHERE, camera={"type": {"a": 1}}), r"^camera\.type: expected \"orbit\""),
    ("array camera type", _doc(SPHERE, camera={"type": ["orbit"]}), r"^camera\.type"),
    ("object light type", _doc(SPHERE, settings={"lights": [{"type": {}}]}), r"^settings\.lights\[0\]\.type"),
    ("huge light intensity", _doc(SPHERE, settings={"lights": [{"type": "point", "position": [0, 2, 0],
                                                              "intensity": 10 ** 400}]}),
     r"^settings\.lights\[0\]: point_light: parameter 'intensity'"),
    ("1e39 light intensity", _doc(SPHERE, settings={"lights": [{"type": "point", "position": [0, 2, 0],
                                                              "intensity": 1e39}]}),
     r"^settings\.lights\[0\]: point_light: parameter 'intensity'"),
    ("scalar light position", _doc(SPHERE, settings={"lights": [{"type": "point", "position": 3}]}),
     r"^settings\.lights\[0\]\.position: expected 3 numbers"),
    ("complex expression", _doc({"kind": "implicit", "expr": "sqrt(-1) + x"}), r"^scene: implicit: the constant"),
    ("exponential tower", _doc({"kind": "displace_expr", "child": SPHERE, "expr": "E**E**E**E", "lipschitz": 1}),
     r"^scene: displace_expr: the constant"),
    ("division by zero", _doc({"kind": "displace_expr", "child": SPHERE, "expr": "x / 0", "lipschitz": 1}),
     r"^scene: displace_expr: division by zero"),
]


@pytest.mark.parametrize("text, pattern", [d[1:] for d in DOCUMENTS], ids=[d[0] for d in DOCUMENTS])
def test_bad_documents_name_the_json_path(text, pattern):
    refused(lambda: loads(text), sg.SceneDocumentError, pattern)


def _fuzz_document():
    r = sg.param(0.8, name="r", range=(0.1, 2))
    scene = sg.union(sg.sphere(r).translate((1, 0, 0)), sg.box((1, 2, 1)).rotate(30, (0, 1, 0)),
                     sg.torus(1, 0.2).twist(0.5), sg.displace_expr(sg.sphere(0.5), "0.05*sin(8*x)"),
                     sg.implicit("x**2 + y**2 + z**2 - 0.5", bounds=((-1,) * 3, (1,) * 3)), k=0.1)
    return to_dict(scene, camera=sg.OrbitCamera(distance=5),
                   settings={"aa": 2, "lights": [sg.point_light((0, 3, 0), intensity=2.0)]})


def _paths(value, path=()):
    yield path
    items = value.items() if isinstance(value, dict) else enumerate(value) if isinstance(value, list) else ()
    for k, v in items:
        yield from _paths(v, path + (k,))


def _deep(n):
    out = 1
    for _ in range(n):
        out = [out]
    return out


FUZZ = [10 ** 400, -(10 ** 400), 1e39, 2 ** 63, {"a": 1}, ["x"], "x", True, None, {"float": "inf"},
        {"expr": "E**E**E**E"}, {"live": {"a": 1}, "args": [1]}, _deep(300)]


@pytest.mark.slow
def test_every_field_of_a_document_takes_hostile_values_with_a_clear_error():
    """Each field (and the document's every nested position) replaced by a huge, wrong-typed
    or deeply nested value: loading and compiling either works or raises SdfglError, within
    FAST seconds; NaN is refused by the parser."""
    doc = _fuzz_document()
    loads(json.dumps(doc))
    raw, slow, refusals = [], [], 0
    for path in list(_paths(doc))[1:]:
        for bad in FUZZ:
            d = copy.deepcopy(doc)
            holder = d
            for k in path[:-1]:
                holder = holder[k]
            holder[path[-1]] = bad
            text = json.dumps(d)
            t0 = time.perf_counter()
            try:
                sg.compile(loads(text).scene)
            except sg.SdfglError:
                refusals += 1
            except Exception as exc:  # noqa: BLE001 - what this test looks for
                raw.append(f"{'.'.join(map(str, path))} = {bad!r:.30}: {type(exc).__name__}: {exc}")
            if time.perf_counter() - t0 > FAST:
                slow.append(f"{'.'.join(map(str, path))} = {bad!r:.30}: {time.perf_counter() - t0:.2f} s")
    assert not raw, "\n".join(raw[:20])
    assert not slow, "\n".join(slow[:20])
    assert refusals > len(list(_paths(doc)))  # most replacements are refused, not silently taken
    refused(lambda: loads(json.dumps(doc).replace('"radius": 0.5', '"radius": NaN')), sg.SceneDocumentError,
            "NaN is not allowed")


def test_a_union_of_2000_children_from_a_document_renders_quickly(renderer):
    import random
    rng = random.Random(0)
    kids = [{"kind": "sphere", "radius": 0.05, "center": [rng.uniform(-3, 3) for _ in range(3)]} if i % 2 else
            {"kind": "translate", "child": {"kind": "box", "size": [0.1, 0.1, 0.1]},
             "offset": [rng.uniform(-3, 3) for _ in range(3)]} for i in range(2000)]
    t0 = time.perf_counter()
    scene = loads(_doc({"kind": "union", "children": kids})).scene
    res = renderer.render(scene, size=(16, 12))
    assert res.color.shape == (12, 16, 3)
    assert time.perf_counter() - t0 < 5


# -- run lengths -------------------------------------------------------------------------

def test_clip_length_is_bounded(tmp_path):
    out = tmp_path / "a.gif"
    s = sg.sphere(1)
    refused(lambda: sg.animate(s, out, seconds=1e9, size=(8, 8)), sg.ParameterError,
            rf"3e\+10 frames, more than the limit of {MAX_FRAMES}")
    refused(lambda: sg.animate(s, out, frames=10 ** 12, size=(8, 8)), sg.ParameterError, "frames is more than")
    for bad in (math.nan, math.inf, -1.0, "4"):
        refused(lambda: sg.animate(s, out, seconds=bad, size=(8, 8)), sg.ParameterError, "'seconds' must be")
    refused(lambda: sg.animate(s, out, seconds=1, start=math.nan, size=(8, 8)), sg.ParameterError, "'start'")
    assert not out.exists()


def test_crf_is_checked_for_the_codec(tmp_path):
    s = sg.sphere(1)
    refused(lambda: sg.animate(s, tmp_path / "a.mp4", seconds=0.1, size=(8, 8), crf=999), sg.ParameterError,
            r"'crf' must be a whole number in 0\.\.51 for libx264, got 999")
    refused(lambda: sg.animate(s, tmp_path / "a.webm", seconds=0.1, size=(8, 8), crf=64), sg.ParameterError,
            r"0\.\.63 for libvpx-vp9")
    refused(lambda: sg.animate(s, tmp_path / "a.mp4", seconds=0.1, size=(8, 8), crf=-1), sg.ParameterError, "crf")
    refused(lambda: sg.animate(s, tmp_path / "a.gif", seconds=0.1, size=(8, 8), crf=20), sg.ParameterError,
            "'crf' sets the quality of a video")
    assert not list(tmp_path.iterdir())


def _cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "sdfgl", *args], capture_output=True, text=True, timeout=120, cwd=cwd)


def test_cli_refuses_endless_clips_bad_crf_and_empty_windows(tmp_path):
    for args, pattern in ((["animate", "-o", str(tmp_path / "a.gif"), "--seconds", "1e9", "--size", "8x8"],
                           "more than the limit"),
                          (["animate", "-o", str(tmp_path / "a.gif"), "--crf", "999", "--size", "8x8"],
                           "'crf' sets the quality of a video"),
                          (["view", "--size", "0x0"], "size must be two whole numbers in 1..16384")):
        r = _cli(*args)
        assert r.returncode != 0, args
        assert pattern in r.stderr, r.stderr
        assert "Traceback" not in r.stderr, r.stderr


def _jobs(folder, output, **top):
    doc = {"jobs": [{"scene": "scene.py", "size": [8, 8], "output": output}], **top}
    path = folder / "jobs.json"
    path.write_text(json.dumps(doc))
    return path


@pytest.mark.parametrize("where", ["../outside.png", "sub/../../outside.png", "/tmp/sdfgl-outside.png"])
@pytest.mark.slow
def test_batch_outputs_outside_the_job_folder_need_permission(tmp_path, where):
    folder = tmp_path / "job"
    folder.mkdir()
    path = _jobs(folder, where)
    refused(lambda: load_jobs(path), JobFileError, r"outside the job file's folder .*\"allow_outside\": true")
    assert Path(load_jobs(path, allow_outside=True)[0].output).resolve() == (folder / where).resolve()
    assert load_jobs(_jobs(folder, where, allow_outside=True))
    refused(lambda: load_jobs(_jobs(folder, where, allow_outside="yes")), JobFileError, "allow_outside: must be")
    assert load_jobs(_jobs(folder, "inside/ok.png"))  # inside is fine, as before
    r = _cli("batch", str(_jobs(folder, where)), "--list")
    assert r.returncode != 0 and "outside the job file's folder" in r.stderr and "Traceback" not in r.stderr
    r = _cli("batch", str(path), "--list", "--allow-outside")
    assert r.returncode == 0, r.stderr


def test_a_job_file_that_expands_into_too_many_jobs_is_refused_fast(tmp_path):
    doc = {"jobs": [{"scene": "s.py", "count": 10 ** 12, "output": "{index}.png"}]}
    refused(lambda: parse_jobs(doc, tmp_path), JobFileError, rf"expands into {10 ** 12} jobs .* at most {MAX_JOBS}")
    doc = {"jobs": [{"scene": "s.py", "sweep": {"camera.yaw": list(range(1000)), "camera.pitch": list(range(1001))},
                     "output": "{index}.png"}]}
    refused(lambda: parse_jobs(doc, tmp_path), JobFileError, "expands into 1001000 jobs")


def test_the_limits_are_documented():
    text = (Path(__file__).parent.parent / "docs" / "batch-format.md").read_text()
    assert MAX_JOBS == 1_000_000 and "allow_outside" in text and "at most 1 000 000 jobs" in text
    assert "MAX_FRAMES" in sg.animate.__doc__


def test_a_graph_that_doubles_at_every_level_is_refused_before_the_driver_compiles() -> None:
    s = sg.sphere(0.5)
    for _ in range(14):  # 2^14 copies once the driver inlines the reused subtrees
        s = sg.union(s.translate((0.3, 0, 0)), s.translate((0, 0.3, 0)))
    t0 = time.perf_counter()
    with pytest.raises(sg.ParameterError, match="reused subtrees"):
        sg.render(s, size=(16, 12))
    assert time.perf_counter() - t0 < 5
    small = sg.sphere(0.5)
    for _ in range(3):  # a few levels stay well within the bound and render
        small = sg.union(small.translate((0.3, 0, 0)), small.translate((0, 0.3, 0)))
    assert sg.render(small, size=(16, 12)).color.std() > 0


def test_equal_children_built_apart_are_written_once() -> None:
    one = sg.box(0.5).twist(30)
    many = sg.union(*[sg.box(0.5).twist(30) for _ in range(2000)])
    t0 = time.perf_counter()
    image = sg.render(many, size=(32, 24)).color
    assert time.perf_counter() - t0 < 5
    assert np.array_equal(image, sg.render(one, size=(32, 24)).color)
    assert len(sg.compile(many)) < 1.2 * len(sg.compile(one))
