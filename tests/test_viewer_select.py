"""The scene tree's "select" view tints where the selected node is the surface hit, for any node:
members of a union kept as data (a grid) included. Headless: the same GLSL the window draws."""
import numpy as np
import pytest

import sdfgl as sg
from sdfgl.compiler.generate import generate
from sdfgl.gl.targets import Targets
from sdfgl.render import default_renderer
from sdfgl.uniforms import camera_uniforms, scene_uniforms
from sdfgl.settings import Settings


def select_image(scene, node, cam, size, **settings) -> np.ndarray:
    """The select view of ``node`` rendered headless (RGB int16, rows top first)."""
    src = generate(scene, Settings.build(debug="select", shadows=False, ao=False, **settings), highlight=node)
    r = default_renderer()

    def draw():  # on the renderer's GL thread, which owns its context
        prog, vao = r.programs.entry(src)
        t = Targets(r.ctx, size, ("color",))
        camera_uniforms(prog, cam, size, np.zeros(3))
        scene_uniforms(prog, src, scene, np.zeros(3), r.data)
        t.fbo.use()
        r.ctx.viewport = (0, 0, *size)
        vao.render(vertices=3)
        out = t.read("color")
        t.release()
        return out

    return r.run(draw)[..., :3].astype(np.int16), bool(src.data)


def tinted(img: np.ndarray) -> np.ndarray:
    return img[..., 0] > img[..., 2] + 60


def test_select_tints_grid_members_like_the_same_scene_written_as_code():
    rng = np.random.default_rng(3)
    members = [sg.sphere(0.2 + 0.1 * rng.random()).translate(tuple(rng.uniform(-1.2, 1.2, 3))) for _ in range(40)]
    scene = sg.union(*members, sg.box(0.6).translate((0, -1.7, 0)))
    cam = sg.OrbitCamera(distance=6, yaw=20, pitch=15)
    size = (96, 72)
    for node in (members[5], members[5].children[0], scene, scene.children[-1]):
        data_img, as_data = select_image(scene, node, cam, size, grid=True)
        code_img, code_data = select_image(scene, node, cam, size, grid=False)
        assert as_data and not code_data  # the members really are data in the first image
        got, want = tinted(data_img), tinted(code_img)
        assert want.sum() > 20, node.label()
        iou = (got & want).sum() / (got | want).sum()
        assert iou > 0.95, (node.label(), iou)
    # one member tints a part of the union, not all of it
    one, _ = select_image(scene, members[5], cam, size, grid=True)
    whole, _ = select_image(scene, scene, cam, size, grid=True)
    assert 0 < tinted(one).sum() < 0.5 * tinted(whole).sum()


if __name__ == "__main__":  # pragma: no cover
    pytest.main([__file__])
