"""The HTML view in a real browser: headless Chromium, WebGL2 on SwiftShader (software).

Screenshots of the page's canvas are compared pixel by pixel with the EGL render of the
same scene, camera and settings. Tolerance: under 1% of pixels may differ by more than
8/255 in any channel (the two are different float32 implementations: SwiftShader and
llvmpipe round transcendental functions differently, which moves a few silhouette and
shadow-edge pixels). Images are small to keep the suite cheap.
"""
import json
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.camera import OrbitCamera
from sdfgl.scenefile import load_scene_file
from sdfgl.web import assets
from sdfgl.web.chromium import Chromium, file_url, find_chromium
from sdfgl.web.html import save_html
from sdfgl.web.spec import build, build_spec, camera_from_state

pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(find_chromium() is None, reason="needs Chromium (./install.sh --test installs it)")]

ROOT = Path(__file__).resolve().parents[1]
GALLERY = sorted((ROOT / "examples" / "gallery").glob("*.py"))
W, H = 160, 120
TOLERANCE = 8        # per channel, out of 255
MAX_FRACTION = 0.01  # of pixels beyond the tolerance
ROOT_EL = "document.getElementById('sdfgl-root')"


@pytest.fixture(scope="module")
def browser():
    with Chromium(size=(W + 360, H + 260)) as b:
        yield b


def frames(b: Chromium, root: str = ROOT_EL) -> int:
    return int(b.evaluate(f"{root}.dataset.frames || 0"))


def wait_still(b: Chromium, after: int = 0, root: str = ROOT_EL) -> None:
    """Wait for a full-resolution frame drawn after frame number ``after``."""
    b.wait_for(f"{root}.dataset.still === '1' && +{root}.dataset.frames > {after}", timeout=120)


def canvas(b: Chromium) -> np.ndarray:
    rect = b.evaluate("(() => { const r = document.querySelector('canvas').getBoundingClientRect();"
                      " return [r.x, r.y, r.width, r.height]; })()")
    assert rect[2:] == [W, H]
    return b.screenshot(tuple(rect))


def differing(a: np.ndarray, b: np.ndarray) -> float:
    """Share of pixels where some channel differs by more than TOLERANCE."""
    return float((np.abs(a.astype(int) - b.astype(int)).max(axis=2) > TOLERANCE).mean())


def open_html(b: Chromium, path: Path) -> None:
    b.goto(file_url(path))
    wait_still(b)
    assert b.evaluate("document.querySelector('.sdfgl-error').textContent") == ""


def egl_settings(scene: sg.Node, **settings: object) -> dict:
    """The settings the HTML view starts with (as build_spec picks them)."""
    implicit = scene.exactness == sg.IMPLICIT
    return {"shadows": "soft", "ao": not implicit, **({"method": "newton"} if implicit else {}), **settings}


@pytest.mark.parametrize("path", GALLERY, ids=[p.stem for p in GALLERY])
@pytest.mark.slow
def test_gallery_scene_in_the_browser_matches_egl(browser, tmp_path, path):
    sf = load_scene_file(path)
    cam = OrbitCamera.of(sf.camera, *sf.scene.bounds)
    html = save_html(sf.scene, tmp_path / "scene.html", cam, (W, H), **sf.settings)
    open_html(browser, html)
    web = canvas(browser)
    egl = sg.render(sf.scene, cam, (W, H), **egl_settings(sf.scene, **sf.settings)).color
    frac = differing(web, egl)
    print(f"{path.stem}: {100 * frac:.3f}% of pixels differ by more than {TOLERANCE}/255")
    assert frac < MAX_FRACTION


def test_slider_toggles_and_orbit_change_the_image_as_egl_does(browser, tmp_path):
    r = sg.param(0.6, "r", range=(0.3, 1.0))
    scene = sg.union(sg.sphere(r).color(0.9, 0.4, 0.2), sg.box((0.8, 0.5, 0.8)).translate((0.9, 0, 0)), k=0.1)
    cam = sg.OrbitCamera(target=(0.4, 0, 0), distance=4.0, yaw=25, pitch=20)
    html = save_html(scene, tmp_path / "p.html", cam, (W, H))
    open_html(browser, html)
    before = canvas(browser)

    # the slider: the sphere grows, and the page matches EGL at the new value
    n = frames(browser)
    browser.evaluate("(() => { const s = document.querySelector('input[type=range]');"
                     " s.value = '0.9'; s.dispatchEvent(new Event('input')); })()")
    wait_still(browser, n)
    grown = canvas(browser)
    assert differing(before, grown) > 0.05
    r.value = 0.9
    assert differing(grown, sg.render(scene, cam, (W, H)).color) < MAX_FRACTION

    # key O turns AO off, as ao=False does
    n = frames(browser)
    browser.send("Input.dispatchKeyEvent", {"type": "keyDown", "key": "o", "code": "KeyO", "text": "o",
                                            "windowsVirtualKeyCode": 79}, session=True)
    browser.send("Input.dispatchKeyEvent", {"type": "keyUp", "key": "o", "code": "KeyO",
                                            "windowsVirtualKeyCode": 79}, session=True)
    wait_still(browser, n)
    assert browser.evaluate("window.sdfglViewer.settings.ao") is False
    assert differing(canvas(browser), sg.render(scene, cam, (W, H), ao=False).color) < MAX_FRACTION

    # a left drag orbits (at reduced resolution while moving); the camera the page ends
    # on, rebuilt in Python, renders the same image on EGL
    n, reduced = frames(browser), int(browser.evaluate(f"+{ROOT_EL}.dataset.reduced"))
    mouse = [("mousePressed", 60, 60, 1), *[("mouseMoved", 60 + 8 * i, 60 + 2 * i, 1) for i in range(1, 8)],
             ("mouseReleased", 116, 74, 0)]
    for kind, x, y, buttons in mouse:
        browser.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": "left",
                                                  "buttons": buttons, "clickCount": 1}, session=True)
    wait_still(browser, n)
    state = browser.evaluate("window.sdfglViewer.camera")
    assert state["yaw"] == pytest.approx((25 - 0.4 * 56) % 360) and state["pitch"] == pytest.approx(20 + 0.4 * 14)
    assert int(browser.evaluate(f"+{ROOT_EL}.dataset.reduced")) > reduced
    moved = camera_from_state(state)
    assert differing(canvas(browser), sg.render(scene, moved, (W, H), ao=False).color) < MAX_FRACTION


def test_widget_script_syncs_with_its_model(browser):
    """The anywidget module in the browser with a stand-in model object (the comm is ipywidgets')."""
    r = sg.param(0.5, "r", range=(0.2, 1.0))
    scene = sg.sphere(r) | sg.box(0.5).translate((0.8, 0, 0))
    spec = build_spec(scene, size=(W, H))
    esm = assets.read("viewer.js") + "\n" + assets.read("widget.js")
    browser.goto("about:blank")
    browser.evaluate(f"""(async () => {{
      const spec = {json.dumps(spec)};
      const store = {{ spec, values: [0.5], camera_state: spec.camera, settings_state: spec.settings, frame: {{}} }};
      const handlers = {{}}, saved = [];
      const model = {{
        get: (k) => store[k], set: (k, v) => {{ store[k] = v; }}, save_changes: () => saved.push(JSON.stringify(store.values)),
        on: (ev, fn) => {{ (handlers[ev] = handlers[ev] || []).push(fn); }}, off: () => {{}},
      }};
      const url = URL.createObjectURL(new Blob([{json.dumps(esm)}], {{ type: "text/javascript" }}));
      const mod = await import(url);
      const el = document.createElement("div");
      el.id = "w";
      document.body.append(el);
      mod.default.render({{ model, el }});
      window.fake = {{ store, handlers, saved, set(k, v) {{ store[k] = v; (handlers["change:" + k] || []).forEach((f) => f()); }} }};
    }})()""")
    root = "document.getElementById('w')"
    wait_still(browser, 0, root)
    first = canvas(browser)
    # a slider moved in the view reaches the model (Python then sets r.value)
    browser.evaluate("(() => { const s = document.querySelector('input[type=range]');"
                     " s.value = '0.8'; s.dispatchEvent(new Event('input')); })()")
    assert browser.evaluate("window.fake.store.values") == [0.8]
    # a value set in Python (a model change) moves the slider and the image
    n = frames(browser, root)
    browser.evaluate("window.fake.set('values', [0.3])")
    wait_still(browser, n, root)
    assert browser.evaluate("document.querySelector('input[type=range]').value") == "0.3"
    r.value = 0.3
    small = canvas(browser)
    assert differing(first, small) > 0.05
    assert differing(small, sg.render(scene, camera_from_state(spec["camera"]), (W, H)).color) < MAX_FRACTION
    # a camera set in Python moves the view
    n = frames(browser, root)
    browser.evaluate("window.fake.set('camera_state', {...window.fake.store.camera_state, yaw: 120})")
    wait_still(browser, n, root)
    turned = canvas(browser)
    assert differing(small, turned) > 0.05
    cam = camera_from_state({**spec["camera"], "yaw": 120})
    assert differing(turned, sg.render(scene, cam, (W, H)).color) < MAX_FRACTION


def test_several_sliders_at_once_match_egl(browser, tmp_path):
    sf = load_scene_file(ROOT / "examples" / "live_params.py")
    html = save_html(sf.scene, tmp_path / "live.html", sf.camera, (W, H), **sf.settings)
    open_html(browser, html)
    n = frames(browser)
    browser.evaluate("(() => { const s = document.querySelectorAll('input[type=range]');"
                     " [['1.2', 0], ['0.6', 1], ['0.2', 2]].forEach(([v, i]) => {"
                     " s[i].value = v; s[i].dispatchEvent(new Event('input')); }); })()")
    wait_still(browser, n)
    params = {p.label: p for p in build(sf.scene, size=(W, H))[1]}
    for name, value in (("radius", 1.2), ("hole", 0.6), ("blend", 0.2)):
        params[name].value = value
    egl = sg.render(sf.scene, sf.camera, (W, H), **egl_settings(sf.scene, **sf.settings)).color
    assert differing(canvas(browser), egl) < MAX_FRACTION


@pytest.mark.slow
def test_union_kept_as_data_uploads_its_textures(browser, tmp_path):
    rng = np.random.default_rng(3)
    lamp = sg.box(0.2) | sg.sphere(0.12).translate((0, 0.15, 0))  # a small subtree: its free way is its box (the nearest by its parts)
    parts = [(lamp if i % 4 == 0 else sg.sphere(float(rng.uniform(0.1, 0.25)))).translate(
        tuple(rng.uniform(-1.5, 1.5, 3))).color(*rng.uniform(0.2, 0.9, 3)) for i in range(160)]
    scene = sg.union(*parts)
    cam = sg.OrbitCamera(distance=6.5, yaw=30, pitch=25)
    html = save_html(scene, tmp_path / "grid.html", cam, (W, H))
    text = html.read_text()
    assert "g0Cell" in text and '"uData"' in text  # the union is data (a cell grid in the data texture), not code
    assert "g0RayBox(q, gRayInv" in text and "g0RayBall(q, gRayDir" in text  # and the free way along the ray
    assert "max(enterNear, g0Enter0(qNear, gRayInv, gRayDir))" in text
    open_html(browser, html)
    assert differing(canvas(browser), sg.render(scene, cam, (W, H)).color) < MAX_FRACTION
    # key F frames the scene: the view turns to the box centre, keeps its angles, and every
    # corner of the scene box is in view (and the page still matches EGL)
    n = frames(browser)
    browser.evaluate("document.dispatchEvent(new KeyboardEvent('keydown', {key: 'f'}))")
    wait_still(browser, n)
    state = browser.evaluate("window.sdfglViewer.camera")
    lo, hi = scene.bounds
    assert state["target"] == pytest.approx(list((lo + hi) / 2)) and (state["yaw"], state["pitch"]) == (30, 25)
    framed = camera_from_state(state)
    r, u, f = framed.basis()
    for corner in np.array(np.meshgrid(*zip(lo, hi))).T.reshape(-1, 3):
        v = corner - framed.eye
        x, y = (v @ r) / (v @ f) / framed.tan_half_fov, (v @ u) / (v @ f) / framed.tan_half_fov
        assert abs(y) < 1 and abs(x) < W / H
    assert differing(canvas(browser), sg.render(scene, framed, (W, H)).color) < MAX_FRACTION
