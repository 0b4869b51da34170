"""The PNG encoder: every supported layout decodes (by Pillow) to the same pixels."""
import io

import numpy as np
import pytest
from PIL import Image

import sdfgl as sg
from sdfgl.outputs import save_outputs, write_image
from sdfgl.png import can_encode, encode_png

rng = np.random.default_rng(7)


@pytest.mark.parametrize("shape,dtype", [((5, 7), np.uint8), ((5, 7, 1), np.uint8), ((6, 3, 2), np.uint8),
                                         ((9, 13, 3), np.uint8), ((4, 11, 4), np.uint8), ((1, 1, 3), np.uint8),
                                         ((8, 5), np.uint16), ((3, 4, 1), np.uint16)],
                         ids=lambda v: str(v))
def test_round_trips_through_pillow(shape, dtype):
    a = rng.integers(0, np.iinfo(dtype).max, size=shape, endpoint=True).astype(dtype)
    back = np.asarray(Image.open(io.BytesIO(encode_png(a))))
    assert back.shape == (a.shape[:2] if a.ndim == 3 and a.shape[2] == 1 else a.shape)
    assert np.array_equal(back.reshape(a.shape).astype(dtype), a)


def test_non_contiguous_input_is_encoded_as_seen():
    a = rng.integers(0, 255, size=(10, 12, 4), endpoint=True).astype(np.uint8)
    view = a[::-2, 1::3, :3]
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(encode_png(view)))), view)


@pytest.mark.parametrize("a", [np.zeros((4, 4), np.float32), np.zeros((4, 4, 5), np.uint8), np.zeros((4, 4, 3), np.uint16), np.zeros((0, 4, 3), np.uint8),
                               np.zeros(4, np.uint8)], ids=["float", "5-channel", "16-bit RGB", "empty", "1-d"])
def test_refuses_what_png_cannot_hold(a):
    assert not can_encode(a)
    with pytest.raises(ValueError, match="PNG: an image must be"):
        encode_png(a)


def test_render_outputs_round_trip(tmp_path):
    res = sg.render(sg.sphere(1) | sg.box(0.5).translate((1, 0, 0)), size=(33, 21),
                    outputs=("color", "depth", "normal", "steps"))
    paths = save_outputs(res, tmp_path / "r.png", ("color", "depth", "normal", "steps"))
    assert np.array_equal(np.asarray(Image.open(paths[0])), res.color)
    assert np.array_equal(np.asarray(Image.open(tmp_path / "r.steps.png")), np.clip(res.steps, 0, 65535))
    assert Image.open(tmp_path / "r.depth.png").mode.startswith("I;16")


def test_options_still_go_to_pillow(tmp_path):
    a = rng.integers(0, 255, size=(16, 16, 3), endpoint=True).astype(np.uint8)
    fast, small = write_image(a, tmp_path / "a.png"), write_image(a, tmp_path / "b.png", compress_level=9)
    assert np.array_equal(np.asarray(Image.open(fast)), np.asarray(Image.open(small)))
    assert fast.read_bytes() != small.read_bytes()
