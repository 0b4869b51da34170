"""``sdfgl pbr``: path-trace a scene file (or the demo) through Mitsuba 3 to an image."""
from __future__ import annotations

import argparse
import sys
import time
from typing import Any, Callable

from ..extras import require_extra
from .common import (add_camera_arguments, add_scene_arguments, camera_from_args, image_size, load_scene_args,
                     require_scene)


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl pbr``."""
    p = sub.add_parser("pbr", help="path-trace a scene file (or the demo) with Mitsuba 3 (extra sdfgl[pbr])")
    add_scene_arguments(p, "render the built-in showcase scene")
    p.add_argument("-o", "--output", default="pbr.png",
                   help="image path: .png/.jpg (8-bit, gamma 2.2), .exr (linear float) or .npy (default pbr.png)")
    p.add_argument("--size", type=image_size, default=(640, 480), help="WIDTHxHEIGHT (default 640x480)")
    p.add_argument("--spp", type=int, default=64, help="samples per pixel (default 64)")
    p.add_argument("--resolution", type=int, help="SDF grid (or mesh lattice) cells along the scene's "
                   "longest side (default: from the pixel footprint)")
    p.add_argument("--geometry", choices=("auto", "mesh", "grid"), default="auto",
                   help="what Mitsuba intersects: the scene's mesh, its sampled SDF grid, or auto (default: the "
                        "mesh for a bounded scene)")
    p.add_argument("--quality", type=float, default=1.0, help="multiplies the automatic grid or mesh resolution (default 1)")
    p.add_argument("--max-depth", type=int, default=8, help="longest light path (default 8)")
    p.add_argument("--ground", action="store_true", help="add the checkered ground plane (the demo has it)")
    p.add_argument("--transparent", action="store_true", help="write the coverage as alpha instead of the sky")
    p.add_argument("--exposure", type=float, default=1.0, help="multiply the radiance before encoding (default 1)")
    p.add_argument("--variant", help="Mitsuba variant (default: llvm_ad_rgb when it works here, else scalar_rgb)")
    p.add_argument("--seed", type=int, default=0, help="sampler seed (default 0)")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    add_camera_arguments(p)
    p.set_defaults(func=run)


def progress_line() -> Callable[[str, float], None]:
    """A progress callback writing one updating line (stage, percent, ETA) to standard error."""
    start = time.perf_counter()

    def report(stage: str, fraction: float) -> None:
        elapsed = time.perf_counter() - start
        eta = f", ETA {elapsed / fraction - elapsed:.0f} s" if stage == "path tracing" and fraction > 0 else ""
        sys.stderr.write(f"\rsdfgl pbr: {stage} {100 * fraction:3.0f}%{eta}   ")
        if stage == "path tracing" and fraction >= 1:
            sys.stderr.write("\n")
        sys.stderr.flush()
    return report


def geometry_line(settings: dict[str, Any]) -> str:
    """What Mitsuba intersected, from a PBRImage's settings: the grid's cells or the mesh's triangles."""
    if settings["geometry"] == "mesh":
        return f"mesh of {settings['mesh_faces']} triangles"
    return f"grid {'x'.join(str(c) for c in settings['grid_cells'])}"


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl pbr`` (Mitsuba is checked for before the scene loads)."""
    require_scene(a, "pbr")
    require_extra("pbr", "mitsuba", purpose="sdfgl pbr")
    from ..pbr.render import render_pbr
    sf = load_scene_args(a)
    scene = sf.scene
    img = render_pbr(scene, camera_from_args(a, scene, sf.camera), a.size, a.spp, resolution=a.resolution,
                     quality=a.quality, ground=a.ground or bool(sf.settings.get("ground")), max_depth=a.max_depth,
                     seed=a.seed, variant=a.variant, progress=None if a.quiet else progress_line(), geometry=a.geometry)
    path = img.save(a.output, exposure=a.exposure, transparent=a.transparent)
    s, t = img.settings, img.timings
    print(f"wrote {path} ({a.size[0]}x{a.size[1]}, {s['spp']} spp, Mitsuba {s['variant']}, "
          f"{geometry_line(s)}): sampling {t['sample_s']:.2f} s, "
          f"path tracing {t['trace_s']:.2f} s, total {t['total_s']:.2f} s")
    return 0
