"""``sdfgl view``: an interactive window on a scene file (reloaded when saved) or the demo."""
from __future__ import annotations

import argparse
import math
from typing import Any

from ..scenefile_process import DEFAULT_TIMEOUT_S, SceneFileLoader

from .common import (SCENE_HELP, add_camera_arguments, add_mesh_arguments, add_scene_arguments, add_settings_arguments,
                     camera_flags_given, camera_from_args, image_size, load_scene_args, meshes_from_args,
                     render_settings, settings_overrides)


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl view`` (the viewer's key list is imported only when its help can show)."""
    keys = ""
    if command in (None, "view"):
        from ..viewer import KEYS_HELP
        keys = "keys:\n" + KEYS_HELP
    v = sub.add_parser("view", help="open an interactive window on a scene file (reloaded when saved)",
                       formatter_class=argparse.RawDescriptionHelpFormatter, epilog=keys)
    add_scene_arguments(v, "view the built-in showcase scene", SCENE_HELP + " (default: the demo)")
    v.add_argument("--size", type=image_size, default=(960, 540), help="window size WIDTHxHEIGHT (default 960x540)")
    v.add_argument("--target-ms", type=float, default=50.0,
                   help="frame time to hold while the camera moves, by lowering the resolution (default 50)")
    v.add_argument("--no-adaptive", action="store_true", help="always render at full resolution")
    v.add_argument("--max-samples", type=int, default=16, help="jittered samples accumulated when idle (16)")
    v.add_argument("--screenshot-dir", default=".", help="where P saves screenshots (default: here)")
    v.add_argument("--state-file", help="keep a JSON file with the view's state up to date (for scripts)")
    v.add_argument("--load-timeout", type=positive_seconds, default=DEFAULT_TIMEOUT_S, metavar="SECONDS",
                   help="stop loading the scene file after this long, at the start (then exit) and on each "
                        f"reload (then keep the last scene) (default {DEFAULT_TIMEOUT_S:g})")
    v.add_argument("--panel", action=argparse.BooleanOptionalAction, default=None,
                   help="open with the side panel shown / hidden (default: shown if the window is >= 800 wide)")
    add_mesh_arguments(v)
    live = v.add_argument_group("live control (needs pip install 'sdfgl[live]')")
    live.add_argument("--osc", type=port_number, metavar="PORT",
                      help="receive OSC messages on this UDP port (bound as --bindings says)")
    live.add_argument("--osc-host", default="127.0.0.1",
                      help="the address OSC listens on (default 127.0.0.1; 0.0.0.0 for other machines)")
    live.add_argument("--midi", metavar="PORT_NAME",
                      help="read MIDI control changes from this input port ('' for the first one)")
    live.add_argument("--midi-virtual", action="store_true",
                      help="open --midi as a new virtual port other programs connect to")
    live.add_argument("--bindings", metavar="FILE",
                      help="a JSON bindings file (MIDI CC / OSC address -> parameter); the panel's "
                           "'save bindings' writes it back")
    add_camera_arguments(v)
    add_settings_arguments(v)
    v.set_defaults(func=run)


def positive_seconds(text: str) -> float:
    """A number of seconds > 0 (argparse type)."""
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds, got {text!r}") from None
    if not (math.isfinite(x) and x > 0):
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0, got {text!r}")
    return x


def port_number(text: str) -> int:
    """A UDP port 0..65535 (argparse type; 0 picks a free one)."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a port number, got {text!r}") from None
    if not 0 <= n <= 65535:
        raise argparse.ArgumentTypeError(f"expected a port number 0..65535, got {text!r}")
    return n


def live_options(a: argparse.Namespace) -> dict[str, Any]:
    """The Viewer's ``live`` and ``bindings`` arguments from --osc, --midi and --bindings (none: {})."""
    if a.osc is None and a.midi is None and a.bindings is None and not a.midi_virtual:
        return {}
    from ..extras import require_extra
    from ..live import LiveControl
    modules = (("pythonosc",) if a.osc is not None else ()) + (("mido", "rtmidi") if a.midi is not None
                                                                or a.midi_virtual else ())
    if modules:
        require_extra("live", *modules, purpose="live control (--osc, --midi)")
    midi = a.midi if a.midi is not None else ("sdfgl" if a.midi_virtual else None)
    control = LiveControl(osc=a.osc, osc_host=a.osc_host, midi=midi, midi_virtual=a.midi_virtual, deferred=True)
    return {"live": control, "bindings": a.bindings}


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl view`` until the window closes."""
    from ..viewer import Viewer
    common = dict(size=a.size, target_ms=a.target_ms, adaptive=not a.no_adaptive, max_samples=a.max_samples,
                  state_file=a.state_file, screenshot_dir=a.screenshot_dir, panel=a.panel, meshes=meshes_from_args(a),
                  **live_options(a))
    if a.scene is None or a.demo:
        sf = load_scene_args(a)
        v = Viewer(sf.scene, camera_from_args(a, sf.scene, sf.camera), **common, **render_settings(a, sf))
    else:
        camera = None
        if camera_flags_given(a):
            loader = SceneFileLoader(a.load_timeout)
            try:
                sf = loader.wait(a.scene)  # the file is run in a child process, as the window runs it
            finally:
                loader.close()
            camera = camera_from_args(a, sf.scene, sf.camera)
        v = Viewer(camera=camera, path=a.scene, load_timeout=a.load_timeout, **common, **settings_overrides(a))
    v.run()
    return 0
