"""The browser view's figures: WebGL2 (headless Chromium, SwiftShader) against EGL for every
gallery scene, HTML sizes and frame times, and the README screenshot docs/browser.png.

    python benchmarks/browser_figures.py [--size 320x240] [--no-screenshot] [--nodes]

--nodes also compares every node type of the test zoo (tests/nodes_zoo.py) at 96x72.
"""
import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np
from PIL import Image

import sdfgl as sg
from sdfgl.camera import OrbitCamera
from sdfgl.demo import demo_camera, demo_scene
from sdfgl.scenefile import load_scene_file
from sdfgl.web.chromium import Chromium, file_url
from sdfgl.web.html import save_html

ROOT = Path(__file__).resolve().parents[1]
STILL = "document.getElementById('sdfgl-root').dataset.still === '1'"


def still_after(b: Chromium, n: int) -> None:
    b.wait_for(f"{STILL} && +document.getElementById('sdfgl-root').dataset.frames > {n}", timeout=300)


def frame_ms(b: Chromium, repeats: int = 3) -> float:
    """Median time of a full-resolution redraw in the page (program already compiled)."""
    out = []
    for _ in range(repeats):
        n = int(b.evaluate("+document.getElementById('sdfgl-root').dataset.frames"))
        b.evaluate("window.sdfglViewer.setSettings({})")
        still_after(b, n)
        out.append(float(b.evaluate("document.getElementById('sdfgl-root').dataset.frameMs")))
    return statistics.median(out)


def compare(size: tuple[int, int], tmp: Path) -> None:
    w, h = size
    print(f"| scene | HTML KiB | pixels > 8/255 | max diff | mean diff | WebGL2 frame ms | EGL frame ms |")
    print("|---|---|---|---|---|---|---|")
    with Chromium(size=(w + 360, h + 260)) as b:
        scenes = [(p.stem, load_scene_file(p)) for p in sorted((ROOT / "examples" / "gallery").glob("*.py"))]
        for name, sf in scenes:
            cam = OrbitCamera.of(sf.camera, *sf.scene.bounds)
            html = save_html(sf.scene, tmp / f"{name}.html", cam, size, **sf.settings)
            b.goto(file_url(html))
            still_after(b, 0)
            rect = b.evaluate("(() => { const r = document.querySelector('canvas').getBoundingClientRect();"
                              " return [r.x, r.y, r.width, r.height]; })()")
            web = b.screenshot(tuple(rect))
            ms = frame_ms(b)
            implicit = sf.scene.exactness == sg.IMPLICIT
            st = {"shadows": "soft", "ao": not implicit, **({"method": "newton"} if implicit else {}), **sf.settings}
            sg.render(sf.scene, cam, size, **st)
            draws = [sg.render(sf.scene, cam, size, **st) for _ in range(3)]
            egl = draws[0].color
            d = np.abs(web.astype(int) - egl.astype(int)).max(axis=2)
            egl_ms = statistics.median(r.timings["draw_s"] * 1000 for r in draws)
            print(f"| {name} | {html.stat().st_size / 1024:.0f} | {100 * (d > 8).mean():.3f}% | {d.max()} | "
                  f"{d.mean():.3f} | {ms:.0f} | {egl_ms:.0f} |")


def compare_nodes(tmp: Path, size: tuple[int, int] = (96, 72)) -> None:
    import sys
    sys.path.insert(0, str(ROOT))
    from tests.nodes_zoo import all_nodes
    print("| node | pixels > 8/255 | max diff |\n|---|---|---|")
    with Chromium(size=(size[0] + 360, size[1] + 300)) as b:
        for name, node in all_nodes().items():
            html = save_html(node, tmp / "node.html", None, size)
            b.goto(file_url(html))
            still_after(b, 0)
            web = b.screenshot((0, 0, *size))
            implicit = node.exactness == sg.IMPLICIT
            st = {"shadows": "soft", "ao": not implicit, **({"method": "newton"} if implicit else {})}
            d = np.abs(web.astype(int) - sg.render(node, None, size, **st).color.astype(int)).max(axis=2)
            print(f"| {name} | {100 * (d > 8).mean():.3f}% | {d.max()} |")


def screenshot(tmp: Path) -> None:
    sf = load_scene_file(ROOT / "examples" / "live_params.py")
    html = save_html(sf.scene, tmp / "live.html", sf.camera, (560, 360), **sf.settings)
    with Chromium(size=(900, 372)) as b:
        b.goto(file_url(html))
        still_after(b, 0)
        out = ROOT / "docs" / "browser.png"
        Image.fromarray(b.screenshot()).save(out)
        print(f"wrote {out}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--size", default="320x240")
    p.add_argument("--no-screenshot", action="store_true")
    p.add_argument("--nodes", action="store_true", help="also compare every node type of the test zoo")
    a = p.parse_args()
    size = tuple(int(x) for x in a.size.split("x"))
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        t0 = time.perf_counter()
        demo = save_html(demo_scene(), tmp / "demo.html", demo_camera(), (800, 500), ground=True)
        print(f"demo scene HTML (800x500 view): {demo.stat().st_size / 1024:.1f} KiB, "
              f"written in {1000 * (time.perf_counter() - t0):.0f} ms")
        compare(size, tmp)  # type: ignore[arg-type]
        if a.nodes:
            compare_nodes(tmp)
        if not a.no_screenshot:
            screenshot(tmp)


if __name__ == "__main__":
    main()
