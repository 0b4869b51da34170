"""sdfgl studio: the node palette, copy as Python, the workspace, the server's security checks,
and the page in headless Chromium (built by its own editor API) against sg.render.

Pixel tolerance as in test_browser.py: under 1% of pixels may differ by more than 8/255
(SwiftShader and llvmpipe round transcendental functions differently).
"""
import asyncio
import base64
import http.client
import io
import json

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.errors import SceneDocumentError, SdfglError
from sdfgl.nodes.record import registry
from sdfgl.scene_io import from_dict, to_dict
from sdfgl.studio import Studio, Workspace
from sdfgl.studio.palette import palette
from sdfgl.studio.python_code import to_python
from sdfgl.web.chromium import Chromium, find_chromium

tornado = pytest.importorskip("tornado")

W, H = 160, 120
TOLERANCE = 8
MAX_FRACTION = 0.01
CAMERA = sg.OrbitCamera(target=(0, 0, 0), distance=4.5, yaw=30, pitch=25)
CODE = "__import__('os').system('touch /tmp/owned')"


def csg() -> sg.Node:
    """fogleman/sdf's CSG example."""
    c = sg.cylinder(0.5, 4)
    return (sg.sphere(1) & sg.box(1.5)) - (c.orient(sg.X) | c | c.orient(sg.Z))


def differing(a: np.ndarray, b: np.ndarray) -> float:
    return float((np.abs(a.astype(int) - b.astype(int)).max(axis=2) > TOLERANCE).mean())


# -- without a server -------------------------------------------------------------------------

def test_palette_lists_every_registered_kind_with_its_inputs_and_fields():
    entries = {e["kind"]: e for e in palette()}
    assert set(entries) == set(registry()) | {"output"} and "output" not in registry()
    assert [f["name"] for f in entries["output"]["fields"]] == ["camera", "settings"]
    assert entries["union"]["inputs"] == [{"name": "children", "many": True, "shape2d": False}]
    assert [f["name"] for f in entries["union"]["fields"]] == ["k", "blend"]
    radius = next(f for f in entries["sphere"]["fields"] if f["name"] == "radius")
    assert radius == {"name": "radius", "required": False, "default": 1.0, "number": True, "min": 0.125, "max": 4.0}
    assert [i["name"] for i in entries["translate"]["inputs"]] == ["child"]
    assert entries["extrude"]["inputs"][0]["shape2d"] is True
    json.dumps(palette(), allow_nan=False)  # the page receives it as JSON


def test_copy_as_python_rebuilds_the_same_glsl():
    r = sg.param(0.9, "r", range=(0.5, 1.5))
    c = sg.cylinder(0.5, 4)
    scene = (sg.sphere(r) & sg.box(1.5)) - (c.orient(sg.X) | c | c.orient(sg.Z))
    doc = to_dict(scene.translate((0.1, 0, 0)), CAMERA, {"aa": 2})
    code = to_python(doc)
    assert "eval" not in code and "from_dict" not in code
    ns: dict = {}
    exec(compile(code, "<studio>", "exec"), ns)  # the code this module generated, nothing from a document
    assert sg.compile(ns["scene"]) == sg.compile(from_dict(doc))
    assert ns["settings"] == {"aa": 2} and ns["camera"].distance == CAMERA.distance


def test_copy_as_python_writes_the_output_nodes_lights():
    lights = [sg.directional_light((1, 2, 0.5), color="#ffeedd", intensity=1.5, shadow="hard"),
              sg.point_light((0, 3, 1), intensity=4.0)]
    doc = to_dict(sg.sphere(1), CAMERA, {"aa": 1, "lights": lights})
    code = to_python(doc)
    assert "sg.directional_light(" in code and "sg.point_light(" in code
    ns: dict = {}
    exec(compile(code, "<studio>", "exec"), ns)
    assert sg.compile(ns["scene"], **ns["settings"]) == sg.compile(sg.sphere(1), aa=1, lights=lights)


def test_workspace_counts_compiles_and_slider_values_do_not_recompile(tmp_path):
    s = Workspace(tmp_path / "part.json", size=(W, H))
    r = sg.param(0.7, "r", range=(0.2, 1.2))
    spec = s.compile(to_dict(sg.sphere(r)))
    assert s.compiles == 1 and spec["params"][0]["label"] == "r"
    s.set_values({"r": 1.1})
    assert s.compiles == 1 and s.doc["params"]["r"]["value"] == 1.1 and s.document.params["r"].value == 1.1
    with pytest.raises(SdfglError, match="no live parameter named 'q'"):
        s.set_values({"q": 1})
    path = s.save()
    assert json.loads(path.read_text()) == s.doc
    again = Workspace(path, size=(W, H))
    assert again.doc == s.doc


def test_workspace_compiles_a_node_preview_as_one_webgl2_shader_with_its_live_parameters():
    s = Workspace(None, size=(W, H))
    r = sg.param(0.7, "r", range=(0.2, 1.2))
    spec = s.preview(to_dict(sg.sphere(r).translate((0.5, 0, 0))))
    assert s.preview_compiles == 1 and s.compiles == 0
    assert spec["size"] == [120, 80] and list(spec["variants"]) == ["1|off|0|none"]
    assert spec["settings"] == {"aa": 1, "shadows": False, "ao": False, "debug": None}
    assert [(p["uniform"], p["label"], p["min"], p["max"]) for p in spec["params"]] == [("uP0", "r", 0.2, 1.2)]
    assert "#version 300 es" in "".join(spec["blocks"]) and spec["frame"]["live"]
    flat = s.preview({"format": "sdfgl-scene", "version": 1, "scene": {"kind": "circle", "radius": 1.0}})
    assert s.preview_compiles == 2 and flat["blocks"] != spec["blocks"]  # a 2D shape: shown as a thin slab
    from sdfgl.web.spec import build
    slab, _ = build(sg.extrude(sg.circle(1.0), 0.1), None, (120, 80), toggles=False, aa=1, shadows=False, ao=False)
    assert flat["blocks"] == slab["blocks"]
    with pytest.raises(SdfglError):  # a broken subtree is refused, naming what is wrong
        s.preview({"format": "sdfgl-scene", "version": 1, "scene": {"kind": "circle", "radius": "big"}})


def test_workspace_refuses_code_in_strings_with_the_json_path(tmp_path):
    s = Workspace(None, size=(W, H))
    bad = {"format": "sdfgl-scene", "version": 1, "scene": {"kind": "implicit", "expr": CODE}}
    with pytest.raises(SceneDocumentError, match=r"^scene: implicit: unexpected character") as exc:
        s.compile(bad)
    assert s.compiles == 0
    from sdfgl.studio.workspace import error_of
    assert error_of(exc.value).path == "scene"
    with pytest.raises(SdfglError, match="started without a file"):
        s.save(bad)
    (tmp_path / "bad.json").write_text(json.dumps(bad))
    with pytest.raises(SceneDocumentError, match="scene: implicit: unexpected character"):
        Workspace(tmp_path / "bad.json")


# -- the server ---------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def served(tmp_path_factory):
    path = tmp_path_factory.mktemp("studio") / "part.json"
    with Studio(Workspace(path, size=(W, H))) as st:
        yield st


def get(st: Studio, target: str, host: str | None = None, cookie: str | None = None) -> int:
    conn = http.client.HTTPConnection("127.0.0.1", st.port, timeout=10)
    headers = {"Host": host or f"127.0.0.1:{st.port}"}
    if cookie:
        headers["Cookie"] = cookie
    conn.request("GET", target, headers=headers)
    status = conn.getresponse().status
    conn.close()
    return status


def test_token_and_host_are_required(served):
    st = served
    assert get(st, f"/?token={st.token}") == 200
    assert get(st, f"/?token={st.token}", host=f"localhost:{st.port}") == 200
    assert get(st, "/") == 403
    assert get(st, "/?token=wrong") == 403
    assert get(st, "/assets/studio.js") == 403
    assert get(st, "/assets/studio.js", cookie=f"sdfgl-studio-token-{st.port}={st.token}") == 200
    assert get(st, "/assets/studio.js", cookie=f"sdfgl-studio-token-{st.port + 1}={st.token}") == 403
    assert get(st, f"/assets/viewer.js?token={st.token}") == 200
    assert get(st, f"/?token={st.token}", host=f"evil.example:{st.port}") == 403   # DNS rebinding
    assert get(st, f"/?token={st.token}", host="127.0.0.1:1") == 403
    assert get(st, f"/assets/..%2Fserver.py?token={st.token}") == 404


def ws_talk(st: Studio, origin: str, messages: list[dict], token: str | None = None, replies: int = 1) -> list[dict]:
    from tornado.httpclient import HTTPRequest
    from tornado.websocket import websocket_connect

    async def talk() -> list[dict]:
        req = HTTPRequest(f"ws://127.0.0.1:{st.port}/ws?token={token or st.token}", headers={"Origin": origin})
        conn = await websocket_connect(req)
        out = [json.loads(await conn.read_message())]
        for m in messages:
            conn.write_message(json.dumps(m))
        while len(out) < replies + 1:
            out.append(json.loads(await conn.read_message()))
        conn.close()
        return out
    return asyncio.run(asyncio.wait_for(talk(), 60))


def test_websocket_checks_origin_and_token(served):
    from tornado.httpclient import HTTPClientError
    st = served
    with pytest.raises(HTTPClientError, match="403"):
        ws_talk(st, "http://evil.example", [], replies=0)
    with pytest.raises(HTTPClientError, match="403"):
        ws_talk(st, f"http://127.0.0.1:{st.port + 1}", [], replies=0)
    with pytest.raises(HTTPClientError, match="403"):
        ws_talk(st, st.origin, [], token="wrong", replies=0)
    hello, = ws_talk(st, st.origin, [], replies=0)
    assert hello["type"] == "hello" and hello["doc"]["format"] == "sdfgl-scene" and hello["file"] == "part.json"
    assert f'src="{st.url}"'.replace("&", "&amp;") in st._repr_html_()   # a notebook cell shows the page


def test_websocket_refuses_code_in_strings_with_the_json_path(served):
    st = served
    before = st.workspace.compiles
    doc = {"format": "sdfgl-scene", "version": 1,
           "scene": {"kind": "union", "children": [{"kind": "sphere"}, {"kind": "implicit", "expr": CODE}]}}
    _, reply = ws_talk(st, st.origin, [{"type": "doc", "gen": 1, "doc": doc}])
    assert reply["type"] == "error" and reply["path"] == "scene.children[1]" and reply["gen"] == 1
    assert st.workspace.compiles == before


# -- the page in headless Chromium ------------------------------------------------------------------

def canvas(b: Chromium) -> np.ndarray:
    rect = b.evaluate("(() => { const r = document.querySelector('#studio-view canvas').getBoundingClientRect();"
                      " return [r.x, r.y, r.width, r.height]; })()")
    assert rect[2:] == [W, H]
    return b.screenshot(tuple(rect))


PREVIEW = (120, 80)  # a node preview's size (workspace.PREVIEW_SIZE) and settings
PREVIEW_SETTINGS = {"aa": 1, "shadows": False, "ao": False}
PREVIEW_FRACTION = 0.02


def preview(b: Chromium, node: int) -> np.ndarray:
    """The pixels of a node's preview canvas (its 2D canvas, read back as PNG)."""
    from PIL import Image
    url = b.evaluate(f"document.querySelector('#node-{node} canvas.studio-preview').toDataURL('image/png')")
    img = np.asarray(Image.open(io.BytesIO(base64.b64decode(url.split(",", 1)[1]))).convert("RGB"))
    assert img.shape == (PREVIEW[1], PREVIEW[0], 3)
    return img


def frames(b: Chromium) -> int:
    return int(b.evaluate("+document.getElementById('studio-view').dataset.frames || 0"))


def settle(b: Chromium, after: int = -1) -> None:
    """Wait until the newest edit's view has drawn a full-resolution frame (after frame ``after``
    of the same view, for a slider move; a recompile starts a new view)."""
    root = "document.getElementById('studio-view')"
    b.wait_for(f"window.studio.state.shownGen === window.studio.state.gen && {root}.dataset.still === '1'"
               f" && +{root}.dataset.frames > {after}", timeout=120)


BUILD_CSG = """(async () => {
  const s = window.studio;
  s.clear();
  const cyl = s.addNode("cylinder", 40, 300, { radius: 0.5, height: 4 });
  const rx = s.addNode("rotate", 300, 250, { matrix: %(mx)s });
  const rz = s.addNode("rotate", 300, 420, { matrix: %(mz)s });
  s.connect(cyl, rx); s.connect(cyl, rz);
  const holes = s.addNode("union", 560, 300);
  s.connect(rx, holes); s.connect(cyl, holes); s.connect(rz, holes);
  const ball = s.addNode("sphere", 300, 20, { radius: 1 });
  const box = s.addNode("box", 300, 130, { size: 1.5 });
  const core = s.addNode("intersection", 560, 60);
  s.connect(ball, core); s.connect(box, core);
  const part = s.addNode("difference", 820, 150);
  s.connect(core, part); s.connect(holes, part);
  const out = s.addNode("output", 1060, 150, { camera: %(camera)s });
  s.connect(part, out);
  const err = await s.compileNow();
  return { err, ball, box, doc: s.document() };
})()"""


def open_page(b, url: str) -> None:
    """Load the studio page at ``url`` in browser ``b`` and wait for its first shown compile."""
    b.goto(url)
    b.wait_for("document.body.dataset.ready === '1' && window.studio.state.shownGen >= 1", timeout=60)


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    path = tmp_path_factory.mktemp("page") / "part.json"
    pytest.importorskip("pythonosc")
    from sdfgl.live import LiveControl
    live = LiveControl(osc=0)
    with Studio(Workspace(path, size=(W, H)), live=live) as st, Chromium(size=(1400, 800)) as b:
        live.start()
        open_page(b, st.url)
        yield st, b


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_csg_part_built_in_the_page_renders_like_sg_render(page):
    st, b = page
    m = {"camera": json.dumps(to_dict(sg.sphere(1), CAMERA)["camera"]),
         "mx": json.dumps(to_dict(sg.sphere(1).orient(sg.X))["scene"]["matrix"]),
         "mz": json.dumps(to_dict(sg.sphere(1).orient(sg.Z))["scene"]["matrix"])}
    built = b.evaluate(BUILD_CSG % m)
    assert built["err"] is None, built["err"]
    settle(b)
    assert b.evaluate("document.getElementById('studio-error').textContent") == ""
    doc = built["doc"]
    assert doc["nodes"] and doc["scene"]["kind"] == "difference"  # the cylinder used three times is shared
    web = canvas(b)
    egl = sg.render(csg(), CAMERA, (W, H), shadows="soft", ao=True).color
    assert differing(web, egl) < MAX_FRACTION

    # a live parameter: making the field live recompiles once; moving its slider never does
    compiles = st.workspace.compiles
    b.evaluate(f"window.studio.setLive({built['ball']}, 'radius', true); window.studio.compileNow()")
    b.wait_for(f"window.studio.state.compiles > {compiles}", timeout=60)
    settle(b)
    compiles = st.workspace.compiles
    name = f"n{built['ball']}_radius"
    n = frames(b)
    b.evaluate(f"window.studio.setParam('{name}', 1.12)")
    settle(b, n)
    grown = sg.render((sg.sphere(1.12) & sg.box(1.5)) - _holes(), CAMERA, (W, H), shadows="soft", ao=True).color
    assert differing(canvas(b), grown) < MAX_FRACTION
    assert differing(canvas(b), egl) > 0.01
    assert st.workspace.compiles == compiles and b.evaluate("window.studio.state.compiles") == compiles
    b.wait_for(f"window.studio.state.params['{name}'].value === 1.12")

    # a colour node: the picker writes the colour as the document does
    tinted = b.evaluate("""(() => { const s = window.studio;
      const c = s.addNode("color", 300, 600);
      const pick = document.querySelector(`#node-${c} input[data-colour]`);
      pick.value = "#ff8000"; pick.dispatchEvent(new Event("change", { bubbles: true }));
      return s.editor.getNodeFromId(c).data.fields.rgb; })()""")
    assert tinted == [1, 0.502, 0]
    # adding and taking back a node may recompile, as any structure edit: the debounced compile
    # is run now and awaited, so that none is still pending when the count is taken
    b.evaluate("(() => { window.studio.undo(); return window.studio.compileNow(); })()")
    settle(b)
    compiles = st.workspace.compiles

    # a node's own preview: its subtree drawn live with the view's camera, like sg.render
    b.wait_for("window.studio.previewsIdle()", timeout=120)
    want = sg.render(sg.sphere(1.12), CAMERA, PREVIEW, **PREVIEW_SETTINGS).color
    assert differing(preview(b, built["ball"]), want) < PREVIEW_FRACTION
    assert st.workspace.compiles == compiles

    # an error stays at its node; the last good image stays up
    n_err = b.evaluate(f"""(async () => {{ window.studio.setField({built['box']}, 'size', 'wide');
        return await window.studio.compileNow(); }})()""")
    assert n_err["node"] == built["box"] and "size" in n_err["message"]
    assert b.evaluate(f"document.getElementById('node-{built['box']}').classList.contains('studio-has-error')")
    assert differing(canvas(b), grown) < MAX_FRACTION
    assert st.workspace.compiles == compiles
    assert b.evaluate("window.studio.undo()") is True
    b.wait_for("window.studio.state.shownGen === window.studio.state.gen && "
               "document.getElementById('studio-error').textContent === ''", timeout=60)

    # save -> the file holds the page's document; load it back -> the same GLSL
    saved_name = b.evaluate("window.studio.save()")
    assert saved_name == "part.json"
    saved = json.loads(st.workspace.path.read_text())
    page_doc = b.evaluate("window.studio.document()")
    assert saved == page_doc and saved["params"][name]["value"] == 1.12
    b.evaluate(f"window.studio.load({json.dumps(saved)})")
    reloaded = b.evaluate("window.studio.document()")
    assert sg.compile(from_dict(reloaded)) == sg.compile(from_dict(saved))
    assert reloaded["params"] == saved["params"] and reloaded["camera"] == saved["camera"]

    # copy as Python rebuilds the same GLSL
    code = b.evaluate("window.studio.python()")
    ns: dict = {}
    exec(compile(code, "<studio>", "exec"), ns)  # generated by sdfgl from the decoded document
    assert sg.compile(ns["scene"]) == sg.compile(from_dict(saved))

    # export PNG: sg.render on the server
    from PIL import Image
    png = np.asarray(Image.open(io.BytesIO(base64.b64decode(b.evaluate("window.studio.export('png').then((r) => r.b64)")))).convert("RGB"))
    assert png.shape == (H, W, 3) and differing(png, grown) < MAX_FRACTION


def _holes() -> sg.Node:
    c = sg.cylinder(0.5, 4)
    return c.orient(sg.X) | c | c.orient(sg.Z)


IMPLICIT_SETTINGS = {"shadows": "soft", "ao": False, "method": "newton"}  # the view's start for an implicit scene


def build_one(b: Chromium, make: str) -> dict:
    """Clear the graph, add one node by the primitives panel's call ``make`` and view it."""
    cam = json.dumps(to_dict(sg.sphere(1), CAMERA)["camera"])
    return b.evaluate(f"""(async () => {{
      const s = window.studio;
      s.clear();
      const id = await {make};
      s.connect(id, s.addNode("output", 600, 100, {{ camera: {cam} }}));
      return {{ err: await s.compileNow(), doc: s.document() }};
    }})()""")


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_implicit_and_parametric_primitives_of_the_panel_render_like_python(page):
    pytest.importorskip("sympy")
    st, b = page
    box = ((-1.2, -1.2, -1.2), (1.2, 1.2, 1.2))
    built = build_one(b, f"window.studio.addImplicit('x^4 + y^4 + z^4 - 1', {json.dumps(box)})")
    assert built["err"] is None, built["err"]
    settle(b)
    want = sg.render(sg.implicit("x^4 + y^4 + z^4 - 1", box), CAMERA, (W, H), **IMPLICIT_SETTINGS).color
    assert differing(canvas(b), want) < MAX_FRACTION

    unit = ((-1.0, -1.0, -1.0), (1.0, 1.0, 1.0))
    built = build_one(b, f"window.studio.addParametric('s', 't', 's^2 - t^2', {json.dumps(unit)})")
    assert built["err"] is None, built["err"]
    settle(b)
    surface = sg.parametric("s", "t", "s^2 - t^2", unit)
    assert sg.compile(from_dict(built["doc"])) == sg.compile(surface)
    want = sg.render(surface, CAMERA, (W, H), **IMPLICIT_SETTINGS).color
    assert differing(canvas(b), want) < MAX_FRACTION


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_a_structure_edit_compiles_in_the_background_while_the_view_stays_live(page):
    import threading
    st, b = page
    b.evaluate("""(async () => { const s = window.studio; s.clear();
      const ball = s.addNode("sphere", 40, 40, { radius: 0.8 });
      s.setLive(ball, "radius", true);
      s.connect(ball, s.addNode("output", 400, 40));
      window.testBall = ball;
      return await s.compileNow(); })()""")
    settle(b)
    gate = threading.Event()
    st.worker.submit(gate.wait, 60)  # the server's compile worker is busy until the gate opens
    try:
        compiles = st.workspace.compiles
        b.evaluate("window.studio.setField(window.testBall, 'center', [0.3, 0, 0]); window.studio.compileNow(); 0")
        n = frames(b)
        b.evaluate("window.studio.setParam(`n${window.testBall}_radius`, 1.2)")
        settle_same_view = f"+document.getElementById('studio-view').dataset.frames > {n}"
        b.wait_for(settle_same_view, timeout=60)   # the old view still draws, with the new value
        assert b.evaluate("window.studio.state.shownGen < window.studio.state.gen")
        assert st.workspace.compiles == compiles
    finally:
        gate.set()
    settle(b)
    assert st.workspace.compiles == compiles + 1
    assert b.evaluate("window.studio.document()")["scene"]["center"] == [0.3, 0, 0]


def test_exports_go_through_the_existing_writers(tmp_path):
    ws = Workspace(tmp_path / "part.json", size=(W, H))
    ws.compile(to_dict(sg.sphere(0.8) | sg.box(0.9).translate((0.7, 0, 0)), CAMERA))
    name, page = ws.export("html")
    assert name == "part.html" and page.decode().startswith("<!DOCTYPE html>") and b"sdfgl-spec" in page
    name, png = ws.export("png")
    from PIL import Image
    image = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))
    assert name == "part.png" and differing(image, sg.render(sg.sphere(0.8) | sg.box(0.9).translate((0.7, 0, 0)),
                                                             CAMERA, (W, H)).color) == 0
    pytest.importorskip("trimesh")
    name, stl = ws.export("stl")
    assert name == "part.stl" and len(stl) > 84
    pytest.importorskip("imageio_ffmpeg")
    ws.size = (32, 24)   # a small clip: 120 frames
    name, clip = ws.export("mp4")
    assert name == "part.mp4" and clip[4:8] == b"ftyp"
    with pytest.raises(SdfglError, match="format must be one of png, html, stl, 3mf, mp4"):
        ws.export("exe")
    assert sorted(p.name for p in tmp_path.iterdir()) == []   # nothing written beside the document


def test_the_command_line_serves_the_document_until_interrupted(tmp_path):
    import signal
    import subprocess
    import sys
    doc = tmp_path / "part.json"
    sg.save_scene(sg.sphere(0.7), doc)
    proc = subprocess.Popen([sys.executable, "-m", "sdfgl", "studio", str(doc), "--no-browser", "--size", "64x48"],
                            stdout=subprocess.PIPE, text=True)
    try:
        line = proc.stdout.readline()
        assert line.startswith("sdfgl studio: http://127.0.0.1:") and "?token=" in line, line
        url = line.split()[2]
        port = int(url.split(":")[2].split("/")[0])
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
        conn.request("GET", url.split(f":{port}", 1)[1])
        assert conn.getresponse().status == 200
        conn.close()
    finally:
        proc.send_signal(signal.SIGINT)
        assert proc.wait(20) == 0


def test_the_command_line_stops_on_sigterm_and_on_sigint_when_started_with_it_ignored(tmp_path):
    # a shell without job control starts a background command with SIGINT ignored
    import signal
    import subprocess
    import sys
    doc = tmp_path / "part.json"
    sg.save_scene(sg.sphere(0.7), doc)
    for sig in (signal.SIGINT, signal.SIGTERM):
        proc = subprocess.Popen([sys.executable, "-m", "sdfgl", "studio", str(doc), "--no-browser"],
                                stdout=subprocess.PIPE, text=True,
                                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
        try:
            assert proc.stdout.readline().startswith("sdfgl studio: http://127.0.0.1:")
        finally:
            proc.send_signal(sig)
            try:
                code = proc.wait(20)
            except subprocess.TimeoutExpired:
                proc.kill()
                raise
        assert code == 0, sig


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_an_osc_binding_moves_the_pages_slider_without_a_recompile(page):
    import time

    from sdfgl.live import send_osc
    st, b = page
    cam = json.dumps(to_dict(sg.sphere(1), CAMERA)["camera"])
    ball = b.evaluate("""(async () => { const s = window.studio; s.clear();
      const ball = s.addNode("sphere", 40, 40, { radius: 0.7 });
      s.setLive(ball, "radius", true);
      s.connect(ball, s.addNode("output", 400, 40, { camera: CAMERA }));
      await s.compileNow();
      return ball; })()""".replace("CAMERA", cam))
    settle(b)
    name = f"n{ball}_radius"
    compiles = st.workspace.compiles
    # MIDI learn in the page: the next control change moved drives the parameter (the Web MIDI
    # handler fed with the bytes of a CC message; headless Chromium has no MIDI device)
    n = frames(b)
    b.evaluate(f"window.studio.midiLearn('{name}')")
    assert b.evaluate("window.studio.midiMessage([0xB0, 21, 127])") is True
    settle(b, n)
    lo, hi = b.evaluate(f"[window.studio.state.params['{name}'].min, window.studio.state.params['{name}'].max]")
    assert b.evaluate(f"window.studio.state.params['{name}'].value") == pytest.approx(hi)
    assert b.evaluate("window.studio.document().metadata.studio.midi")[name] == {"cc": 21, "channel": 0}
    b.evaluate("window.studio.midiMessage([0xB0, 21, 0])")
    assert b.evaluate(f"window.studio.state.params['{name}'].value") == pytest.approx(lo)
    assert b.evaluate("window.studio.midiMessage([0xB1, 21, 64])") is False   # another channel
    time.sleep(0.5)   # longer than the page's compile delay: learning and moving scheduled no compile
    assert st.workspace.compiles == compiles and b.evaluate("window.studio.state.shownGen === window.studio.state.gen")

    st.live.bind_osc("/radius", name)
    n = frames(b)
    send_osc("/radius", 1.3, port=st.live.osc_port)    # loopback UDP
    b.wait_for(f"Math.abs(window.studio.state.params['{name}'].value - 1.3) < 1e-6", timeout=30)  # OSC floats: 32 bits
    settle(b, n)
    want = sg.render(sg.sphere(1.3), CAMERA, (W, H), shadows="soft", ao=True).color
    assert differing(canvas(b), want) < MAX_FRACTION
    assert st.workspace.compiles == compiles and st.workspace.doc["params"][name]["value"] == pytest.approx(1.3)


def test_panel_primitives_declare_named_parameters_checked_by_name(tmp_path):
    pytest.importorskip("sympy")
    made = Workspace.primitive("implicit", {"expr": "x^2 + y^2 + z^2 - r^2", "bounds": [[-2] * 3, [2] * 3]},
                               "r = 0.8 in [0.3, 1.5]\nk = 2")
    assert made["node"]["params"] == [["r", {"param": "r"}], ["k", {"param": "k"}]]
    assert made["params"]["r"] == {"value": 0.8, "min": 0.3, "max": 1.5}
    assert made["params"]["k"]["min"] < 2 < made["params"]["k"]["max"]   # no range given: around the default
    glsl = Workspace.primitive("glsl", {"code": "return length(p) - r;", "bounds": [[-2] * 3, [2] * 3]},
                               "r = 0.5 in [0.1, 2]")
    assert glsl["node"]["kind"] == "glsl" and glsl["node"]["code"] == "return length(p) - r;"
    surface = Workspace.primitive("parametric", {"x": "a*s", "y": "t", "z": "s^2 - t^2"}, "a = 1 in [0.5, 2]")
    assert surface["node"]["kind"] == "implicit" and surface["node"]["params"] == [["a", {"param": "a"}]]
    for kind, fields, decl, msg in (
            ("implicit", {"expr": "x - r"}, "r = 3 in [0.1, 2]", r"parameter 'r': its default 3 is outside its range"),
            ("implicit", {"expr": "x - r"}, "r = 1 in [2, 1]", r"parameter 'r': its range \[2, 1\] must have low < high"),
            ("implicit", {"expr": "x - y"}, "y = 1", r"parameter name 'y' is taken"),
            ("implicit", {"expr": "x - s"}, "sin = 1", r"parameter name 'sin' is taken"),
            ("implicit", {"expr": "x - r"}, "r = 1\nr = 2", r"parameter 'r' is declared twice"),
            ("implicit", {"expr": "x - r"}, "r := 1", r"cannot read the parameter declaration 'r := 1'"),
            ("implicit", {"expr": "x - q"}, "r = 1", r"unknown symbol"),
            ("glsl", {"code": "return length(p) - dot;"}, "dot = 1", r"parameter name 'dot' is taken \(a GLSL"),
            ("glsl", {"code": "#define R 1\nreturn 1.0;"}, "", r"line 1 of the code uses '#'"),
            ("parametric", {"x": "s", "y": "t", "z": "t"}, "t = 1", r"parameter name 't' is taken")):
        with pytest.raises(SdfglError, match=msg):
            Workspace.primitive(kind, fields, decl)
    # in a document the named parameters are live: a new value moves a uniform, no recompile
    ws = Workspace(None, size=(W, H))
    doc = {"format": "sdfgl-scene", "version": 1, "params": glsl["params"], "scene": glsl["node"]}
    spec = ws.compile(doc)
    assert ws.compiles == 1 and [p["label"] for p in spec["params"]] == ["r"]
    ws.set_values({"r": 1.2})
    assert ws.compiles == 1 and ws.document.params["r"].value == 1.2
    doc["params"]["r"]["value"] = 1.2
    assert sg.compile(from_dict(doc)) == sg.compile(from_dict({**doc, "params": glsl["params"]}))


def _named_slider(b: Chromium, node: int, param: str, value: float) -> None:
    """Move the named parameter's slider on node ``node`` as a user drags it (an input event)."""
    b.evaluate(f"""(() => {{ const s = document.querySelector('#node-{node} input[data-named-param="{param}"]');
      s.value = '{value}'; s.dispatchEvent(new Event('input', {{ bubbles: true }})); }})()""")


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_named_parameters_of_the_panel_are_sliders_on_the_node_without_a_recompile(page):
    pytest.importorskip("sympy")
    st, b = page
    box = [[-1.6] * 3, [1.6] * 3]
    made = f"""window.studio.addPrimitive('implicit', {{ expr: 'x^2 + y^2 + z^2 - r^2', bounds: {json.dumps(box)} }},
      'r = 0.8 in [0.3, 1.5]')"""
    built = build_one(b, made)
    assert built["err"] is None, built["err"]
    settle(b)
    node = built["doc"]["scene"]
    name = node["params"][0][1]["param"]
    assert node["params"][0][0] == "r" and built["doc"]["params"][name] == {"value": 0.8, "min": 0.3, "max": 1.5}
    r = sg.param(0.8, "r", range=(0.3, 1.5))
    want = sg.implicit("x^2 + y^2 + z^2 - r^2", box, params={"r": r})
    assert differing(canvas(b), sg.render(want, CAMERA, (W, H), **IMPLICIT_SETTINGS).color) < MAX_FRACTION
    node_id = b.evaluate("Number(Object.values(window.studio.editor.export().drawflow.Home.data)"
                         ".find((n) => n.name === 'implicit').id)")
    compiles, n = st.workspace.compiles, frames(b)
    _named_slider(b, node_id, name, 1.2)
    settle(b, n)
    r.value = 1.2
    assert differing(canvas(b), sg.render(want, CAMERA, (W, H), **IMPLICIT_SETTINGS).color) < MAX_FRACTION
    assert st.workspace.compiles == compiles and st.workspace.doc["params"][name]["value"] == 1.2
    assert b.evaluate("window.studio.document()")["params"][name]["value"] == 1.2

    # a GLSL snippet of the panel: a node like the built-ins, its parameter a slider
    made = f"""window.studio.addPrimitive('glsl', {{ code: 'float q = length(p.xz) - r;\\nreturn length(vec2(q, p.y)) - 0.3;',
      bounds: {json.dumps(box)} }}, 'r = 0.7 in [0.3, 1.2]')"""
    built = build_one(b, made)
    assert built["err"] is None, built["err"]
    settle(b)
    assert built["doc"]["scene"]["kind"] == "glsl"
    r = sg.param(0.7, "r", range=(0.3, 1.2))
    torus = sg.glsl("float q = length(p.xz) - r;\nreturn length(vec2(q, p.y)) - 0.3;", bounds=box, params={"r": r})
    assert differing(canvas(b), sg.render(torus, CAMERA, (W, H)).color) < MAX_FRACTION
    node_id = b.evaluate("Number(Object.values(window.studio.editor.export().drawflow.Home.data)"
                         ".find((n) => n.name === 'glsl').id)")
    name = built["doc"]["scene"]["params"][0][1]["param"]
    compiles, n = st.workspace.compiles, frames(b)
    _named_slider(b, node_id, name, 1.0)
    settle(b, n)
    r.value = 1.0
    assert differing(canvas(b), sg.render(torus, CAMERA, (W, H)).color) < MAX_FRACTION
    assert st.workspace.compiles == compiles
    # a bad declaration is refused by the server, naming the parameter; no node is added
    err = b.evaluate("window.studio.addPrimitive('glsl', { code: 'return length(p) - r;' }, 'r = 5 in [0, 1]')"
                     ".then(() => null, (e) => e.message)")
    assert "parameter 'r': its default 5 is outside its range [0, 1]" in err


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_node_positions_are_saved_in_the_document_and_restored_on_open(page):
    st, b = page
    b.evaluate("""(async () => { const s = window.studio; s.clear();
      const ball = s.addNode("sphere", 37, 211, { radius: 0.6 });
      const cube = s.addNode("box", 58, 433, { size: 0.9 });
      const u = s.addNode("union", 402, 305);
      s.connect(ball, u); s.connect(cube, u);
      s.connect(u, s.addNode("output", 777, 123));
      return await s.compileNow(); })()""")
    settle(b)
    assert b.evaluate("window.studio.save()") == "part.json"
    saved = json.loads(st.workspace.path.read_text())
    want = {"scene": [402, 305], "scene.children[0]": [37, 211], "scene.children[1]": [58, 433], "output": [777, 123]}
    assert saved["metadata"]["studio"]["positions"] == want
    assert sg.load_scene(st.workspace.path).settings == {}   # kept, never rendered
    opened = Workspace(st.workspace.path)  # opening the file: the page builds its graph from it
    b.evaluate(f"window.studio.load({json.dumps(opened.doc)})")
    placed = b.evaluate("""Object.fromEntries(Object.values(window.studio.editor.export().drawflow.Home.data)
      .map((n) => [n.name + (n.data.fields.radius ?? n.data.fields.size ?? ''), [n.pos_x, n.pos_y]]))""")
    assert placed == {"sphere0.6": [37, 211], "box0.9": [58, 433], "union": [402, 305], "output": [777, 123]}
    assert b.evaluate("window.studio.document()")["metadata"]["studio"]["positions"] == want


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_output_node_controls_write_the_settings_and_re_render(page):
    st, b = page
    cam = json.dumps(to_dict(sg.sphere(1), CAMERA)["camera"])
    out = b.evaluate("""(async () => { const s = window.studio; s.clear();
      const ball = s.addNode("sphere", 40, 40, { radius: 0.7 });
      const floor = s.addNode("box", 40, 260, { size: [3, 0.2, 3] });
      const down = s.addNode("translate", 260, 260, { offset: [0, -0.9, 0] });
      s.connect(floor, down);
      const u = s.addNode("union", 480, 100);
      s.connect(ball, u); s.connect(down, u);
      const out = s.addNode("output", 700, 100, { camera: CAMERA, settings: { shadows: "soft" } });
      s.connect(u, out);
      await s.compileNow();
      return out; })()""".replace("CAMERA", cam))
    settle(b)
    scene = sg.sphere(0.7) | sg.box((3, 0.2, 3)).translate((0, -0.9, 0))
    shadowed = sg.render(scene, CAMERA, (W, H)).color
    assert differing(canvas(b), shadowed) < MAX_FRACTION
    assert b.evaluate(f"document.querySelector('#node-{out} [data-control=\"shadows\"]').checked") is True

    def control(sel: str, js: str) -> None:
        compiles = st.workspace.compiles
        b.evaluate(f"""(() => {{ const c = document.querySelector('#node-{out} {sel}'); {js};
          c.dispatchEvent(new Event('change', {{ bubbles: true }})); }})()""")
        b.wait_for(f"window.studio.state.compiles > {compiles}", timeout=60)
        settle(b)

    control('[data-control="shadows"]', "c.checked = false")
    assert b.evaluate("window.studio.document()")["settings"] == {"shadows": False}
    plain = sg.render(scene, CAMERA, (W, H), shadows=False).color
    assert differing(canvas(b), plain) < MAX_FRACTION and differing(canvas(b), shadowed) > 0.005
    control('[data-control="ao"]', "c.checked = false")
    control('[data-control="background"]', "c.value = '#336699'")
    control('[data-light-on="0"]', "c.checked = true")
    settings = b.evaluate("window.studio.document()")["settings"]
    assert settings == {"shadows": False, "ao": False, "background": "#336699",
                        "lights": [{"type": "directional", "direction": [0.5, 0.7, 0.4], "color": "#ffffff",
                                    "intensity": 1}]}
    from sdfgl.scene_io.decode import from_document
    doc = from_document(b.evaluate("window.studio.document()"))
    want = sg.render(doc.scene, doc.camera, (W, H), **doc.settings).color
    assert differing(canvas(b), want) < MAX_FRACTION
    control('[data-control="method"]', "c.value = 'sphere'")
    control('[data-control="aa"]', "c.value = '2'")
    assert b.evaluate("window.studio.document()")["settings"]["method"] == "sphere"
    assert b.evaluate("window.studio.document()")["settings"]["aa"] == 2
    assert b.evaluate("document.getElementById('studio-error').textContent") == ""


# -- node previews: live, in the page's one WebGL context -----------------------------------------

# counts the WebGL contexts the page creates (installed before any of the page's scripts run)
COUNT_CONTEXTS = """(() => {
  window.__glContexts = 0;
  const seen = new WeakSet();
  for (const cls of [HTMLCanvasElement, window.OffscreenCanvas].filter(Boolean)) {
    const get = cls.prototype.getContext;
    cls.prototype.getContext = function (type, ...rest) {
      const ctx = get.call(this, type, ...rest);
      if (ctx && /webgl/.test(type) && !seen.has(ctx)) { seen.add(ctx); window.__glContexts++; }
      return ctx;
    };
  }
})()"""

BUILD_ROW = """(async () => {
  const s = window.studio;
  s.clear();
  const parts = [], balls = [];
  for (let i = 0; i < 10; i++) {
    const ball = s.addNode("sphere", 40 + 130 * i, 40, { radius: 0.2 + 0.03 * i });
    const moved = s.addNode("translate", 40 + 130 * i, 260, { offset: [0.5 * i - 2.25, 0, 0] });
    s.connect(ball, moved);
    balls.push(ball); parts.push(moved);
  }
  const all = s.addNode("union", 600, 480);
  for (const m of parts) s.connect(m, all);
  const out = s.addNode("output", 900, 480, { camera: %(camera)s });
  s.connect(all, out);
  const err = await s.compileNow();
  return { err, balls, parts, all, nodes: Object.keys(s.editor.export().drawflow.Home.data).length };
})()"""


def row_scene(radii: list[float]) -> sg.Node:
    return sg.union(*[sg.sphere(r).translate((0.5 * i - 2.25, 0, 0)) for i, r in enumerate(radii)])


@pytest.fixture(scope="module")
def counted(tmp_path_factory):
    path = tmp_path_factory.mktemp("previews") / "row.json"
    with Studio(Workspace(path, size=(W, H))) as st, Chromium(size=(1400, 800)) as b:
        b.send("Page.addScriptToEvaluateOnNewDocument", {"source": COUNT_CONTEXTS}, session=True)
        open_page(b, st.url)
        yield st, b


@pytest.mark.browser
@pytest.mark.slow
@pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")
def test_every_node_has_a_live_preview_in_the_pages_one_webgl_context(counted):
    st, b = counted
    built = b.evaluate(BUILD_ROW % {"camera": json.dumps(to_dict(sg.sphere(1), CAMERA)["camera"])})
    assert built["err"] is None, built["err"]
    assert built["nodes"] >= 20
    settle(b)
    b.wait_for("window.studio.previewsIdle()", timeout=180)
    ids = built["balls"] + built["parts"] + [built["all"]]
    assert b.evaluate("window.studio.previewCount()") == len(ids)
    drawn = b.evaluate(f"{ids}.map((id) => +document.getElementById(`node-${{id}}`).dataset.previews || 0)")
    assert min(drawn) > 0
    assert b.evaluate("window.__glContexts") == 1
    radii = [0.2 + 0.03 * i for i in range(10)]

    # a preview is its subtree as sg.render draws it, with the output view's camera
    want = sg.render(sg.sphere(radii[3]).translate((-0.75, 0, 0)), CAMERA, PREVIEW, **PREVIEW_SETTINGS).color
    assert differing(preview(b, built["parts"][3]), want) < PREVIEW_FRACTION
    whole = preview(b, built["all"])
    assert differing(whole, sg.render(row_scene(radii), CAMERA, PREVIEW, **PREVIEW_SETTINGS).color) < PREVIEW_FRACTION

    # a slider moves the previews that read it, with no compile of the view or of any preview
    ball = built["balls"][3]
    b.evaluate(f"window.studio.setLive({ball}, 'radius', true); window.studio.compileNow()")
    settle(b)
    b.wait_for("window.studio.previewsIdle()", timeout=120)
    compiles, previews = st.workspace.compiles, st.workspace.preview_compiles
    n = int(b.evaluate(f"+document.getElementById('node-{built['all']}').dataset.previews"))
    b.evaluate(f"window.studio.setParam('n{ball}_radius', 0.5)")
    b.wait_for(f"+document.getElementById('node-{built['all']}').dataset.previews > {n}"
               " && window.studio.previewsIdle()", timeout=60)
    radii[3] = 0.5
    want = sg.render(row_scene(radii), CAMERA, PREVIEW, **PREVIEW_SETTINGS).color
    moved = preview(b, built["all"])
    assert differing(moved, want) < PREVIEW_FRACTION and differing(moved, whole) > 0.005
    assert differing(preview(b, ball), sg.render(sg.sphere(0.5), CAMERA, PREVIEW, **PREVIEW_SETTINGS).color) \
        < PREVIEW_FRACTION
    assert st.workspace.compiles == compiles and st.workspace.preview_compiles == previews

    # structure edits recompile the previews of the subtrees they change; the context stays one
    programs = b.evaluate("window.studio.glPrograms()")
    for k in range(10):
        err = b.evaluate(f"window.studio.setField({built['balls'][0]}, 'radius', {0.21 + 0.01 * k});"
                         " window.studio.compileNow()")
        assert err is None, err
    settle(b)
    b.wait_for("window.studio.previewsIdle()", timeout=180)
    assert st.workspace.preview_compiles > previews
    assert b.evaluate("window.__glContexts") == 1
    assert b.evaluate("window.studio.glPrograms()") <= programs + 1  # replaced programs are deleted
    radii[0] = 0.3
    want = sg.render(row_scene(radii), CAMERA, PREVIEW, **PREVIEW_SETTINGS).color
    assert differing(preview(b, built["all"]), want) < PREVIEW_FRACTION
