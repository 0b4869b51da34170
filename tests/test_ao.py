"""Ambient occlusion's open test (shaders/stages/ao.glsl): where the farthest sample proves
every sample clear of the surface, the other four are not taken, and the image is the one all
five samples give."""
import dataclasses

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.bench import FrameTimer, Variant
from sdfgl.demo import demo_camera, demo_scene

SIZE = (160, 120)


def _image(renderer: sg.Renderer, scene: sg.Node, cam: sg.Camera, open_test: bool) -> np.ndarray:
    """The frame of ``scene`` with soft shadows, AO and the ground, with or without the open test."""
    def without(src):
        return dataclasses.replace(src, text=src.text.replace("#define AO_LIPSCHITZ", "// AO_LIPSCHITZ"))
    v = Variant("ao", str(open_test), {"shadows": "soft", "ao": True, "ground": True}, scene, cam,
                source=None if open_test else without)
    timer = FrameTimer(renderer, SIZE, read_back=True)
    timer.prepare(v)
    timer.draw(v)
    return np.frombuffer(v.result["_image"], np.uint8).reshape(SIZE[1], SIZE[0], 3).astype(int)


@pytest.mark.parametrize("make", [lambda: (demo_scene(), demo_camera()),
                                  lambda: (sg.box(1) - sg.box(0.8).translate((0.3, 0.3, 0.3)),
                                           sg.OrbitCamera(distance=4, yaw=40, pitch=35))],
                         ids=["demo", "corner"])
def test_open_test_keeps_the_image(renderer, make):
    scene, cam = make()
    with_test, full = _image(renderer, scene, cam, True), _image(renderer, scene, cam, False)
    assert np.abs(with_test - full).max() <= 1  # at most one 8-bit level, anywhere
    no_ao = renderer.render(scene, cam, SIZE, shadows="soft", ao=False, ground=True).color.astype(int)
    assert np.mean(np.abs(no_ao - full).max(axis=-1) > 8) > 0.005  # the scenes' AO shows: the test has work


def test_open_test_only_where_the_field_is_a_bound():
    assert "#define AO_LIPSCHITZ 1.0" in sg.compile(sg.sphere(1), ao=True)
    assert "AO_LIPSCHITZ" not in sg.compile(sg.sphere(1), ao=False)
    implicit = sg.implicit("x*x + y*y + z*z - 1", bounds=((-1, -1, -1), (1, 1, 1)))
    src = sg.compile(implicit, ao=True)
    assert "#define AO\n" in src and "#define AO_LIPSCHITZ" not in src
