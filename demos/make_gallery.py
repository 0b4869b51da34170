"""Render every scene in demos/gallery/ and tile them into one contact sheet.

    python demos/make_gallery.py [--size 240x160] [--out gallery.png]
    python demos/make_gallery.py --update-docs      # replace the tracked docs/gallery.png
"""
import argparse
import time
from pathlib import Path

from PIL import Image

import sdfgl as sg
from sdfgl.scenefile import load_scene_file

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--size", default="240x160")
    p.add_argument("--out", type=Path, default=Path("gallery.png"), help="where to write (default ./gallery.png)")
    p.add_argument("--update-docs", action="store_true", help="write docs/gallery.png (a tracked file) instead")
    a = p.parse_args()
    if a.update_docs:
        a.out = ROOT / "docs" / "gallery.png"
    w, h = (int(x) for x in a.size.split("x"))
    paths = sorted((ROOT / "demos" / "gallery").glob("*.py"))
    cols = 4
    sheet = Image.new("RGB", (w * cols, h * (-(-len(paths) // cols))), (255, 255, 255))
    for i, path in enumerate(paths):
        sf = load_scene_file(path)
        t0 = time.perf_counter()
        res = sg.render(sf.scene, sf.camera, (w, h), aa=2, **sf.settings)
        print(f"{path.stem:12s} {time.perf_counter() - t0:6.2f} s")
        sheet.paste(Image.fromarray(res.color), ((i % cols) * w, (i // cols) * h))
    a.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
