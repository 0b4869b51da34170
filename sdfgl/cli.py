"""Command line: ``sdfgl render | shader | view | html | bench``."""
from __future__ import annotations

import argparse
import sys
from typing import Sequence

from .errors import SdfglError


def _size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size must look like 800x600, got {text!r}") from None
    return w, h


def _shadows(text: str) -> object:
    if text not in ("off", "hard", "soft"):
        raise argparse.ArgumentTypeError(f"shadows must be off, hard or soft, got {text!r}")
    return False if text == "off" else text


def _add_settings(p: argparse.ArgumentParser) -> None:
    p.add_argument("--aa", type=int, default=1, help="samples per pixel side, 1..4 (default 1)")
    p.add_argument("--shadows", type=_shadows, default="soft", help="off, hard or soft (default soft)")
    p.add_argument("--no-ao", dest="ao", action="store_false", help="turn ambient occlusion off")
    p.add_argument("--ground", action="store_true", help="add an analytic ground plane under the scene")
    p.add_argument("--method", default="enhanced", help="marching method: sphere, relaxed, enhanced (default), newton, forward_newton, reference")
    p.add_argument("--max-steps", type=int, default=256, help="step limit per primary ray (default 256)")


CLI_DEFAULTS = {"aa": 1, "shadows": "soft", "ao": True, "ground": False, "method": "enhanced", "max_steps": 256}


def _overrides(a: argparse.Namespace) -> dict[str, object]:
    """The settings given on the command line (those that differ from the defaults)."""
    given = {"aa": a.aa, "shadows": a.shadows, "ao": a.ao, "ground": a.ground, "method": a.method,
             "max_steps": a.max_steps}
    return {k: v for k, v in given.items() if v != CLI_DEFAULTS[k]}


def _settings(a: argparse.Namespace) -> dict[str, object]:
    """Defaults, then the scene file's own 'settings', then what the command line gave."""
    return {**CLI_DEFAULTS, **getattr(a, "file_settings", {}), **_overrides(a)}


def _load(a: argparse.Namespace):  # -> tuple[Node, Camera | None]
    from .demo import demo_camera, demo_scene
    from .scenefile import load_scene_file
    if getattr(a, "demo", False) or a.scene is None:
        if a.scene is not None:
            raise SdfglError("give either a scene file or --demo, not both")
        return demo_scene(), demo_camera(), True
    sf = load_scene_file(a.scene)
    a.file_settings = sf.settings
    return sf.scene, sf.camera, False


def _camera(a: argparse.Namespace, scene, camera):  # noqa: ANN001
    from .camera import OrbitCamera
    if a.yaw is None and a.pitch is None and a.distance is None:
        return camera
    base = camera if isinstance(camera, OrbitCamera) else OrbitCamera.framing(*scene.bounds)
    return OrbitCamera(base.target, a.distance or base.distance, base.yaw if a.yaw is None else a.yaw,
                       base.pitch if a.pitch is None else a.pitch, base.fov)


def cmd_render(a: argparse.Namespace) -> int:
    from .render import render
    scene, camera, is_demo = _load(a)
    settings = _settings(a)
    if is_demo and not a.no_ground:
        settings["ground"] = True
    res = render(scene, _camera(a, scene, camera), a.size, **settings)
    path = res.save(a.output)
    t = res.timings
    print(f"wrote {path} ({a.size[0]}x{a.size[1]}, aa {a.aa}): compile {t['compile_s'] * 1000:.0f} ms, "
          f"draw {t['draw_s'] * 1000:.0f} ms")
    return 0


def cmd_shader(a: argparse.Namespace) -> int:
    from .codegen import compile as compile_scene
    scene, _, _ = _load(a)
    sys.stdout.write(compile_scene(scene, **_settings(a)))
    return 0


def cmd_view(a: argparse.Namespace) -> int:
    from .viewer import Viewer
    settings = _settings(a)
    if a.scene is None or a.demo:
        from .demo import demo_camera, demo_scene
        v = Viewer(demo_scene(), demo_camera(), size=a.size, target_ms=a.target_ms, adaptive=not a.no_adaptive,
                   max_samples=a.max_samples, state_file=a.state_file, screenshot_dir=a.screenshot_dir, panel=a.panel,
                   **{**settings, "ground": True})
    else:
        v = Viewer(path=a.scene, size=a.size, target_ms=a.target_ms, adaptive=not a.no_adaptive,
                   max_samples=a.max_samples, state_file=a.state_file, screenshot_dir=a.screenshot_dir, panel=a.panel,
                   **_overrides(a))
    v.run()
    return 0


def cmd_bench(a: argparse.Namespace) -> int:
    from .bench import run
    run(a.quick, a.size, a.out, not a.no_progress, a.scenes)
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="sdfgl", description="Render signed-distance-function scenes with GLSL.")
    sub = parser.add_subparsers(dest="command", required=True)

    r = sub.add_parser("render", help="render a scene file (or the demo) headless to an image")
    r.add_argument("scene", nargs="?", help="Python file defining 'scene' (and optionally 'camera')")
    r.add_argument("--demo", action="store_true", help="render the built-in showcase scene")
    r.add_argument("-o", "--output", default="out.png", help="image path (default out.png)")
    r.add_argument("--size", type=_size, default=(800, 600), help="WIDTHxHEIGHT (default 800x600)")
    r.add_argument("--yaw", type=float, help="orbit camera yaw in degrees")
    r.add_argument("--pitch", type=float, help="orbit camera pitch in degrees")
    r.add_argument("--distance", type=float, help="orbit camera distance")
    r.add_argument("--no-ground", action="store_true", help="with --demo: leave the ground plane out")
    _add_settings(r)
    r.set_defaults(func=cmd_render)

    s = sub.add_parser("shader", help="print the generated fragment shader")
    s.add_argument("scene", nargs="?", help="Python file defining 'scene'")
    s.add_argument("--demo", action="store_true", help="use the built-in showcase scene")
    _add_settings(s)
    s.set_defaults(func=cmd_shader)

    from .viewer import KEYS_HELP
    v = sub.add_parser("view", help="open an interactive window on a scene file (reloaded when saved)",
                       formatter_class=argparse.RawDescriptionHelpFormatter, epilog="keys:\n" + KEYS_HELP)
    v.add_argument("scene", nargs="?", help="Python file defining 'scene' (default: the demo)")
    v.add_argument("--demo", action="store_true", help="view the built-in showcase scene")
    v.add_argument("--size", type=_size, default=(960, 540), help="window size WIDTHxHEIGHT (default 960x540)")
    v.add_argument("--target-ms", type=float, default=50.0,
                   help="frame time to hold while the camera moves, by lowering the resolution (default 50)")
    v.add_argument("--no-adaptive", action="store_true", help="always render at full resolution")
    v.add_argument("--max-samples", type=int, default=16, help="jittered samples accumulated when idle (16)")
    v.add_argument("--screenshot-dir", default=".", help="where P saves screenshots (default: here)")
    v.add_argument("--state-file", help="keep a JSON file with the view's state up to date (for scripts)")
    v.add_argument("--panel", action=argparse.BooleanOptionalAction, default=None,
                   help="open with the side panel shown / hidden (default: shown if the window is >= 800 wide)")
    _add_settings(v)
    v.set_defaults(func=cmd_view)

    from .web.cli import add_parser as add_html
    add_html(sub)

    from .bench import add_arguments
    b = sub.add_parser("bench", help="benchmark marching methods: frame time beside error")
    add_arguments(b)
    b.set_defaults(func=cmd_bench)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    a = parser.parse_args(argv)
    try:
        return int(a.func(a))
    except SdfglError as exc:
        print(f"sdfgl: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
