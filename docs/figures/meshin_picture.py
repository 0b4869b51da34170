"""Render docs/meshin_drilled.png: a closed triangle mesh (a displaced sphere, 20 480
triangles) loaded as an exact field, drilled, filleted onto a base and rendered.

    python docs/figures/meshin_picture.py [docs/meshin_drilled.png]
"""
import sys
from pathlib import Path

import numpy as np
import trimesh

import sdfgl as sg

HERE = Path(__file__).resolve().parent

if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else HERE.parent / "meshin_drilled.png")
    ico = trimesh.creation.icosphere(5)
    v = ico.vertices
    bump = 1 + 0.12 * np.sin(6 * v[:, 0]) * np.sin(6 * v[:, 1]) * np.sin(6 * v[:, 2])
    part = sg.from_mesh(trimesh.Trimesh(v * bump[:, None], ico.faces), name="displaced sphere")
    holes = sg.union(*(sg.cylinder(0.25, 3).orient(axis) for axis in (sg.X, sg.Z)))
    base = sg.rounded_box((2.6, 0.3, 2.6), 0.1).translate((0, -1.0, 0))
    scene = sg.union((part - holes).color("#d98c5f"), base.color("#8fa3b8"), k=0.2)
    cam = sg.OrbitCamera(distance=5.2, yaw=35, pitch=25, target=(0, -0.2, 0))
    sg.render(scene, cam, (480, 320), aa=2, ground=True).save(out)
    print(f"wrote {out}")
