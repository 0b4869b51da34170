"""How long writing the colour image takes at 1920x1080, by PNG option (and beside the render).

    python benchmarks/png_write_times.py [repeats]

Renders the demo scene once at 1080p (aa 1, soft shadows, AO, ground), then writes it with
each option, interleaved, and prints median write time and file size per option: Pillow's
options, and sdfgl's own encoder (sdfgl.png, what ``res.save("x.png")`` uses), whose deflate
is ISA-L's where the ``fast`` extra (isal) is installed, zlib's otherwise.
"""
import io
import statistics
import sys
import time

from PIL import Image

import sdfgl as sg
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.png import encode_png

OPTIONS = {
    "pillow default (compress_level 6)": {},
    "compress_level 1": {"compress_level": 1},
    "compress_level 3": {"compress_level": 3},
    "compress_level 0 (stored)": {"compress_level": 0},
    "optimize=True": {"optimize": True},
}


def deflater() -> str:
    """Which deflate sdfgl.png uses here."""
    try:
        import isal  # noqa: F401
    except ImportError:
        return "zlib"
    return "ISA-L"


def main(repeats: int = 7) -> None:
    scene, cam = demo_scene(), demo_camera()
    sg.render(scene, cam, (1920, 1080), ground=True)  # compile once
    renders = []
    for _ in range(3):
        t0 = time.perf_counter()
        res = sg.render(scene, cam, (1920, 1080), ground=True)
        renders.append(time.perf_counter() - t0)
    img = Image.fromarray(res.color)
    ours = f"sdfgl encode_png (Sub filter, {deflater()} level 1)"
    times = {k: [] for k in (*OPTIONS, ours)}
    sizes = {}
    for _ in range(repeats):
        for name, opts in OPTIONS.items():  # interleaved: load drifts hit every option alike
            buf = io.BytesIO()
            t0 = time.perf_counter()
            img.save(buf, format="PNG", **opts)
            times[name].append(time.perf_counter() - t0)
            sizes[name] = buf.tell()
        t0 = time.perf_counter()
        sizes[ours] = len(encode_png(res.color))
        times[ours].append(time.perf_counter() - t0)
    print(f"render 1920x1080 (warm, median of 3): {statistics.median(renders) * 1000:.0f} ms")
    print("| PNG option | write ms (median) | file KiB |")
    print("|---|---|---|")
    for name in times:
        print(f"| {name} | {statistics.median(times[name]) * 1000:.0f} | {sizes[name] / 1024:.0f} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
