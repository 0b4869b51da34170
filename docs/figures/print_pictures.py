"""The printing guide's pictures, drawn headless with matplotlib from the meshes sdfgl writes:
docs/print_two_material.png (a two-material 3MF, read back from the file, each part in its own
base material's colour) and docs/print_adaptive.png (fogleman's CSG part, uniform sharp mesh beside
the adaptive one at the same bound). Run: python docs/figures/print_pictures.py"""
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import sdfgl as sg  # noqa: E402
from sdfgl.mesh.threemf import read_3mf  # noqa: E402

DOCS = Path(__file__).resolve().parents[1]
LIGHT = np.array([0.4, 0.8, 0.6]) / np.linalg.norm([0.4, 0.8, 0.6])


def draw(ax, tri: np.ndarray, rgb: np.ndarray, lim: float, title: str, edges: float = 0.2,
         view: tuple[float, float] = (30, 35)) -> None:
    """Flat-shaded triangles (n, 3, 3) in colours (n, 3) on a 3D axis without frame."""
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
    shade = 0.35 + 0.65 * np.clip(n @ LIGHT, 0, 1)
    ax.add_collection3d(Poly3DCollection(tri, facecolors=np.clip(rgb * shade[:, None], 0, 1),
                                         edgecolors=(0, 0, 0, 0.3 if edges else 0), linewidths=edges))
    ax.set_xlim(-lim, lim), ax.set_ylim(-lim, lim), ax.set_zlim(-lim, lim)
    ax.view_init(elev=view[0], azim=view[1])
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)


def two_material() -> None:
    body = sg.rounded_box((40, 40, 6), 1)
    inlay = sg.extrude(sg.text("sg", size=22, align="center"), 6.4).translate((0, -7, 0))
    parts = {"body": (body - inlay).material("white"), "inlay": inlay.material("red")}
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "two.3mf"
        sg.save_3mf(parts, path, units="mm", resolution=160)
        doc = read_3mf(path)  # the parts as a slicer reads them: objects, triangles, base materials
    tris, rgbs = [], []
    for obj in doc["objects"].values():
        tris.append(obj["vertices"][obj["faces"]])
        rgbs.append(np.array([[int(c[i:i + 2], 16) / 255.0 for i in (1, 3, 5)] for c in obj["colors"]]))
    fig = plt.figure(figsize=(5, 5), dpi=100)
    ax = fig.add_subplot(projection="3d")
    draw(ax, np.concatenate(tris), np.concatenate(rgbs), 24.0,
         "sg.save_3mf({'body': ..., 'inlay': ...}, 'two.3mf', units='mm')\nread back from the file: "
         f"{len(doc['objects'])} objects ({', '.join(doc['objects'])}), their base materials' colours", edges=0.0,
         view=(50, -70))
    fig.savefig(DOCS / "print_two_material.png", bbox_inches="tight")
    plt.close(fig)


def adaptive() -> None:
    c = sg.cylinder(0.5, 4)
    part = (sg.sphere(1) & sg.box(1.5)) - (c.orient(sg.X) | c | c.orient(sg.Z))
    uniform = sg.mesh(part, resolution=64, mode="sharp", colors=False)
    bound = 0.05 * float(uniform.step)
    fine = sg.mesh(part, tolerance=bound, colors=False)
    fig = plt.figure(figsize=(9, 4.6), dpi=100)
    for i, (m, what) in enumerate(((uniform, f"uniform sharp, resolution 64: {len(uniform.faces)} triangles"),
                                   (fine, f"tolerance={bound:.4f} (0.05 cell): {len(fine.faces)} triangles"))):
        ax = fig.add_subplot(1, 2, i + 1, projection="3d")
        tri = m.vertices[m.faces]
        draw(ax, tri, np.tile([0.85, 0.35, 0.25], (len(tri), 1)), 0.8, what)
    fig.savefig(DOCS / "print_adaptive.png", bbox_inches="tight")
    plt.close(fig)


if __name__ == "__main__":
    two_material()
    adaptive()
    print(f"wrote {DOCS / 'print_two_material.png'} and {DOCS / 'print_adaptive.png'}")
