"""Figures of a triangle mesh as a field (sg.from_mesh): a 100 000-triangle closed mesh (a
bumpy torus, 500 x 100 quads), against libigl, rasterisation and float64 ray casts; the
measuring code is sdfgl.bench_mesh_field (the rows `sdfgl bench` reports).

    python benchmarks/mesh_field.py            # full sizes
    python benchmarks/mesh_field.py --quick    # the bench's --quick sizes, 500 pixels
    python benchmarks/mesh_field.py --out docs/bench/mesh_field.md   # also the table the mesh guide includes
"""
import argparse
import os
import time

import numpy as np

import sdfgl as sg
from sdfgl import bench_mesh_field as B
from sdfgl.gl.context import describe


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="small sizes (a smoke run)")
    ap.add_argument("--out", help="write the figures as a markdown table to this file")
    a = ap.parse_args()
    sizes = B.QUICK if a.quick else B.FULL
    pixels, step, lattice = (500, 0.01, 64) if a.quick else (3000, 0.008, 128)
    renderer = sg.Renderer()
    print(f"machine: {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}; GL: {describe(renderer.ctx)}")
    tm = B.bumpy_torus(sizes["nu"], sizes["nv"])
    t0 = time.perf_counter()
    node = sg.from_mesh(tm, name="bumpy torus")
    t1 = time.perf_counter()
    node.bvh
    t2 = time.perf_counter()
    print(f"mesh: {len(node.faces)} triangles, diagonal {B.diagonal(node):.4f}; from_mesh {t1 - t0:.2f} s, hierarchy "
          f"{t2 - t1:.2f} s (depth {node.bvh.depth})")
    rng = np.random.default_rng(0)
    d = B.distance_row(node, B.sample_points(node, sizes["points"], rng), renderer)
    print(f"distance at {d['points']} points: GPU {d['gpu_s']:.2f} s, libigl {d['igl_s']:.2f} s, ratio "
          f"{d['ratio']:.2f}x; max |diff| {d['max_diff_diag']:.2e} diagonals; signs agree beyond 1e-4 diagonals: "
          f"{100 * d['sign_agreement']:.4f} %")
    f = B.frame_row(tm, node, sizes["size"], sizes["frames"], renderer)
    print(f"render {f['size'][0]}x{f['size'][1]} (no shadows/AO): field {f['field_s']:.3f} s/frame, moderngl raster "
          f"{f['raster_s']:.4f} s/frame, ratio {f['ratio']:.1f}x")
    h = B.depth_row(tm, f, pixels, rng)
    print(f"hits on {pixels} sampled pixels: {h['both']} both, {h['false']} false, {h['lost']} lost; within 0.01 "
          f"footprints {100 * h['within_0.01']:.2f} %, median {h['median_px']:.4f}, max {h['max_px']:.3f} footprints")
    m = B.remesh_row(node, step, lattice)
    print(f"drilled and meshed again ({m['triangles']} triangles, {m['mesh_s']:.1f} s): watertight {m['watertight']}, "
          f"volume {m['volume']:.5f} vs twin {m['twin_volume']:.5f} ({(m['volume'] / m['twin_volume'] - 1) * 100:+.2f} %)")
    if a.out:
        with open(a.out, "w", encoding="utf-8") as out:
            out.write(table(describe(renderer.ctx), len(node.faces), d, f, h, m, step, lattice))
        print(f"wrote {a.out}")


def table(gl: str, triangles: int, d: dict, f: dict, h: dict, m: dict, step: float, lattice: int) -> str:
    """The figures as the markdown table of the mesh guide (docs/guide/meshes-in.md includes it)."""
    w, ht = f["size"]
    rows = [
        (f"signed distance at {d['points']} points, `sg.evaluate` / libigl `signed_distance` time",
         f"{d['gpu_s']:.2f} s / {d['igl_s']:.2f} s = {d['ratio']:.2f}x", "<= 0.1x on a GPU"),
        ("max \\|GPU - libigl\\|", f"{d['max_diff_diag']:.1e} of the bbox diagonal", "<= 1e-5"),
        ("signs farther than 1e-4 diagonals from the surface that agree", f"{100 * d['sign_agreement']:.3f} %", "100 %"),
        (f"{w}x{ht} frame of the mesh as a field (no shadows or AO) / moderngl rasterising it",
         f"{f['field_s']:.3f} s / {f['raster_s']:.4f} s = {f['ratio']:.0f}x", "<= 3x on a GPU"),
        (f"rendered depth against float64 ray-triangle casts, {h['pixels']} sampled pixels",
         f"{h['both']} hits: {100 * h['within_0.01']:.1f} % within 0.01 footprints (max {h['max_px']:.3f}), "
         f"{h['false']} false and {h['lost']} lost hits", ">= 99.9 %"),
        (f"mesh minus two cylinders, meshed again at step {step:g} ({m['triangles']} triangles)",
         f"{'watertight' if m['watertight'] else 'NOT watertight'}; volume "
         f"{(m['volume'] / m['twin_volume'] - 1) * 100:+.2f} % against the twin's {lattice}^3 lattice", "within 0.5 %"),
    ]
    return (f"`python benchmarks/mesh_field.py --out docs/bench/mesh_field.md`: a bumpy torus of {triangles} triangles, "
            f"{os.cpu_count()} CPUs, {gl}.\n\n| figure | measured | goal |\n|---|---|---|\n"
            + "".join(f"| {a} | {b} | {c} |\n" for a, b, c in rows))


if __name__ == "__main__":
    main()
