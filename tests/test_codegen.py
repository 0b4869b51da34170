"""Generated GLSL: determinism, only what the scene uses, features absent when off,
every #define combination compiles on the real driver (and in glslangValidator)."""
import itertools
import re

import numpy as np
import subprocess

import pytest

import sdfgl as sg
from sdfgl.compiler.generate import generate
from sdfgl.errors import ShaderCompileError
from sdfgl.nodes.base import Primitive
from sdfgl.settings import Settings

from .conftest import glslang


def scene():
    return (sg.sphere(1) & sg.box(1.5)) - sg.cylinder(0.5, 4).orient(sg.X)


def test_same_scene_same_source_byte_for_byte():
    a = sg.compile(scene(), aa=2, shadows="soft", ao=True)
    b = sg.compile(scene(), aa=2, shadows="soft", ao=True)
    assert a == b
    assert sg.compile(scene(), aa=3) != a


def test_only_used_library_functions_are_included():
    src = sg.compile(sg.sphere(1))
    assert "float sdSphere(" in src
    for other in ("sdBox", "sdTorus", "sdCapsule", "sdCone", "opSmin", "sdHexPrism"):
        assert other not in src
    src = sg.compile(sg.union(sg.sphere(1), sg.torus(1, 0.2), k=0.3))
    assert "float opSmin(" in src and "float sdTorus(" in src and "sdBox" not in src


def test_features_that_are_off_are_absent():
    off = sg.compile(scene(), shadows=False, ao=False)
    # the functions are not in the source; only #ifdef-guarded call sites remain
    assert "float shadow(" not in off and "float calcAO(" not in off and "float groundHit(" not in off
    assert "#define SHADOWS" not in off and "#define AO" not in off
    soft = sg.compile(scene(), shadows="soft", ao=True, ground=True)
    assert "#define SHADOWS_SOFT" in soft and "float calcAO(" in soft and "float groundHit(" in soft
    hard = sg.compile(scene(), shadows="hard", ao=False)
    assert "#define SHADOWS_HARD" in hard and "penumbra" not in hard
    assert "#define OUT_DEPTH" not in sg.compile(scene())  # unless asked for, no extra outputs


def test_map_is_straight_line_distance_only_code():
    src = sg.compile(scene().color(0.2, 0.4, 0.6))
    body = src.split("float map(vec3 p) {")[1].split("}")[0]
    assert "for" not in body and "if" not in body and "vec4" not in body  # no colour work in map()
    assert "vec3 mapColor(vec3 p)" in src


def test_bad_settings_raise_clear_errors():
    with pytest.raises(sg.ParameterError, match=r"setting 'aa' must be an integer 1..4, got 5"):
        sg.compile(scene(), aa=5)
    with pytest.raises(sg.ParameterError, match=r"setting 'shadows' must be False, 'hard' or 'soft'"):
        sg.compile(scene(), shadows="fuzzy")
    with pytest.raises(sg.ParameterError, match=r"unknown setting\(s\) colour"):
        sg.compile(scene(), colour=1)
    with pytest.raises(sg.ParameterError, match=r"scene must be an sdfgl node"):
        sg.compile("sphere")


def test_huge_constant_is_rejected_naming_the_node():
    # a node's own parameter is refused when the node is built
    with pytest.raises(sg.ParameterError, match=r"translate: parameter 'offset\[0\]' must be at most 3.4e\+38"):
        sg.sphere(1).translate((1e39, 0, 0))
    # a constant inside a live expression (whose value is fine) by the code generator
    with pytest.raises(sg.ParameterError, match=r"sphere\(radius=param-expr.*value 1e\+39 does not fit in a float32"):
        sg.compile(sg.sphere(sg.param(1e-10) * 1e39))


COMBOS = list(itertools.product([1, 2, 3, 4], [False, "hard", "soft"], [False, True]))


@pytest.mark.parametrize("aa, shadows, ao", COMBOS)
def test_every_define_combination_compiles(renderer, aa, shadows, ao):
    st = Settings(aa=aa, shadows=shadows, ao=ao, ground=(aa % 2 == 0),
                  outputs=("color", "depth", "normal", "steps") if aa > 2 else ("color",))
    src = generate(scene(), st)
    renderer.programs.get(src)  # real driver compile + link
    if glslang:
        path = f"/tmp/sdfgl_{aa}_{shadows}_{ao}.frag"
        with open(path, "w") as f:
            f.write(src.text)
        out = subprocess.run([glslang, path], capture_output=True, text=True)
        assert out.returncode == 0, out.stdout + out.stderr


class _Broken(Primitive):
    """A deliberately broken node: its GLSL calls a function that does not exist."""

    kind = "broken"

    def _expr(self, em, p):
        return f"noSuchFunction({p})"

    def _distance(self, p):
        return p[..., 0]

    @property
    def _bounds(self):
        return sg.box(1).bounds


def test_compile_error_names_the_node(renderer):
    s = sg.sphere(1) | _Broken().translate((1, 0, 0))
    with pytest.raises(ShaderCompileError) as info:
        renderer.render(s, size=(8, 8))
    msg = str(info.value)
    assert "from union(k=0) > translate(offset=(1, 0, 0)) > broken()" in msg
    assert "noSuchFunction" in msg


def test_identical_subtrees_are_emitted_once(renderer):
    part = (sg.box(1) - sg.sphere(0.6)).color(0.2, 0.5, 0.8)
    s = part.translate((2, 0, 0)) | part.translate((-2, 0, 0)) | part.rotate(30, sg.Y)
    src = sg.compile(s)
    body = src.split("float map(vec3 p) {")[1].split("\n}")[0]
    assert src.count("float d0_color(vec3 p) {") == 1 and body.count("d0_color(") == 3
    assert src.count("sdBox(") - src.count("float sdBox(") == 2  # once in the distance, once in the colour function
    pts = np.random.default_rng(2).uniform(-3, 3, (2000, 3))
    assert np.abs(sg.evaluate(s, pts, renderer=renderer) - s.distance(pts)).max() < 1e-5


def test_map_is_called_in_loops_that_cannot_be_unrolled():
    # Mesa inlines every call: seven normal taps written out would be seven copies of map()
    src = sg.compile(scene(), ao=True, shadows="soft")
    assert "for (int i = uZero; i < 7; i++)" in src and "for (int i = uZero; i < 5 && !open; i++)" in src
    # one map() call site in the marching loop: settling (the hit probe, its refinement)
    # takes its samples in that loop, since llvmpipe runs every call site for every pixel
    for method, shape in (("enhanced", scene()), ("newton", sg.product(sg.sphere(1), sg.box(1)))):
        src = sg.compile(shape, method=method, analytic=False)
        bodies = dict(re.findall(r"\n\w+ (\w+)\([^)]*\) \{\n(.*?)\n\}\n", src, re.S))
        march = bodies["march"]
        sampling = [f for f, body in bodies.items() if "map(" in body and f not in ("map", "march")]
        assert march.count("map(") == 1, method
        assert not [f for f in sampling if f + "(" in march], method  # no nested loop around another map()


def test_every_target_is_a_row_of_the_table_and_others_are_refused():
    from sdfgl.compiler.targets import TARGETS
    s = sg.sphere(1).color(1, 0, 0)
    mains = {name: generate(s, Settings(), target=name).owners[-1] for name in TARGETS}
    assert mains["render"] == "shaders/mains/render_main.glsl"
    assert mains["evaluate_color"] == "shaders/mains/evaluate_channel_main.glsl"
    assert all(mains[m] == f"shaders/mains/{m}_main.glsl" for m in ("mesh_grid", "mesh_gradient", "mesh_project"))
    with pytest.raises(sg.ParameterError, match="target must be one of render, evaluate, .*got 'renderr'"):
        generate(s, Settings(), target="renderr")


@pytest.mark.skipif(not glslang, reason="glslangValidator is not installed")
def test_every_node_passes_the_second_compiler(tmp_path):
    # Mesa accepts some GLSL that 3.30 does not have (a line continuation, a function named
    # like a built-in): glslang holds every node's shader to the version it declares
    from .nodes_zoo import all_nodes
    for name, node in all_nodes().items():
        st = Settings(method="newton", ao=False) if node.exactness == sg.IMPLICIT else Settings()
        for dialect in ("desktop", "webgl2"):
            path = tmp_path / f"{name}_{dialect}.frag"
            path.write_text(generate(node, st, dialect=dialect).text)
            out = subprocess.run([glslang, str(path)], capture_output=True, text=True)
            assert out.returncode == 0, f"{name} ({dialect}): {out.stdout + out.stderr}"
