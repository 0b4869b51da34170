"""Animation: the clock, functions over live params, keyframes, camera paths, writers, sg.animate."""
import tracemalloc

import imageio_ffmpeg
import numpy as np
import pytest
from PIL import Image

import sdfgl as sg
from sdfgl.animate.writers import GifWriter
from sdfgl.cli import main
from sdfgl.demo import demo_camera, demo_scene

from .test_parity import assert_parity


def _live_scene(t):
    """Every function of the ops table over the clock, in scalar and vector roles."""
    v = sg.param((0.2, 0.1, -0.1), "v")
    radius = sg.clamp(0.6 + 0.2 * sg.sin(t * 1.3) + 0.1 * sg.cos(t), 0.3, 0.9) + 0.05 * sg.abs(sg.tan(t * 0.1))
    k = sg.mix(0.05, 0.3, sg.smoothstep(0.0, 2.0, t)) + 0.01 * sg.step(1.0, t) + 0.01 * sg.fract(t)
    size = sg.max(sg.min(sg.mix((0.8, 0.5, 0.6), (0.5, 0.9, 0.7), sg.fract(t * 0.25)), 0.85), 0.45)
    off = v * sg.sqrt(1.0 + sg.abs(sg.sign(sg.sin(t)))) + sg.mod(t, 1.5) * sg.exp(-1.0) * sg.log(2.0)
    angle = sg.pow(2.0 + sg.floor(t), 1.5) * 10 + sg.radians(t) * 57.0
    return sg.union(sg.sphere(radius).translate(off), sg.box(size).rotate(angle, (0, 1, 0)).translate((0.7, 0, 0)),
                    k=k)


def test_functions_over_the_clock_match_the_twin_at_every_time(renderer):
    t = sg.time()
    scene = _live_scene(t)
    src = sg.compile(scene)
    assert [p for p in scene.live_params() if isinstance(p, sg.params.Time)] == [t]
    pts = np.random.default_rng(3).uniform(-1.6, 1.6, (2500, 3))
    for now in (0.0, 0.7, 1.4, 2.9, 7.3):
        t.value = now
        assert sg.compile(scene) == src  # time is a uniform: the source never changes
        assert_parity(scene, pts, renderer)


def test_functions_of_numbers_are_numbers_and_bad_arguments_are_named():
    assert sg.sin(0.5) == pytest.approx(np.sin(0.5)) and isinstance(sg.clamp(3, 0, 1), float)
    assert np.allclose(sg.mix((0, 0, 0), (2, 4, 6), 0.5), (1, 2, 3))
    assert sg.mod(-1.0, 3.0) == pytest.approx(2.0)  # GLSL's mod, not C's fmod
    with pytest.raises(sg.ParameterError, match=r"sg.sin: parameter 'x' must be a number"):
        sg.sin("x")
    with pytest.raises(sg.ParameterError, match=r"sg.clamp: takes 3 arguments, got 2"):
        sg.clamp(sg.time(), 1)


def test_a_time_that_breaks_a_node_is_refused_naming_frame_node_and_value_before_any_frame(tmp_path):
    t = sg.time()
    scene = sg.sphere(0.5 + sg.sin(t))  # radius < 0 from t ~ 3.67 s
    out = tmp_path / "clip.gif"
    with pytest.raises(sg.ParameterError, match=r"frame 37 \(t = 3\.7 s\): sphere: parameter 'radius' must be > 0"):
        sg.animate(scene, out, seconds=5, fps=10, size=(32, 24))
    assert not out.exists() and list(tmp_path.iterdir()) == []
    assert t.value == 0.0  # the check put the clock back
    with pytest.raises(sg.ParameterError, match="sphere: parameter 'radius' must be > 0"):
        t.value = 4.0


def test_keyframes_pass_through_keys_and_ease():
    t = sg.time()
    lin = sg.keyframes({0: 1.0, 2: 2.0, 3: 0.5}, time=t)
    smooth = sg.keyframes([(0, (0, 0, 0)), (1, (1, 2, 3))], ease="smooth", time=t)
    step = sg.keyframes({0: 1.0, 1: 5.0}, ease="step", time=t)
    for now, a, s, st in [(-1, 1.0, 0, 1.0), (0, 1.0, 0, 1.0), (0.5, 1.25, 0.5, 1.0), (0.25, 1.125, 0.15625, 1.0),
                          (2, 2.0, 1, 5.0), (2.5, 1.25, 1, 5.0), (3, 0.5, 1, 5.0), (9, 0.5, 1, 5.0)]:
        t.value = now
        assert lin.value == pytest.approx(a)
        assert np.allclose(smooth.value, np.array([1, 2, 3]) * s)
        assert step.value == st
    with pytest.raises(sg.ParameterError, match="key times must increase, key 1"):
        sg.keyframes([(1, 1.0), (1, 2.0)])
    with pytest.raises(sg.ParameterError, match="key 1 value .* does not match"):
        sg.keyframes([(0, 1.0), (1, (1, 2, 3))])
    with pytest.raises(sg.ParameterError, match="ease must be one of"):
        sg.keyframes({0: 1}, ease="bounce")


def test_camera_paths_pass_through_keys_and_the_turntable_loops():
    path = sg.camera_path({0: ((6, 2, 0), (0, 0, 0)), 2: {"eye": (0, 3, 6), "target": (0, 0.5, 0), "fov": 30},
                           4: ((-6, 2, 0), (0, 0, 0))})
    for tk, eye, target, fov in [(0, (6, 2, 0), (0, 0, 0), 45), (2, (0, 3, 6), (0, 0.5, 0), 30),
                                 (4, (-6, 2, 0), (0, 0, 0), 45)]:
        cam = path.camera(tk)
        assert np.allclose(cam.eye, eye) and np.allclose(cam.target, target) and cam.fov == pytest.approx(fov)
    mid = path.camera(1.0)
    assert not np.allclose(mid.eye, (3, 2.5, 3))  # a spline, not the straight chord
    tt = sg.turntable(distance=5, pitch=20, yaw=10)
    c0, c1, cq = tt.camera(0, 4), tt.camera(4, 4), tt.camera(1, 4)
    assert np.allclose(c0.eye, c1.eye) and cq.yaw == pytest.approx(100)
    framed = sg.turntable().camera(0, 1, sg.sphere(1).translate((5, 0, 0)))
    assert np.allclose(framed.target, (5, 0, 0))
    with pytest.raises(sg.ParameterError, match="turntable: parameter 'pitch'"):
        sg.turntable(pitch=95)


def test_one_program_for_all_frames_and_each_frame_is_the_render_of_its_time(tmp_path, renderer):
    t = sg.time()
    scene = sg.union(sg.sphere(sg.keyframes({0: 0.6, 0.5: 0.9}, time=t)), sg.box(0.8).translate((1.2, 0, 0)),
                     k=0.1 + 0.1 * sg.sin(t))
    path = sg.turntable(distance=5, pitch=25)
    res = sg.animate(scene, tmp_path / "f" / "%03d.png", seconds=0.5, fps=12, camera=path, size=(48, 32),
                     renderer=renderer, aa=1)
    assert res.frames == 6 and res.compiles <= 5  # the coarse pass and the image's tile programs (4 with the ground), in the first frames
    again = sg.animate(scene, tmp_path / "g", frames=3, fps=12, camera=path, size=(48, 32), renderer=renderer, aa=1)
    assert again.compiles == 0  # same source, same program
    frames = [np.asarray(Image.open(tmp_path / "f" / f"{i:03d}.png")) for i in range(6)]
    assert sorted(p.name for p in (tmp_path / "g").iterdir()) == ["frame_0000.png", "frame_0001.png",
                                                                  "frame_0002.png"]
    assert len({f.tobytes() for f in frames}) == 6  # every frame moved
    t.value = 4 / 12
    direct = sg.render(scene, path.camera(4 / 12, 0.5, scene), (48, 32), aa=1)
    assert np.array_equal(frames[4], direct.color)


def test_mp4_webm_and_gif_of_the_demo_turntable_read_back(tmp_path):
    scene, cam = demo_scene(), demo_camera()
    tt = sg.turntable(distance=cam.distance, pitch=cam.pitch, target=cam.target)

    def rendered(i, fps, n, size):
        return sg.render(scene, tt.camera(i / fps, n / fps, scene), size, ground=True).color.astype(float)
    for name in ("spin.mp4", "spin.webm"):
        res = sg.animate(scene, tmp_path / name, frames=12, fps=24, camera=tt, size=(128, 72), ground=True)
        assert res.compiles <= 5  # the coarse pass and the image's tile programs (4 with the ground), in the first frames
        n, secs = imageio_ffmpeg.count_frames_and_secs(str(tmp_path / name))
        reader = imageio_ffmpeg.read_frames(str(tmp_path / name))
        meta = next(reader)
        frames = [np.frombuffer(f, np.uint8).reshape(72, 128, 3) for f in reader]
        assert n == 12 == len(frames) and meta["size"] == (128, 72) and meta["fps"] == pytest.approx(24)
        assert secs == pytest.approx(0.5, abs=0.05)
        for i in (0, 7):  # lossy, but the picture of that frame
            assert np.abs(frames[i] - rendered(i, 24, 12, (128, 72))).mean() < 6
    sg.animate(scene, tmp_path / "spin.gif", frames=6, fps=10, camera=tt, size=(96, 54), ground=True)
    gif = Image.open(tmp_path / "spin.gif")
    assert gif.n_frames == 6 and gif.size == (96, 54) and gif.info["loop"] == 0 and gif.info["duration"] == 100
    for i in (0, 5):  # every frame decodes to its own picture (own palette, dithered)
        gif.seek(i)
        assert np.abs(np.asarray(gif.convert("RGB"), float) - rendered(i, 10, 6, (96, 54))).mean() < 6
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temporary files left


def test_gif_streams_to_disk_and_memory_stays_flat(tmp_path, renderer):
    w = GifWriter(tmp_path / "s.gif", (64, 48), 10)
    rng = np.random.default_rng(0)
    sizes = []
    for _ in range(3):
        w.append(rng.integers(0, 255, (48, 64, 3), dtype=np.uint8))
        w._fp.flush()
        sizes.append(w._tmp.stat().st_size)
    w.close()
    assert sizes[0] < sizes[1] < sizes[2]  # each frame is on disk as it arrives
    assert Image.open(tmp_path / "s.gif").n_frames == 3

    scene = sg.sphere(0.8 + 0.1 * sg.sin(sg.time() * 3))
    peaks = []
    for n in (4, 24):
        tracemalloc.start()
        sg.animate(scene, tmp_path / f"m{n}.gif", frames=n, fps=10, size=(96, 64), renderer=renderer)
        peaks.append(tracemalloc.get_traced_memory()[1])
        tracemalloc.stop()
    assert peaks[1] < 1.5 * peaks[0] + 200_000, peaks  # 6x the frames, not 6x the memory


def test_a_failing_frame_leaves_no_file(tmp_path):
    def camera(t):
        if t > 0.25:
            raise sg.ParameterError("camera function: no camera after 0.25 s")
        return sg.OrbitCamera(distance=4)
    with pytest.raises(sg.ParameterError, match="no camera after"):
        sg.animate(sg.sphere(1), tmp_path / "x.mp4", frames=2, fps=2, camera=camera, size=(32, 32))
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(sg.ParameterError, match="cannot tell the format"):
        sg.animate(sg.sphere(1), tmp_path / "x.avi", frames=2, size=(32, 32))


def test_cli_animate_scene_file_turntable(tmp_path, capsys):
    f = tmp_path / "pulse.py"
    f.write_text("import sdfgl as sg\nt = sg.time()\nscene = sg.torus(0.8 + 0.1 * sg.sin(6.28 * t), 0.25)\n"
                 "camera = sg.OrbitCamera(distance=4, pitch=35)\n")
    out = tmp_path / "pulse.mp4"
    assert main(["animate", str(f), "-o", str(out), "--seconds", "0.5", "--fps", "16", "--size", "64x48",
                 "--turntable", "--no-progress"]) == 0
    assert "8 frames 64x48" in capsys.readouterr().out
    assert imageio_ffmpeg.count_frames_and_secs(str(out))[0] == 8


def test_function_edge_cases_and_bad_keys_give_values_or_named_errors():
    assert sg.smoothstep(1.0, 1.0, 2.0) == 1.0 and sg.smoothstep(1.0, 1.0, 0.5) == 0.0  # no ZeroDivisionError
    assert np.isnan(sg.mod(1.0, 0.0)) and float(sg.mod(sg.param(-1.0), 3.0)) == pytest.approx(2.0)
    assert float(sg.clamp(x=sg.param(2.0), lo=0.0, hi=1.0)) == 1.0  # parameters are named as documented
    with pytest.raises(sg.ParameterError, match=r"sg.mix: parameter 't' must be a number"):
        sg.mix(0.0, 1.0, t="half")
    with pytest.raises(sg.ParameterError, match=r"keyframes: 'keys' must be a dict \{seconds: value\}"):
        sg.keyframes(None)
    with pytest.raises(sg.ParameterError, match=r"camera_path: parameter 'fov' must be > 0"):
        sg.camera_path({0: ((5, 0, 0), (0, 0, 0))}, fov=-1)
