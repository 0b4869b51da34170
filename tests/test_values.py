"""The values layer: axes, and the rule that it (and camera, look, settings) stay below the scene graph."""
import ast
import pathlib

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.values import axes

PKG = pathlib.Path(sg.__file__).parent


def _sdfgl_imports(path: pathlib.Path) -> set[str]:
    """The sdfgl modules ``path`` imports (at any depth of its code), as dotted names."""
    package = path.relative_to(PKG.parent).with_suffix("").parts[:-1]  # what "." means in ``path``
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            base = list(package[:len(package) - node.level + 1]) if node.level else []
            mod = ".".join(base + ([node.module] if node.module else []))
            out |= {mod} | {f"{mod}.{a.name}" for a in node.names}
        elif isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
    return {m for m in out if m == "sdfgl" or m.startswith("sdfgl.")}


def test_values_import_nothing_of_sdfgl_but_errors():
    for path in (PKG / "values").glob("*.py"):
        bad = {m for m in _sdfgl_imports(path) if not m.startswith(("sdfgl.values", "sdfgl.errors"))}
        assert not bad, f"{path.name} imports {bad}"


@pytest.mark.parametrize("module", ["camera.py", "settings.py", "look/__init__.py", "look/lights.py",
                                    "look/background.py", "look/shading.py"])
def test_camera_look_settings_do_not_import_the_scene_graph(module):
    bad = {m for m in _sdfgl_imports(PKG / module) if m.startswith(("sdfgl.nodes", "sdfgl.codegen", "sdfgl.compiler"))}
    assert not bad, f"{module} imports {bad}"


@pytest.mark.parametrize("given", ["x", "X", " x", sg.X, (2.0, 0, 0), [1, 0, 0], np.array([3.0, 0.0, 0.0])])
def test_coordinate_axis_forms(given):
    assert axes.coordinate("n", "axis", given) == 0


@pytest.mark.parametrize("given", ["w", "xy", "", (1, 1, 0), -sg.X, (0, 0, 0), (1, 0), None, 1.0, sg.param(1.0)])
def test_coordinate_axis_refusals_name_the_parameter(given):
    with pytest.raises(sg.ParameterError, match="n: parameter 'axis'"):
        axes.coordinate("n", "axis", given)


def test_direction_forms():
    assert np.array_equal(axes.direction("n", "axis", "z"), sg.Z)
    assert np.array_equal(axes.direction("n", "axis", (1, 1, 0)), [1.0, 1.0, 0.0])
    with pytest.raises(sg.ParameterError, match="zero vector"):
        axes.direction("n", "axis", (0, 0, 0))
    with pytest.raises(sg.ParameterError, match="'x', 'y', 'z' or a vector"):
        axes.direction("n", "axis", "q")


def _shear_by(b, a):
    """A shear along ``a`` by another axis (z, or x when ``a`` is z)."""
    return b.shear(0.3, a, "x" if axes.coordinate("test", "along", a) == 2 else "z")


def test_every_axis_parameter_takes_a_name_a_constant_and_a_vector():
    """twist, bend and shear gave raw numpy errors for sg.X while rotate and orient took it."""
    b = sg.box((0.6, 2.0, 0.4))
    for make in (lambda a: b.twist(90, a), lambda a: b.bend(30, a), lambda a: b.taper(0.1, a),
                 lambda a: _shear_by(b, a), lambda a: b.rotate(30, a), lambda a: b.orient(a)):
        for ax, name in ((sg.X, "x"), (sg.Y, "y"), (sg.Z, "z")):
            by_constant, by_name, by_vector = make(ax), make(name), make(tuple(2.0 * ax))
            assert by_constant.key == by_name.key == by_vector.key
            assert by_name.key == make(name.upper()).key


def test_shear_takes_vectors_for_both_axes():
    b = sg.box(1.0)
    assert b.shear(0.5, sg.Z, sg.X).key == b.shear(0.5, "z", "x").key
    with pytest.raises(sg.ParameterError, match="two different axes"):
        b.shear(0.5, sg.X, "x")


def test_warps_keep_their_default_axis_key():
    b = sg.box((0.6, 2.0, 0.4))
    assert b.twist(90, sg.Y).key == b.twist(90).key and "axis" not in b.twist(90).params
    assert b.bend(30, sg.Z).key == b.bend(30).key and b.bend(30, sg.X).params["axis"] == "x"


def test_axes_given_as_vectors_round_trip_through_scene_documents():
    b = sg.box((0.6, 2.0, 0.4))
    for scene in (b.twist(90, sg.X), b.bend(30, (0, 0, 2)), b.shear(0.3, sg.Z, "x"), b.taper(0.1, sg.Z)):
        assert sg.from_dict(scene.to_dict()).key == scene.key
