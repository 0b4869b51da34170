"""Command line: ``sdfgl render | shader | view | html | mesh | pbr | bench | animate | batch`` (also ``python -m sdfgl``)."""
from __future__ import annotations

import argparse
import sys
from typing import Sequence

from .version import __version__
from .cli_common import finite_number, add_camera_arguments, camera_from_args, require_scene
from .errors import SdfglError
from .settings import METHODS, OUTPUTS


def _size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size must look like 800x600, got {text!r}") from None
    return w, h


def _outputs(text: str) -> tuple[str, ...]:
    names = tuple(x.strip() for x in text.split(",") if x.strip())
    bad = [n for n in names if n not in OUTPUTS]
    if bad or not names:
        raise argparse.ArgumentTypeError(f"outputs must be a comma list of {', '.join(OUTPUTS)}, got {text!r}")
    return names


def _add_settings(p: argparse.ArgumentParser) -> None:
    p.add_argument("--aa", type=int, default=1, choices=range(1, 5), metavar="{1,2,3,4}",
                   help="samples per pixel side (default 1)")
    p.add_argument("--shadows", choices=("off", "hard", "soft"), default="soft", help="(default soft)")
    p.add_argument("--no-ao", dest="ao", action="store_false", help="turn ambient occlusion off")
    p.add_argument("--ground", action="store_true", help="add an analytic ground plane under the scene")
    p.add_argument("--method", choices=METHODS, default="auto", help="marching method (default auto: enhanced, "
                   "newton for implicit fields)")
    p.add_argument("--max-steps", type=int, default=256, help="marching rounds per primary ray away from surfaces, 1..100000 (default 256; near-surface rounds are counted apart, up to twice that in all)")


CLI_DEFAULTS = {"aa": 1, "shadows": "soft", "ao": True, "ground": False, "method": "auto", "max_steps": 256}


def _overrides(a: argparse.Namespace) -> dict[str, object]:
    """The settings given on the command line (those that differ from the defaults)."""
    given = {"aa": a.aa, "shadows": False if a.shadows == "off" else a.shadows, "ao": a.ao, "ground": a.ground,
             "method": a.method, "max_steps": a.max_steps}
    return {k: v for k, v in given.items() if v != CLI_DEFAULTS[k]}


def _settings(a: argparse.Namespace) -> dict[str, object]:
    """Defaults, then the scene file's own 'settings', then what the command line gave."""
    return {**CLI_DEFAULTS, **getattr(a, "file_settings", {}), **_overrides(a)}


def _load(a: argparse.Namespace):  # -> tuple[Node, Camera | None, bool]
    """The scene, camera and whether it is the demo: from --demo or a .py / .json scene file."""
    if getattr(a, "demo", False) or a.scene is None:
        if a.scene is not None:
            raise SdfglError("give either a scene file or --demo, not both")
        from .demo import demo_camera, demo_scene
        return demo_scene(), demo_camera(), True
    from .scenefile import load_scene_file
    sf = load_scene_file(a.scene)
    a.file_settings = sf.settings
    return sf.scene, sf.camera, False


def cmd_render(a: argparse.Namespace) -> int:
    from .outputs import save_outputs
    from .render import render
    require_scene(a, "render")
    scene, camera, is_demo = _load(a)
    settings = _settings(a)
    if is_demo and not a.no_ground:
        settings["ground"] = True
    outputs = tuple(dict.fromkeys(("color",) + (a.outputs or ())))
    if a.output.lower().endswith(".npz") and a.outputs is None:
        outputs = OUTPUTS
    settings.update(_look(a))
    cam = camera_from_args(a, scene, camera)
    if a.ortho:
        from .camera import OrbitCamera
        yaw, pitch = (cam.yaw, cam.pitch) if isinstance(cam, OrbitCamera) else (30.0, 20.0)
        cam = OrbitCamera.framing(*scene.bounds, yaw, pitch, aspect=a.size[0] / a.size[1], projection="orthographic")
    res = render(scene, cam, a.size, outputs=outputs, **settings)
    paths = save_outputs(res, a.output, outputs)
    t = res.timings
    print(f"wrote {', '.join(str(p) for p in paths)} ({a.size[0]}x{a.size[1]}, aa {a.aa}): "
          f"compile {t['compile_s'] * 1000:.0f} ms, draw {t['draw_s'] * 1000:.0f} ms")
    return 0


def _look(a: argparse.Namespace) -> dict[str, object]:
    """The look options of `sdfgl render`: --background, --alpha, --fog."""
    out: dict[str, object] = {}
    if a.background:
        parts = a.background.split(",")
        out["background"] = parts[0] if len(parts) == 1 else tuple(parts)
    if a.alpha:
        out["alpha"] = True
    if a.fog is not None:
        out["fog"] = a.fog
    return out


def cmd_shader(a: argparse.Namespace) -> int:
    from .camera import OrbitCamera
    from .codegen import generate
    from .render import shader_origin
    from .settings import Settings
    require_scene(a, "shader")
    scene, camera, _ = _load(a)
    cam = camera_from_args(a, scene, camera) or OrbitCamera.framing(*scene.bounds)
    sys.stdout.write(generate(scene, Settings.build(**_settings(a)), shader_origin(scene, cam.eye),
                              projection=cam.projection).text)
    return 0


def cmd_view(a: argparse.Namespace) -> int:
    from .viewer import Viewer
    settings = _settings(a)
    common = dict(size=a.size, target_ms=a.target_ms, adaptive=not a.no_adaptive, max_samples=a.max_samples,
                  state_file=a.state_file, screenshot_dir=a.screenshot_dir, panel=a.panel)
    if a.scene is None or a.demo:
        scene, camera, _ = _load(a)
        v = Viewer(scene, camera_from_args(a, scene, camera), **common, **{**settings, "ground": True})
    else:
        camera = None
        if any(getattr(a, k) is not None for k in ("yaw", "pitch", "distance", "fov", "target")):
            scene, file_camera, _ = _load(a)
            camera = camera_from_args(a, scene, file_camera)
        v = Viewer(camera=camera, path=a.scene, **common, **_overrides(a))
    v.run()
    return 0


def cmd_bench(a: argparse.Namespace) -> int:
    from .bench import run
    run(a.quick, a.size, a.out, not a.no_progress, a.scenes)
    return 0


def build_parser(argv: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The ``sdfgl`` argument parser; given ``argv``, only the chosen subcommand's heavy
    modules are imported (None builds everything)."""
    parser = argparse.ArgumentParser(prog="sdfgl", description="Render signed-distance-function scenes with GLSL.")
    parser.add_argument("--version", action="version", version=f"sdfgl {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="{render,shader,view,html,bench}")
    scene_help = "scene file: Python defining 'scene' (and optionally 'camera', 'settings'), or a .json document"

    r = sub.add_parser("render", help="render a scene file (or the demo) headless to an image")
    r.add_argument("scene", nargs="?", help=scene_help)
    r.add_argument("--demo", action="store_true", help="render the built-in showcase scene")
    r.add_argument("-o", "--output", default="out.png",
                   help="image path (default out.png); a .npz path gets every output as float arrays")
    r.add_argument("--outputs", type=_outputs, metavar="LIST",
                   help=f"also write these images beside the colour one: a comma list of {', '.join(OUTPUTS[1:])} "
                        f"(e.g. depth,normal -> out.depth.png, out.normal.png)")
    r.add_argument("--size", type=_size, default=(800, 600), help="WIDTHxHEIGHT (default 800x600)")
    r.add_argument("--no-ground", action="store_true", help="with --demo: leave the ground plane out")
    r.add_argument("--background", help="a colour ('#ffffff', 'white') or TOP,BOTTOM for a gradient")
    r.add_argument("--alpha", action="store_true", help="transparent background: RGBA PNG, alpha = coverage")
    r.add_argument("--fog", type=finite_number, help="fade surfaces into the background over this distance")
    r.add_argument("--ortho", action="store_true", help="orthographic camera framing the scene")
    add_camera_arguments(r)
    _add_settings(r)
    r.set_defaults(func=cmd_render)

    s = sub.add_parser("shader", help="print the generated fragment shader")
    s.add_argument("scene", nargs="?", help=scene_help)
    s.add_argument("--demo", action="store_true", help="use the built-in showcase scene")
    add_camera_arguments(s)
    _add_settings(s)
    s.set_defaults(func=cmd_shader)

    # the viewer (glfw) and the benchmark harness are imported only for their own subcommand
    command = next((x for x in argv if not x.startswith("-")), None) if argv is not None else None
    keys = ""
    if command in (None, "view"):
        from .viewer import KEYS_HELP
        keys = "keys:\n" + KEYS_HELP
    v = sub.add_parser("view", help="open an interactive window on a scene file (reloaded when saved)",
                       formatter_class=argparse.RawDescriptionHelpFormatter, epilog=keys)
    v.add_argument("scene", nargs="?", help=scene_help + " (default: the demo)")
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
    add_camera_arguments(v)
    _add_settings(v)
    v.set_defaults(func=cmd_view)

    from .pbr.cli import add_parser as add_pbr
    add_pbr(sub, _size)
    from .web.cli import add_parser as add_html
    add_html(sub)

    b = sub.add_parser("bench", help="benchmark marching methods: frame time beside error")
    if command in (None, "bench"):
        from .bench import add_arguments
        add_arguments(b)
    b.set_defaults(func=cmd_bench)

    from .animate.cli_animate import add_parser as add_animate
    from .animate.cli_batch import add_parser as add_batch
    add_animate(sub)
    add_batch(sub)
    from .mesh.cli import add_parser as add_mesh_parser
    add_mesh_parser(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(args)
    a = parser.parse_args(args)
    try:
        return int(a.func(a))
    except SdfglError as exc:
        print(f"sdfgl: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
