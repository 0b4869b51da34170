"""Mesh fogleman's CSG example (sharp mode) and draw the mesh headless with matplotlib:
docs/mesh_csg.png. Run: python docs/figures/mesh_picture.py"""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import sdfgl as sg  # noqa: E402

c = sg.cylinder(0.5, 4)
part = (sg.sphere(1) & sg.box(1.5)).color(0.85, 0.3, 0.2) - (c.orient(sg.X) | c | c.orient(sg.Z)).color(0.95, 0.8, 0.3)
m = sg.mesh(part, resolution=40, mode="sharp")
tri = m.vertices[m.faces]
n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
n /= np.linalg.norm(n, axis=1, keepdims=True)
light = np.array([0.4, 0.8, 0.6]) / np.linalg.norm([0.4, 0.8, 0.6])
shade = 0.35 + 0.65 * np.clip(n @ light, 0, 1)
rgb = np.clip(m.colors[m.faces].mean(axis=1) * shade[:, None], 0, 1)
fig = plt.figure(figsize=(5, 5), dpi=100)
ax = fig.add_subplot(projection="3d")
ax.add_collection3d(Poly3DCollection(tri, facecolors=rgb, edgecolors=(0, 0, 0, 0.25), linewidths=0.2))
ax.set_xlim(-0.8, 0.8), ax.set_ylim(-0.8, 0.8), ax.set_zlim(-0.8, 0.8)
ax.view_init(elev=25, azim=35)
ax.set_axis_off()
ax.set_title(f"sg.mesh(part, resolution=40, mode='sharp'): {len(m.faces)} triangles", fontsize=9)
out = Path(__file__).resolve().parents[1] / "mesh_csg.png"
fig.savefig(out, bbox_inches="tight")
print(f"wrote {out}")
