"""Raster meshes in the viewer (``sdfgl view --mesh``): drawn by the raster pass of
``sg.render(..., meshes=...)`` and composited with the scene by depth, in a real window on Xvfb."""
import numpy as np
import pytest
import trimesh
from PIL import Image

from sdfgl import xdisplay

from .xserver import Driver, start_xvfb

pytestmark = pytest.mark.window

SCENE = """import sdfgl as sg
scene = sg.sphere(0.8).color(0.9, 0.3, 0.2)
camera = sg.OrbitCamera(distance=5, yaw=30, pitch=20)
settings = {'shadows': False, 'ao': False}
"""
MESH_COLOR = "#20c040"


@pytest.fixture(scope="module")
def display():
    proc, name = start_xvfb()
    yield name
    xdisplay.stop_xvfb(proc)


@pytest.mark.slow
def test_a_mesh_in_the_viewer_matches_render_with_the_mesh(display, tmp_path):
    import sdfgl as sg
    scene = tmp_path / "scene.py"
    scene.write_text(SCENE)
    part = tmp_path / "part.stl"
    trimesh.creation.box((0.8, 0.8, 0.8)).apply_translation((0.9, 0.2, 0.3)).export(str(part))
    drv = Driver(display, tmp_path / "state.json")
    proc = drv.launch(str(scene), "--mesh", str(part), "--mesh-color", MESH_COLOR, "--size", "320x240",
                      "--screenshot-dir", str(tmp_path / "shots"), "--max-samples", "4")
    try:
        drv.wait_for(lambda s: s["frames"] > 0 and s["error"] == "", timeout=90.0, what="the first frame")
        drv.wait_for(lambda s: s["samples"] >= 4 and not s["moving"], timeout=90.0, what="refinement")
        drv.key("p")
        st = drv.wait_for(lambda s: len(s["screenshots"]) == 1, what="a screenshot")
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.wait(10)
    shot = np.asarray(Image.open(st["screenshots"][0]).convert("RGB"), dtype=np.int16)
    ns: dict = {}
    exec(SCENE, ns)  # noqa: S102 - the test's own scene text
    cam = sg.OrbitCamera(target=tuple(st["target"]), distance=st["distance"], yaw=st["yaw"], pitch=st["pitch"])
    mesh = sg.raster(str(part), color=MESH_COLOR)
    want = sg.render(ns["scene"], cam, (320, 240), meshes=[mesh], aa=2, **ns["settings"]).color.astype(np.int16)
    without = sg.render(ns["scene"], cam, (320, 240), aa=2, **ns["settings"]).color.astype(np.int16)
    mesh_px = np.abs(want - without).sum(-1) > 60  # where the mesh shows in the headless frame
    assert mesh_px.mean() > 0.03
    greenish = lambda img: (img[..., 1] > img[..., 0] + 40) & (img[..., 1] > img[..., 2] + 20)  # noqa: E731
    assert greenish(shot)[mesh_px].mean() > 0.9, "the window does not show the mesh where render() does"
    assert np.abs(shot - want).mean() < 4.0
