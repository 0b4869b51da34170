"""Live control: OSC over loopback UDP and MIDI control changes move live parameters, without recompiling."""
import json
import os
import socket
import threading
import time

import numpy as np
import pytest

import sdfgl as sg
from sdfgl import extras
from sdfgl.extras import MissingExtraError
from sdfgl.live import Binding, LiveBindingError, LiveControl, LiveInputError, load_bindings, send_osc
from sdfgl.render import default_renderer

mido = pytest.importorskip("mido")
pytest.importorskip("pythonosc")


def cc(control, value, channel=0):
    return mido.Message("control_change", control=control, value=value, channel=channel)


def wait_until(pred, timeout=5.0):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if pred():
            return True
        time.sleep(0.01)
    return pred()


def radius_scene():
    r = sg.param(0.5, name="radius", range=(0.2, 1.2))
    return r, sg.sphere(r).color(0.9, 0.3, 0.2)


# -- OSC over loopback UDP ------------------------------------------------------------------
def test_osc_message_moves_the_param_and_the_next_render_shows_it_without_a_recompile():
    r, scene = radius_scene()
    cam = sg.OrbitCamera(distance=4, yaw=0, pitch=0)
    sg.render(scene, camera=cam, size=(64, 64), shadows=False, ao=False)
    before = sg.render(scene, camera=cam, size=(64, 64), shadows=False, ao=False).color  # a second frame links the other tile programs
    programs = default_renderer().programs
    compiles = programs.compiles
    with sg.live_control(scene, osc=0) as ctl:
        assert ctl.osc_port and ctl.osc_port > 0
        ctl.bind_osc("/radius", r)
        send_osc("/radius", 1.0, port=ctl.osc_port)
        assert wait_until(lambda: r.value == 1.0), r.value
    after = sg.render(scene, camera=cam, size=(64, 64), shadows=False, ao=False).color
    assert programs.compiles == compiles  # a uniform changed, not the program
    grew = np.abs(after.astype(int) - before.astype(int)).max(axis=2) > 30
    assert grew.sum() > 200                # the sphere is bigger on the picture


def test_a_burst_of_osc_while_rendering_ends_at_the_last_value_with_one_program():
    r, scene = radius_scene()
    cam = sg.OrbitCamera(distance=4, yaw=0, pitch=0)
    for _ in range(2):  # a second frame links the other tile programs
        sg.render(scene, camera=cam, size=(32, 32), shadows=False, ao=False)
    programs = default_renderer().programs
    compiles = programs.compiles
    values = [round(0.2 + i / 100, 2) for i in range(101)]
    with sg.live_control(scene, osc=0) as ctl:
        ctl.bind_osc("/radius", r)
        sender = threading.Thread(target=lambda: [send_osc("/radius", v, port=ctl.osc_port) for v in values])
        sender.start()
        while sender.is_alive():   # renders read the value while the server thread sets it
            sg.render(scene, camera=cam, size=(32, 32), shadows=False, ao=False)
        sender.join()
        assert wait_until(lambda: r.value == values[-1]), r.value
        assert ctl.received == len(values) and ctl.last_error == ""
    assert programs.compiles == compiles


def test_osc_server_thread_stops_and_frees_its_port():
    r, scene = radius_scene()
    ctl = LiveControl(scene, osc=0).start()
    port = ctl.osc_port
    threads = [t for t in threading.enumerate() if t.name in ("sdfgl-osc", "sdfgl-live-smooth")]
    assert len(threads) == 2
    ctl.stop()
    assert all(not t.is_alive() for t in threads)
    assert ctl.osc_port is None
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:  # the port is free again
        s.bind(("127.0.0.1", port))


def test_osc_port_in_use_is_a_clear_error():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
        with pytest.raises(LiveInputError, match=f"OSC: cannot listen on 127.0.0.1:{port}"):
            LiveControl(osc=port).start()


def test_osc_values_clamp_normalize_and_fill_vectors():
    r, scene = radius_scene()
    off = sg.param((0.0, 0.0, 0.0), name="offset", range=(-1, 1))
    ctl = LiveControl(scene.translate(off))
    ctl.bind_osc("/radius", r)
    ctl.handle_osc("/radius", 7.0)
    assert r.value == 1.2                      # clamped to the param's range
    ctl.handle_osc("/radius", -3)
    assert r.value == 0.2
    ctl.bind_osc("/knob", "radius", normalized=True)
    ctl.handle_osc("/knob", 0.5)
    assert r.value == pytest.approx(0.7)       # 0..1 spans the range
    ctl.bind_osc("/offset", off)
    ctl.handle_osc("/offset", 0.5, 5.0, -0.25)
    assert off.value.tolist() == [0.5, 1.0, -0.25]
    ctl.bind_osc("/offset/z", off, component=2, range=(0.0, 0.5))
    ctl.handle_osc("/offset/z", 0.9)
    assert off.value.tolist() == [0.5, 1.0, 0.5]
    ctl.handle_osc("/radius", "big")           # does not fit: the value stays, the error is kept
    assert r.value == pytest.approx(0.7) and "/radius" in ctl.last_error


# -- MIDI --------------------------------------------------------------------------------------
def test_midi_cc_spans_the_range_on_its_channel():
    r, scene = radius_scene()
    ctl = LiveControl(scene)
    ctl.bind_midi(cc=21, param=r, channel=2)
    ctl.handle_midi(cc(21, 127, channel=2))
    assert r.value == pytest.approx(1.2)
    ctl.handle_midi(cc(21, 0, channel=3))     # another channel: not this binding
    assert r.value == pytest.approx(1.2)
    ctl.handle_midi(cc(21, 0, channel=2))
    assert r.value == pytest.approx(0.2)
    ctl.handle_midi(cc(22, 127, channel=2))   # another control
    assert r.value == pytest.approx(0.2)
    ctl.bind_midi(cc=7, param=r, range=(0.4, 0.6))
    ctl.handle_midi(cc(7, 64, channel=9))      # any channel
    assert r.value == pytest.approx(0.4 + 0.2 * 64 / 127)
    assert ctl.received == 3


def test_midi_cc_drives_one_component_of_a_vector():
    off = sg.param((0.0, 0.0, 0.0), name="offset", range=(-2, 2))
    ctl = LiveControl(sg.sphere(0.5).translate(off))
    with pytest.raises(LiveBindingError, match="give component=0, 1 or 2"):
        ctl.bind_midi(1, off)
    ctl.bind_midi(1, off, component=1)
    ctl.bind_midi(2, off, component=2)
    ctl.handle_midi(cc(1, 127))
    ctl.handle_midi(cc(2, 0))
    assert off.value.tolist() == [0.0, 2.0, -2.0]


def test_midi_learn_binds_the_next_control_moved():
    r, scene = radius_scene()
    ctl = LiveControl(scene)
    ctl.learn(r)
    assert ctl.learning[0] == "radius"
    ctl.handle_midi(mido.Message("note_on", note=60, velocity=100))  # not a control: still learning
    assert ctl.learning is not None and ctl.bindings == []
    ctl.handle_midi(cc(74, 127, channel=5))
    assert ctl.learning is None
    assert ctl.bindings == [Binding("radius", cc=74, channel=5)]
    assert r.value == pytest.approx(1.2)          # the learning message moves it too
    ctl.handle_midi(cc(74, 0, channel=5))
    assert r.value == pytest.approx(0.2)
    ctl.learn("radius")                            # OSC can be learned the same way
    ctl.handle_osc("/fader/1", 0.9)
    assert ctl.describe() == ["CC74/ch5 -> radius", "/fader/1 -> radius"] and r.value == 0.9


def test_learn_refuses_a_param_a_knob_cannot_span():
    free = sg.param(1.0, name="free")
    ctl = LiveControl(sg.sphere(free))
    with pytest.raises(LiveBindingError, match="free has no finite one: give the binding a range"):
        ctl.learn(free)
    ctl.learn(free, range=(0.5, 1.5))
    ctl.handle_midi(cc(3, 127))
    assert free.value == 1.5


def _virtual_midi_available() -> bool:
    if not os.path.exists("/dev/snd/seq"):
        return False
    try:
        mido.open_output("sdfgl-probe", virtual=True).close()
    except Exception:  # noqa: BLE001 - no ALSA sequencer or no rtmidi backend
        return False
    return True


@pytest.mark.skipif(not _virtual_midi_available(), reason="no ALSA sequencer (/dev/snd/seq) for a virtual MIDI port")
def test_midi_through_a_virtual_port():
    r, scene = radius_scene()
    with LiveControl(scene, midi="sdfgl-test-in", midi_virtual=True) as ctl:
        ctl.bind_midi(cc=21, param=r)
        with mido.open_output("sdfgl-test-in") as out:
            out.send(cc(21, 127))
            assert wait_until(lambda: r.value == pytest.approx(1.2))


def test_an_unknown_midi_port_names_the_ports_there_are():
    pytest.importorskip("rtmidi")
    with pytest.raises(LiveInputError, match="no MIDI input port 'no such port'; this system has"):
        LiveControl(midi="no such port").start()


# -- values the nodes refuse, deferred mode, smoothing -------------------------------------
def test_a_value_a_node_refuses_is_dropped_and_reported():
    r = sg.param(0.5, name="radius", range=(-1.0, 1.0))
    ctl = LiveControl(sg.sphere(r))
    ctl.bind_midi(1, r)
    ctl.handle_midi(cc(1, 0))                    # -1: a sphere's radius must be > 0
    assert r.value == 0.5 and "radius" in ctl.last_error


def test_deferred_values_wait_for_apply_pending_and_wake_the_owner():
    r, scene = radius_scene()
    woken = []
    ctl = LiveControl(scene, deferred=True, wake=lambda: woken.append(1))
    ctl.bind_osc("/radius", r)
    ctl.handle_osc("/radius", 0.8)
    ctl.handle_osc("/radius", 0.9)               # the newest value wins
    assert r.value == 0.5 and woken
    assert ctl.apply_pending() == [r] and r.value == 0.9
    assert ctl.apply_pending() == []


def test_smoothing_eases_towards_the_value():
    r, scene = radius_scene()
    with LiveControl(scene) as ctl:
        ctl.bind_osc("/radius", r, smooth=0.05)
        ctl.handle_osc("/radius", 1.2)
        assert r.value == 0.5                    # not at once
        assert wait_until(lambda: 0.5 < r.value < 1.2, timeout=2)
        assert wait_until(lambda: r.value == 1.2, timeout=3)


# -- bindings files --------------------------------------------------------------------------
def test_bindings_file_round_trip(tmp_path):
    r, scene = radius_scene()
    off = sg.param((0.0, 0.0, 0.0), name="offset", range=(-1, 1))
    ctl = LiveControl(scene.translate(off))
    ctl.bind_midi(21, r, smooth=0.1)
    ctl.bind_osc("/offset/y", off, component=1, normalized=True)
    path = ctl.save(tmp_path / "live.json")
    doc = json.loads(path.read_text())
    assert doc["version"] == 1 and doc["bindings"][0] == {"param": "radius", "cc": 21, "channel": None, "smooth": 0.1}
    again = LiveControl(scene.translate(off))
    assert again.load(path) == ctl.bindings == load_bindings(path)
    again.handle_osc("/offset/y", 1.0)
    assert off.value.tolist() == [0.0, 1.0, 0.0]


@pytest.mark.parametrize("doc, message", [
    ("{not json", r"not JSON: .* at line 1"),
    ([], r"expected a JSON object with 'version' and 'bindings'"),
    ({"version": 2, "bindings": []}, r"version: expected 1, got 2"),
    ({"version": 1, "bindings": {}}, r"bindings: expected a list"),
    ({"version": 1, "bindings": [], "extra": 1}, r"unknown key 'extra'"),
    ({"version": 1, "bindings": [{"param": "radius", "cc": 1}, {"param": "radius", "cc": 200}]},
     r"bindings\[1\]\.cc: must be a MIDI control number, an integer 0\.\.127, got 200"),
    ({"version": 1, "bindings": [{"param": "radius"}]}, r"bindings\[0\]: give exactly one source"),
    ({"version": 1, "bindings": [{"param": "radius", "cc": 1, "osc": "/r"}]}, r"bindings\[0\]: give exactly one"),
    ({"version": 1, "bindings": [{"param": "radius", "osc": "radius"}]}, r"bindings\[0\]\.osc: must be an OSC address"),
    ({"version": 1, "bindings": [{"param": "radius", "cc": 1, "channel": 16}]}, r"bindings\[0\]\.channel: must be"),
    ({"version": 1, "bindings": [{"param": "radius", "cc": 1, "range": [2, 1]}]}, r"bindings\[0\]\.range: must be"),
    ({"version": 1, "bindings": [{"param": "radius", "cc": 1, "smooth": -1}]}, r"bindings\[0\]\.smooth: must be"),
    ({"version": 1, "bindings": [{"param": "radius", "cc": 1, "knob": 1}]}, r"bindings\[0\]: unknown key 'knob'"),
    ({"version": 1, "bindings": [{"cc": 1}]}, r"bindings\[0\]: missing 'param'"),
    ({"version": 1, "bindings": [{"param": "radius", "cc": 1}, {"param": "size", "cc": 2}]},
     r"bindings\[1\]: no live parameter named 'size' to bind \(the scene has: radius\)"),
])
def test_bad_bindings_files_name_the_file_and_the_json_path(tmp_path, doc, message):
    path = tmp_path / "live.json"
    path.write_text(doc if isinstance(doc, str) else json.dumps(doc))
    _, scene = radius_scene()
    with pytest.raises(LiveBindingError, match=message) as err:
        LiveControl(scene).load(path)
    assert str(err.value).startswith(str(path))


def test_a_missing_bindings_file_is_a_clear_error(tmp_path):
    with pytest.raises(LiveBindingError, match="cannot read the bindings file"):
        load_bindings(tmp_path / "nope.json")


def test_unnamed_params_bind_but_cannot_be_saved(tmp_path):
    p = sg.param(0.5, range=(0.1, 1))
    ctl = LiveControl(sg.sphere(p))
    ctl.bind_midi(1, p)
    ctl.handle_midi(cc(1, 127))
    assert p.value == 1.0
    with pytest.raises(LiveBindingError, match="give it a name"):
        ctl.save(tmp_path / "live.json")


def test_missing_extra_names_the_pip_line(monkeypatch):
    monkeypatch.setattr(extras, "installed", lambda module: module != "pythonosc")
    with pytest.raises(MissingExtraError, match=r"pip install 'sdfgl\[live\]'"):
        LiveControl(osc=0).start()
