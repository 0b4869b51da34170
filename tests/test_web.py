"""The WebGL2 target, the one-file HTML, notebook reprs and the widget's Python side (no browser)."""
import io
import json
import re
from pathlib import Path

import moderngl
import numpy as np
import pytest
from PIL import Image

import sdfgl as sg
from sdfgl.cli import main
from sdfgl.compiler.generate import generate
from sdfgl.compiler.source import ShaderSource
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.gl.dialect import WEBGL2, dialect
from sdfgl.settings import Settings
from sdfgl.web.html import to_html
from sdfgl.web.spec import build, slider_range

from .nodes_zoo import all_nodes

ROOT = Path(__file__).resolve().parents[1]


def _spec_of(html: str) -> dict:
    m = re.search(r'<script type="application/json" id="sdfgl-spec">(.*?)</script>', html, re.S)
    return json.loads(m.group(1))


def test_every_node_compiles_as_glsl_es_300(renderer):
    # Mesa compiles "#version 300 es" with ES's rules (no implicit int -> float, ...), so
    # every shader file and node snippet is held to the subset both targets accept
    for name, node in all_nodes().items():
        implicit = node.exactness == sg.IMPLICIT
        st = Settings(method="newton", ao=False) if implicit else Settings()
        src = generate(node, st, dialect="webgl2")
        assert src.text.startswith(WEBGL2.header())
        renderer.programs.get(src)  # raises ShaderCompileError naming the node


def test_every_toggle_state_compiles_as_glsl_es_300(renderer):
    r = sg.param(0.5, "r")
    scene = sg.union(sg.sphere(r), sg.torus(0.6, 0.15).translate((0.8, 0, 0)), k=0.1).color(0.8, 0.3, 0.2)
    spec, params = build(scene, size=(64, 48), ground=True)
    assert params == (r,) and len(spec["variants"]) == 27  # AA 1..4 x shadows 3 x AO 2, 3 debug views
    known = {*spec["uniforms"], "uP0", *spec["frame"]["base"]}
    for key, ids in spec["variants"].items():
        text = "".join(spec["blocks"][i] for i in ids)
        prog = renderer.programs.get(ShaderSource(text, ("(test)",) * text.count("\n")))
        # the page sets every uniform a shader reads (a new one in a .glsl file must be added to the viewer)
        read = {name for name in prog if isinstance(prog[name], moderngl.Uniform)}
        assert read <= known, (key, read - known)
    # the scene's map() is stored once for all 27 shaders
    assert sum(b.count("float map(vec3 p)") for b in spec["blocks"]) == 1


def test_implicit_fields_and_newton_compile_as_es(renderer):
    scene = sg.implicit("x**2 + y**2 + z**2 - 1", bounds=((-1.2,) * 3, (1.2,) * 3))
    spec, _ = build(scene, size=(32, 32))
    assert spec["toggles"]["ao"] == [False] and len(spec["variants"]) == 15
    for ids in spec["variants"].values():
        text = "".join(spec["blocks"][i] for i in ids)
        renderer.programs.get(ShaderSource(text, ("(test)",) * text.count("\n")))


def test_unknown_dialect_is_refused():
    with pytest.raises(sg.ParameterError, match="unknown GLSL dialect 'gles2'"):
        dialect("gles2")
    with pytest.raises(sg.ParameterError, match="unknown GLSL dialect"):
        generate(sg.sphere(1), Settings(), dialect="metal")


def test_demo_html_is_one_small_file_without_network():
    html = to_html(demo_scene(), demo_camera(), (800, 500), ground=True)
    size = len(html.encode())
    assert size < 1024 * 1024, size
    assert not re.search(r"https?://|<script[^>]+src=|<link[^>]+href=|import\s*\(|fetch\(", html)
    spec = _spec_of(html)
    assert spec["size"] == [800, 500] and spec["settings"]["shadows"] == "soft"
    assert spec["vertex"].startswith("#version 300 es\nprecision highp float;")


def test_unions_as_data_carry_their_textures():
    spheres = [sg.sphere(0.1).translate((x, y, 0)) for x in np.linspace(-2, 2, 12) for y in np.linspace(-2, 2, 12)]
    spec, _ = build(sg.union(*spheres), size=(64, 48))
    names = {d["name"] for d in spec["data"]}
    assert names == {"uData"}  # every table (cells, lists, instances) in one texture (#12)
    prims = spec["data"][0]
    import base64
    arr = np.frombuffer(base64.b64decode(prims["b64"]), dtype="<f4")
    assert arr.size == prims["width"] * prims["height"] * 4 and np.isfinite(arr).all()


def test_slider_ranges_stay_where_the_nodes_accept_values():
    r = sg.param(1.0, "r")
    ball = sg.sphere(r)  # a live node: its check (radius > 0) bounds the slider (dropped nodes' checks go with them)
    lo, hi = slider_range(r)
    assert 0 < lo < 1.0 < hi <= 2.0 and r.value == 1.0 and ball.live_params() == [r]  # radius > 0; value restored
    assert slider_range(sg.param(0.2, range=(0.1, 3))) == (0.1, 3.0)
    with pytest.raises(sg.ParameterError, match="range must be two numbers low < high"):
        sg.param(1.0, "k", range=(2, 1))
    lo, hi = slider_range(sg.param(1.0, range=(0.5, float("inf"))))  # an open end: the default, within the range
    assert lo == 0.5 and 1.0 < hi < float("inf")
    with pytest.raises(sg.ParameterError, match=r"range must be \(low, high\)"):
        sg.param(1.0, "k", range=3)


def test_live_scene_box_is_tabulated_over_each_slider():
    r = sg.param(1.0, "r", range=(0.5, 2.0))
    spec, _ = build(sg.sphere(r), size=(32, 32))
    sweep = spec["frame"]["sweeps"][0]
    assert sweep["values"][0] == 0.5 and sweep["values"][-1] == 2.0
    his = [f["uBoundsHi"][0] for f in sweep["frames"]]
    assert his == sorted(his) and abs(his[-1] - 2.0) < 0.01  # the box grows with the radius


def test_bad_html_input_says_what_is_wrong(tmp_path):
    with pytest.raises(sg.ParameterError, match="scene must be an sdfgl node"):
        to_html("sphere")
    with pytest.raises(sg.ParameterError, match="view size"):
        to_html(sg.sphere(1), size=(4, 4))
    with pytest.raises(sg.ParameterError, match="unknown setting"):
        to_html(sg.sphere(1), shadow=True)
    with pytest.raises(sg.SdfglError, match="cannot write HTML file"):
        sg.save_html(sg.sphere(1), tmp_path / "missing" / "x.html")


def test_cli_html(tmp_path, capsys):
    out = tmp_path / "csg.html"
    assert main(["html", str(ROOT / "examples" / "csg.py"), "-o", str(out), "--size", "320x200", "--aa", "2"]) == 0
    spec = _spec_of(out.read_text())
    assert spec["size"] == [320, 200] and spec["settings"]["aa"] == 2
    assert "wrote" in capsys.readouterr().out
    assert main(["html", str(tmp_path / "nope.py")]) == 2


def test_render_result_repr_is_short_and_png_is_the_image():
    res = sg.render(sg.sphere(1), size=(40, 30), outputs=("color", "depth"))
    text = repr(res)
    assert len(text) < 120 and "40x30" in text and "depth" in text
    img = np.asarray(Image.open(io.BytesIO(res._repr_png_())))
    assert np.array_equal(img, res.color)


def test_node_preview_can_be_turned_off():
    s = sg.sphere(1) - sg.box(1.2)
    img = Image.open(io.BytesIO(s._repr_png_()))
    assert img.size == (256, 160) and len(np.unique(np.asarray(img).reshape(-1, 3), axis=0)) > 20
    implicit = sg.implicit("x**2 + y**2 + z**2 - 1", bounds=((-1.2,) * 3, (1.2,) * 3))
    assert implicit._repr_png_() is not None  # rendered with a method that suits it
    try:
        sg.set_preview(False)
        assert s._repr_png_() is None
    finally:
        sg.set_preview(True)
    with pytest.raises(sg.SdfglError, match="size"):
        sg.set_preview(True, size=(1, 1))


def test_widget_syncs_params_and_camera_both_ways():
    r = sg.param(1.0, "r", range=(0.3, 1.6))
    scene = sg.sphere(r) | sg.box(1.0).translate((1.5, 0, 0))
    w = sg.widget(scene, size=(64, 48))
    assert w.values == [1.0] and w.frame["uBoundsHi"][1] == pytest.approx(1.003)
    r.value = 1.3                         # Python -> view
    assert w.values == [1.3] and w.frame["uBoundsHi"][1] == pytest.approx(1.3 + 1e-3 * 3.3)
    w.values = [0.7]                      # what the view sends when a slider moves
    assert r.value == 0.7 and w.error == ""
    w.values = [-1.0]                     # refused by the param's range: the view is sent back
    assert r.value == 0.7 and w.values == [0.7] and "outside its range [0.3, 1.6]" in w.error
    w.camera_state = {**w.camera_state, "yaw": 75.0, "distance": 7.0}  # the user orbits
    cam = w.camera
    assert isinstance(cam, sg.OrbitCamera) and cam.yaw == 75.0 and cam.distance == 7.0
    w.camera = sg.OrbitCamera(target=(1, 0, 0), distance=9, yaw=10, pitch=5)  # Python moves the view
    assert w.camera_state["target"] == [1.0, 0.0, 0.0] and w.camera_state["distance"] == 9.0
    assert w.render(size=(32, 24)).color.shape == (24, 32, 3)


def test_show_outside_a_notebook_still_means_a_window():
    from sdfgl.web.notebook import in_kernel
    assert not in_kernel()


def test_clip_box_margin_covers_what_adding_sweeps_misses():
    a, b = sg.param(1.0, "a", range=(0.5, 1.5)), sg.param(1.0, "b", range=(0.5, 1.5))
    spec, _ = build(sg.sphere(a) & sg.sphere(b), size=(32, 32))
    # the box of an intersection grows only when both radii grow: one sweep alone sees no change
    assert spec["frame"]["margin"] >= 0.4
    spec, _ = build(sg.sphere(a).translate((2, 0, 0)) | sg.sphere(b), size=(32, 32))
    assert spec["frame"]["margin"] < 1e-9  # each radius moves its own side: the sum is exact
    assert a.value == 1.0 and b.value == 1.0


def test_a_browser_that_fails_to_start_says_so():
    from sdfgl.web.chromium import Chromium
    with pytest.raises(sg.SdfglError, match=r"Chromium exited \(status 1\)"):
        Chromium(executable="/bin/false", timeout=10)
