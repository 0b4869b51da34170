"""The showcase scenes of Monzón González's thesis, path-traced through Mitsuba 3, beside the real-time render.

    python docs/figures/pbr_showcase.py [--size 360x240] [--spp 64]

Writes docs/pbr_gallery.png (top row: real-time EGL render, bottom row: path traced) and
prints each render's time. Materials follow the thesis: a glass core in the skyscrapers,
a Sierpinski tetrahedron in a Cornell box lit by an area light, and noise mountains
whose rock turns to snow above a height, with glossy water below.
"""
import argparse
import time
from pathlib import Path

import numpy as np
from PIL import Image

import sdfgl as sg
from sdfgl.pbr import Blend, Material, Sky, Sun
from sdfgl.scenefile import load_scene_file

ROOT = Path(__file__).resolve().parents[2]
GALLERY = ROOT / "examples" / "gallery"


def skyscrapers() -> tuple:
    sf = load_scene_file(GALLERY / "skyscrapers.py")
    core = sg.box((1.32, 4.02, 1.32)).translate((0, 2.0, 0)).translate((1.4, 0, 0)).mirror(sg.X)
    look = Blend(Material(transmission=1, roughness=0.05, color=(0.75, 0.88, 0.95)),
                 Material(specular=0.3, roughness=0.6), boundary=core, width=0.005)
    return sf.scene, sf.camera, sf.settings, {"material": look, "ground": True}


def sierpinski_cornell() -> tuple:
    sf = load_scene_file(GALLERY / "sierpinski.py")
    walls = (sg.box((4.4, 4.4, 4.4)) - sg.box((4.0, 4.0, 4.0)) - sg.box((3.0, 3.0, 1.0)).translate((0, 0, 2.2)))
    left = sg.box((0.2, 4.0, 4.0)).translate((-2.1, 0, 0)).color(0.63, 0.07, 0.05)
    right = sg.box((0.2, 4.0, 4.0)).translate((2.1, 0, 0)).color(0.14, 0.45, 0.09)
    room = sg.union(walls.color(0.73, 0.73, 0.73), left, right).translate((0, 2.0, 0))
    scene = sg.union(room, sf.scene)
    camera = sg.Camera.look_at((0, 2.0, 7.2), (0, 1.9, 0), fov=40)
    lamp = {"type": "rectangle", "to_world": lamp_transform((0, 3.98, 0), 0.6),
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [18.0, 15.0, 11.0]}}}
    return scene, camera, {"shadows": "soft"}, {"extra": {"lamp": lamp, "sun": None}, "quality": 2,
                                                "sky": Sky(intensity=0.02)}


def lamp_transform(at: tuple, half: float):
    import mitsuba as mi
    return mi.ScalarTransform4f().translate(list(at)).rotate([1, 0, 0], 90).scale([half, half, 1.0])


def mountains() -> tuple:
    sf = load_scene_file(GALLERY / "mountains.py")
    rock = Material(color=(0.42, 0.36, 0.3), roughness=0.9)
    snow = Material(color=(0.92, 0.93, 0.96), roughness=0.7)
    water = Material(color=(0.1, 0.25, 0.4), specular=1.0, roughness=0.05, ior=1.33)
    look = Blend(water, Blend(rock, snow, boundary=sg.plane((0, 1, 0), (0, 0.55, 0)), width=0.12),
                 boundary=sg.plane((0, 1, 0), (0, -0.17, 0)), width=0.02)
    bounds = ((-25.0, -1.6, -25.0), (25.0, 1.8, 25.0))
    return sf.scene, sf.camera, sf.settings, {"material": look, "bounds": bounds,
                                              "sun": Sun(direction=(0.6, 0.5, -0.3))}


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--size", default="360x240")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--out", type=Path, default=ROOT / "docs" / "pbr_gallery.png")
    a = p.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    scenes = {"skyscrapers": skyscrapers, "sierpinski": sierpinski_cornell, "mountains": mountains}
    sheet = Image.new("RGB", (w * len(scenes), 2 * h), (255, 255, 255))
    for i, (name, make) in enumerate(scenes.items()):
        scene, camera, settings, pbr = make()
        t0 = time.perf_counter()
        rt = sg.render(scene, camera, (w, h), aa=2, **settings)
        t1 = time.perf_counter()
        img = sg.render_pbr(scene, camera, (w, h), spp=a.spp, **pbr)
        t2 = time.perf_counter()
        print(f"{name:12s} real-time {t1 - t0:6.2f} s   path traced {t2 - t1:7.2f} s ({a.spp} spp, "
              f"{img.settings['variant']}, grid {img.settings['resolution']}^3, trace {img.timings['trace_s']:.1f} s)")
        sheet.paste(Image.fromarray(rt.color), (i * w, 0))
        sheet.paste(Image.fromarray(img.to_uint8()), (i * w, h))
        assert np.isfinite(img.rgba).all()
    a.out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
