"""Mesh files: binary STL, OBJ + MTL, PLY, glTF (.glb / .gltf) and 3MF.

STL, PLY and OBJ are written here with numpy (fast; OBJ so each scene colour becomes a
material in the .mtl beside it); trimesh writes glTF and 3MF. glTF indices are 32-bit whenever a mesh has more than
65535 vertices (the writer picks the index type from the count, never wrapping).
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SdfglError
from ..files import written_atomically
from .deps import require

FORMATS = (".stl", ".obj", ".ply", ".glb", ".gltf", ".3mf")
MAX_MATERIALS = 256


def write(mesh: Any, path: Path, **options: Any) -> Path:
    """Write ``mesh`` to ``path`` in the format its suffix names."""
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise SdfglError(f"cannot write mesh file '{path}': unknown format {suffix or '(no suffix)'!r}; "
                         f"use one of {', '.join(FORMATS)}")
    if options:
        raise SdfglError(f"mesh save: unknown option(s) {', '.join(sorted(options))} for '{path}'")
    if len(mesh.faces) == 0:
        raise SdfglError(f"cannot write mesh file '{path}': the mesh is empty (no surface in the box)")
    if suffix == ".obj":
        _obj(mesh, path)
        return path
    with written_atomically(path, "mesh file", check=lambda tmp: check_mesh_file(tmp, suffix, len(mesh.faces))) as tmp:
        if suffix == ".stl":
            _stl(mesh, tmp)
        elif suffix == ".ply":
            _ply(mesh, tmp)
        else:
            tm = mesh.to_trimesh()
            exchange = require("trimesh").exchange
            if suffix == ".3mf":
                require("lxml")
                tmp.write_bytes(exchange.threemf.export_3MF(tm))
            elif suffix == ".gltf":  # one file: the buffer embedded as a data URI
                tmp.write_bytes(exchange.gltf.export_gltf(tm, embed_buffers=True, include_normals=True)["model.gltf"])
            else:
                tmp.write_bytes(tm.export(file_type="glb"))
    return path


def check_mesh_file(path: Path, suffix: str, faces: int) -> None:
    """Read back the head of a mesh file just written and check it is whole: the STL's size
    matches its triangle count, a PLY or OBJ ends where its writer ended, a GLB's length
    field matches the file, a 3MF is a readable zip."""
    size = path.stat().st_size
    with open(path, "rb") as fh:
        head = fh.read(84)
        fh.seek(max(0, size - 1))
        last = fh.read(1)
    bad = ""
    if suffix == ".stl":
        if size != 84 + 50 * faces or int(np.frombuffer(head[80:84], "<u4")[0]) != faces:
            bad = f"{size} bytes for {faces} triangles"
    elif suffix == ".ply":
        if not head.startswith(b"ply\n"):
            bad = "no PLY header"
    elif suffix in (".obj", ".mtl", ".gltf"):
        if last not in (b"\n", b"}"):
            bad = "the file stops mid-line"
    elif suffix == ".glb":
        if head[:4] != b"glTF" or int(np.frombuffer(head[8:12], "<u4")[0]) != size:
            bad = "its length field does not match the file"
    elif suffix == ".3mf":
        import zipfile
        if not zipfile.is_zipfile(path):
            bad = "not a readable zip archive"
    if bad:
        raise SdfglError(f"mesh file '{path}' came out incomplete ({bad})")


def materials(colors: np.ndarray | None, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(palette (K, 3), material index per face): face colours (the mean of their vertices')
    rounded to 8 bits per channel, coarser if needed to keep at most MAX_MATERIALS."""
    if colors is None:
        return np.array([[0.7, 0.68, 0.64]]), np.zeros(len(faces), np.int64)
    fc = colors[faces].mean(axis=1)
    levels = 255
    while True:
        q = np.round(fc * levels).astype(np.int64)
        palette, index = np.unique(q, axis=0, return_inverse=True)
        if len(palette) <= MAX_MATERIALS or levels <= 3:
            return palette / levels, index.ravel()
        levels //= 2


def _obj(mesh: Any, path: Path) -> None:
    mtl = path.with_suffix(".mtl")
    palette, index = materials(mesh.colors, mesh.faces)
    with written_atomically(mtl, "material file", check=lambda tmp: check_mesh_file(tmp, ".mtl", 0)) as tmp_mtl, \
            open(tmp_mtl, "w", encoding="ascii") as fh:
        fh.write("# sdfgl mesh materials: one per scene colour\n")
        for i, rgb in enumerate(palette):
            fh.write(f"newmtl m{i}\nKd {rgb[0]:.4f} {rgb[1]:.4f} {rgb[2]:.4f}\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n\n")
    order = np.argsort(index, kind="stable")
    starts = np.searchsorted(index[order], np.arange(len(palette) + 1))
    with written_atomically(path, "mesh file", check=lambda tmp: check_mesh_file(tmp, ".obj", 0)) as tmp, \
            open(tmp, "w", encoding="ascii") as fh:
        fh.write(f"# sdfgl mesh: {len(mesh.vertices)} vertices, {len(mesh.faces)} triangles\nmtllib {mtl.name}\n")
        np.savetxt(fh, mesh.vertices, fmt="v %.7g %.7g %.7g")
        np.savetxt(fh, mesh.normals, fmt="vn %.5f %.5f %.5f")
        for i in range(len(palette)):
            f = mesh.faces[order[starts[i]:starts[i + 1]]] + 1
            fh.write(f"usemtl m{i}\n")
            np.savetxt(fh, np.repeat(f, 2, axis=1), fmt="f %d//%d %d//%d %d//%d")


def _stl(mesh: Any, path: Path) -> None:
    """Binary STL: 80-byte header, count, then normal + 3 corners + attribute per triangle."""
    tri = mesh.vertices[mesh.faces]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    rec = np.zeros(len(tri), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    rec["n"], rec["v"] = n, tri
    with open(path, "wb") as fh:
        fh.write(b"sdfgl mesh".ljust(80, b" "))
        fh.write(np.uint32(len(tri)).tobytes())
        fh.write(rec.tobytes())


def _ply(mesh: Any, path: Path) -> None:
    """Binary little-endian PLY: positions, normals, 8-bit vertex colours, 32-bit indices."""
    fields = [("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("nx", "<f4"), ("ny", "<f4"), ("nz", "<f4")]
    if mesh.colors is not None:
        fields += [("red", "u1"), ("green", "u1"), ("blue", "u1")]
    v = np.zeros(len(mesh.vertices), dtype=fields)
    for i, c in enumerate("xyz"):
        v[c], v["n" + c] = mesh.vertices[:, i], mesh.normals[:, i]
    if mesh.colors is not None:
        rgb = np.clip(np.round(mesh.colors * 255), 0, 255).astype(np.uint8)
        v["red"], v["green"], v["blue"] = rgb[:, 0], rgb[:, 1], rgb[:, 2]
    f = np.zeros(len(mesh.faces), dtype=[("n", "u1"), ("i", "<i4", 3)])
    f["n"], f["i"] = 3, mesh.faces
    types = {"<f4": "float", "u1": "uchar"}
    head = ["ply", "format binary_little_endian 1.0", "comment sdfgl mesh", f"element vertex {len(v)}",
            *[f"property {types[t]} {name}" for name, t in fields], f"element face {len(f)}",
            "property list uchar int vertex_indices", "end_header"]
    with open(path, "wb") as fh:
        fh.write(("\n".join(head) + "\n").encode("ascii"))
        fh.write(v.tobytes())
        fh.write(f.tobytes())
