"""Frame times with and without the coarse pass at 1280x720, interleaved (off, on, off, on...),
medians of ``frames`` draws: the demo scene (ground on), its CSG part and objects on a plane
seen low, each with soft shadows and AO and without.
`python benchmarks/coarse_pass.py [frames] [tile ...] [scene ...]`."""
import statistics
import sys

import numpy as np

import sdfgl as sg
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.render import Renderer


def scenes() -> dict:
    """name -> (scene, camera, settings)."""
    drill = sg.cylinder(0.5, 4).orient((1, 0, 0)) | sg.cylinder(0.5, 4) | sg.cylinder(0.5, 4).orient((0, 0, 1))
    csg = sg.difference((sg.sphere(1) & sg.box(1.5)).color(0.85, 0.3, 0.2), drill.color(0.95, 0.8, 0.3))
    low = sg.union(sg.plane(), *[sg.box(0.4).translate((x, 0.4, z)) for x in (-3, 0, 3) for z in (-3, 0, 3)],
                   sg.sphere(0.6).translate((1.5, 0.6, 1.5)), sg.torus(0.6, 0.15).translate((-1.5, 0.15, 1.5)))
    return {"demo": (demo_scene(), demo_camera(), {"ground": True}),
            "csg": (csg, sg.OrbitCamera(distance=4.5, yaw=30, pitch=25), {}),
            "low": (low, sg.OrbitCamera(target=(0, 0.3, 0), distance=8, yaw=20, pitch=4), {})}


def main(argv: list[str]) -> None:
    numbers = [int(a) for a in argv if a.isdigit()]
    frames = numbers[0] if numbers else 9
    tiles = numbers[1:] or [8]
    only = [a for a in argv if not a.isdigit()]
    r, size = Renderer(), (1280, 720)
    for name, (scene, cam, extra) in scenes().items():
        if only and name not in only:
            continue
        for look in ({"shadows": "soft", "ao": True}, {"shadows": False, "ao": False}):
            variants = [("off", False)] + [(f"tile {t}", t) for t in tiles]
            first = {v: r.render(scene, cam, size, coarse=c, **look, **extra).color for v, c in variants}
            times: dict[str, list[float]] = {v: [] for v, _ in variants}
            for _ in range(frames):
                for v, c in variants:
                    times[v].append(r.render(scene, cam, size, coarse=c, **look, **extra).timings["draw_s"])
            med = {v: 1000 * statistics.median(ts) for v, ts in times.items()}
            diff = {v: np.mean(np.abs(img.astype(int) - first["off"].astype(int)).max(-1) > 8) for v, img in first.items()}
            print(f"{name:5s} {'shadows+AO' if look['ao'] else 'plain':10s} " + "  ".join(
                f"{v}: {med[v]:6.1f} ms (x{med[v] / med['off']:.3f}, {100 * diff[v]:.3f}% px > 8/255)" for v in med),
                flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
