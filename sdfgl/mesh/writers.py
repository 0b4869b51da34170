"""Mesh files: binary STL, OBJ + MTL, PLY, glTF (.glb / .gltf) and 3MF.

STL, PLY and OBJ are written here with numpy (fast; OBJ so each scene colour becomes a
material in the .mtl beside it); 3MF with the standard library (sdfgl.mesh.threemf: base
materials per colour, the model's unit); trimesh writes glTF. glTF indices are 32-bit whenever a mesh has more than
65535 vertices (the writer picks the index type from the count, never wrapping).

:func:`write_parts` writes several named parts to one file (3MF, OBJ, glTF): one object
(3MF), ``o`` group (OBJ) or node (glTF) per part, each with its materials.
"""
from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SdfglError
from ..files import written_atomically
from ..values.units import unit_name
from .deps import require
from .parts import Part, part_of
from .threemf import write_3mf

FORMATS = (".stl", ".obj", ".ply", ".glb", ".gltf", ".3mf")
PART_FORMATS = (".obj", ".glb", ".gltf", ".3mf")
"""The formats that keep several named parts apart."""


def write(mesh: Any, path: Path, **options: Any) -> Path:
    """Write ``mesh`` to ``path`` in the format its suffix names; ``units=`` (3MF only, default
    millimetres) names the unit the scene's coordinates are taken as."""
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise SdfglError(f"cannot write mesh file '{path}': unknown format {suffix or '(no suffix)'!r}; "
                         f"use one of {', '.join(FORMATS)}")
    units = options.pop("units", None)
    if options:
        raise SdfglError(f"mesh save: unknown option(s) {', '.join(sorted(options))} for '{path}'")
    if units is not None and suffix != ".3mf":
        raise SdfglError(f"mesh save: 'units' is stored by 3MF only, not by {suffix} ('{path}')")
    if len(mesh.faces) == 0:
        raise SdfglError(f"cannot write mesh file '{path}': the mesh is empty (no surface in the box)")
    if suffix == ".obj":
        _obj([part_of("", mesh)], path, named=False)
        return path
    if suffix == ".3mf":
        return write_parts([part_of(path.stem or "mesh", mesh)], path, units)
    with written_atomically(path, "mesh file", check=lambda tmp: check_mesh_file(tmp, suffix, len(mesh.faces))) as tmp:
        if suffix == ".stl":
            _stl(mesh, tmp)
        elif suffix == ".ply":
            _ply(mesh, tmp)
        else:
            tm = mesh.to_trimesh()
            exchange = require("trimesh").exchange
            if suffix == ".gltf":  # one file: the buffer embedded as a data URI
                tmp.write_bytes(exchange.gltf.export_gltf(tm, embed_buffers=True, include_normals=True)["model.gltf"])
            else:
                tmp.write_bytes(tm.export(file_type="glb"))
    return path


def write_parts(parts: list[Part], path: Path, units: str | None = None) -> Path:
    """Write named parts to one ``path`` (.3mf, .obj, .glb or .gltf by suffix); ``units``
    (3MF only; default millimetres) is the unit scene coordinates are taken as."""
    suffix = path.suffix.lower()
    if suffix not in PART_FORMATS:
        raise SdfglError(f"cannot write parts to '{path}': {suffix or '(no suffix)'!r} keeps no parts apart; "
                         f"use one of {', '.join(PART_FORMATS)}")
    names = [p.name for p in parts]
    if len(set(names)) != len(names):
        raise SdfglError(f"cannot write parts to '{path}': part names repeat ({', '.join(names)})")
    if units is not None and suffix != ".3mf":
        raise SdfglError(f"cannot write parts to '{path}': 'units' is stored by 3MF only, not by {suffix}")
    if suffix == ".obj":
        spaced = [n for n in names if len(n.split()) != 1]
        if spaced:
            raise SdfglError(f"cannot write parts to '{path}': OBJ names cannot hold spaces, and part "
                             f"{spaced[0]!r} has one")
        _obj(parts, path, named=True)
        return path
    unit = unit_name(units or "millimeter", f"saving '{path}'")
    faces = sum(len(p.faces) for p in parts)
    with written_atomically(path, "mesh file", check=lambda tmp: check_mesh_file(tmp, suffix, faces)) as tmp:
        if suffix == ".3mf":
            write_3mf(parts, tmp, unit)
        else:
            _gltf_parts(parts, tmp, suffix)
    return path


def _gltf_parts(parts: list[Part], path: Path, suffix: str) -> None:
    """A glTF scene with one node per part and material (a PBR base colour each)."""
    trimesh = require("trimesh")
    scene = trimesh.Scene()
    for part in parts:
        for name, v, f, n, rgb in part.split():
            material = trimesh.visual.material.PBRMaterial(name=name, baseColorFactor=[*map(float, rgb), 1.0],
                                                           metallicFactor=0.0, roughnessFactor=0.8)
            tm = trimesh.Trimesh(v, f, vertex_normals=n, process=False, validate=False,
                                 visual=trimesh.visual.TextureVisuals(material=material))
            scene.add_geometry(tm, geom_name=name, node_name=name)
    if suffix == ".gltf":
        path.write_bytes(trimesh.exchange.gltf.export_gltf(scene, embed_buffers=True, include_normals=True)
                         ["model.gltf"])
    else:
        path.write_bytes(scene.export(file_type="glb"))


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


def _obj(parts: list[Part], path: Path, named: bool) -> None:
    """OBJ + MTL: one material per colour (``m<k>``, or ``part`` / ``part.k`` when ``named``),
    and with ``named`` an ``o part`` group per part."""
    mtl = path.with_suffix(".mtl")
    with written_atomically(mtl, "material file", check=lambda tmp: check_mesh_file(tmp, ".mtl", 0)) as tmp_mtl, \
            open(tmp_mtl, "w", encoding="utf-8") as fh:
        fh.write("# sdfgl mesh materials: one per scene colour\n")
        for part in parts:
            for i, rgb in enumerate(part.palette):
                fh.write(f"newmtl {_material_name(part, i, named)}\n"
                         f"Kd {rgb[0]:.4f} {rgb[1]:.4f} {rgb[2]:.4f}\nKa 0 0 0\nKs 0 0 0\nd 1\nillum 1\n\n")
    nv, nf = sum(len(p.vertices) for p in parts), sum(len(p.faces) for p in parts)
    with written_atomically(path, "mesh file", check=lambda tmp: check_mesh_file(tmp, ".obj", 0)) as tmp, \
            open(tmp, "w", encoding="utf-8") as fh:
        fh.write(f"# sdfgl mesh: {nv} vertices, {nf} triangles\nmtllib {mtl.name}\n")
        base = 1
        for part in parts:
            if named:
                fh.write(f"o {part.name}\n")
            np.savetxt(fh, part.vertices, fmt="v %.7g %.7g %.7g")
            np.savetxt(fh, part.normals, fmt="vn %.5f %.5f %.5f")
            order = np.argsort(part.material, kind="stable")
            starts = np.searchsorted(part.material[order], np.arange(len(part.palette) + 1))
            for i in range(len(part.palette)):
                f = part.faces[order[starts[i]:starts[i + 1]]] + base
                fh.write(f"usemtl {_material_name(part, i, named)}\n")
                np.savetxt(fh, np.repeat(f, 2, axis=1), fmt="f %d//%d %d//%d %d//%d")
            base += len(part.vertices)


def _material_name(part: Part, i: int, named: bool) -> str:
    if not named:
        return f"m{i}"
    return part.name if len(part.palette) == 1 else f"{part.name}.{i}"


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
