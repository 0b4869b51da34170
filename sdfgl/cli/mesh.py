"""``sdfgl mesh scene.py -o part.stl --step 0.01``: mesh a scene file (or the demo), optionally with its report.

A scene file that defines ``parts = {"body": node, "inlay": node}`` is written part by part
(.3mf, .obj, .glb, .gltf: one object per part with its materials; see sdfgl.mesh.multipart);
``--units mm`` says what a scene unit is in a 3MF file.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

from ..errors import SdfglError
from ..extras import require_extra
from .common import add_scene_arguments, load_scene_args

TRIMESH_FORMATS = {".glb": ("trimesh",), ".gltf": ("trimesh",)}
"""Mesh formats written through trimesh, and the packages of the ``mesh`` extra each needs."""


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl mesh``."""
    m = sub.add_parser("mesh", help="export a scene file (or the demo) as a mesh: .stl .obj .ply .glb .gltf .3mf")
    add_scene_arguments(m, "mesh the built-in showcase scene")
    m.add_argument("-o", "--output", default="out.stl", help="mesh path; the suffix picks the format (default out.stl)")
    size = m.add_mutually_exclusive_group()
    size.add_argument("--step", type=float, help="cell size in scene units")
    size.add_argument("--resolution", type=int, help="cells along the longest side of the box")
    size.add_argument("--samples", type=int, help="dense sample count (default 2^22, as fogleman/sdf counts)")
    m.add_argument("--tolerance", type=float,
                   help="adaptive mesh: max |field| at vertices and distance from face centres to the surface, "
                        "in scene units (few triangles where flat; implies --sharp unless --mc; needs sdfgl[mesh])")
    m.add_argument("--bounds", type=float, nargs=6, metavar=("X0", "Y0", "Z0", "X1", "Y1", "Z1"),
                   help="box to mesh (default: the scene bounds padded by one cell; needed if unbounded)")
    kind = m.add_mutually_exclusive_group()
    kind.add_argument("--sharp", action="store_true", help="dual contouring: keep edges and corners sharp")
    kind.add_argument("--mc", action="store_true", help="marching cubes (the default without --tolerance)")
    m.add_argument("--units", help="what one scene unit is in a .3mf file: mm (default), cm, m, inch, ft, um; "
                                   "coordinates are not scaled")
    m.add_argument("--report", action="store_true",
                   help="also measure the mesh against the float64 twin and print the accuracy report "
                        "(slow: often many times the meshing; needs scipy, sdfgl[mesh])")
    g = m.add_argument_group("printing checks (printed when any is given; lengths in --units, default mm)")
    g.add_argument("--min-wall", type=float, metavar="T", help="flag the thinnest wall thinner than T, with where it is")
    g.add_argument("--overhang", type=float, metavar="DEG",
                   help="area facing down more than DEG degrees from vertical (default 45)")
    g.add_argument("--density", type=float, metavar="G_CM3", help="the mass for this density in g/cm^3")
    m.add_argument("--no-report", action="store_true", help=argparse.SUPPRESS)  # the report used to be the default
    m.add_argument("--quiet", action="store_true", help="no progress line")
    m.set_defaults(func=run)


def check_extras(a: argparse.Namespace) -> None:
    """Refuse before meshing when the output format or ``--report`` needs a missing package."""
    suffix = Path(a.output).suffix.lower()
    if suffix in TRIMESH_FORMATS:
        require_extra("mesh", *TRIMESH_FORMATS[suffix], purpose=f"writing '{a.output}'")
    if a.report:
        require_extra("mesh", "scipy", purpose="the mesh report (--report)")
    if a.tolerance is not None:
        require_extra("mesh", "pyfqmr", "meshoptimizer", purpose="an adaptive mesh (--tolerance)")


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl mesh``."""
    from ..mesh.build import mesh
    if a.no_report:
        print("sdfgl mesh: --no-report is no longer needed: the report is off unless --report is given",
              file=sys.stderr)
    check_extras(a)
    if a.units is not None:
        from ..values.units import unit_name
        unit_name(a.units, "--units")
        if Path(a.output).suffix.lower() != ".3mf" and not print_checks_asked(a):
            raise SdfglError(f"--units is stored by 3MF only, not by '{a.output}' "
                             "(it also names the unit of the printing checks)")
    sf = load_scene_args(a)
    bounds = None if a.bounds is None else (a.bounds[:3], a.bounds[3:])
    options = dict(step=a.step, resolution=a.resolution, samples=a.samples, bounds=bounds,
                   mode="sharp" if a.sharp else "mc" if a.mc else None, progress=not a.quiet,
                   tolerance=a.tolerance)
    if sf.parts is not None:
        return write_parts_file(sf.parts, a, options)
    t0 = time.perf_counter()
    m = mesh(sf.scene, **options)
    if len(m.faces) == 0:
        raise SdfglError("the scene has no surface inside the box: nothing to write")
    path = m.save(a.output, **file_units(a))
    t = time.perf_counter() - t0
    refined = "" if m.default_step is None else f" (refined from {m.default_step:.4g} for thin or small curved parts)"
    if m.tolerance is not None:
        refined += f", tolerance {m.tolerance:g} (max error {m.error:.3g} measured)"
    print(f"wrote {path}: {len(m.vertices)} vertices, {len(m.faces)} triangles, cell {m.step:.4g}{refined}, "
          f"{m.timings['total_s']:.2f} s meshing, {t:.2f} s with writing")
    if a.report:
        print(f"report: {m.report()}")
    if print_checks_asked(a):
        print(f"print: {print_checks(m, a)}")
    sys.stdout.flush()
    return 0


def print_checks_asked(a: argparse.Namespace) -> bool:
    """Whether any of ``--min-wall --overhang --density`` was given."""
    return a.min_wall is not None or a.overhang is not None or a.density is not None


def print_checks(m: Any, a: argparse.Namespace) -> Any:
    """The mesh's printing checks as the flags ask (lengths in ``--units``, default mm)."""
    return m.print_report(min_wall=a.min_wall, overhang=45.0 if a.overhang is None else a.overhang,
                          density=a.density, units=a.units or "millimeter")


def file_units(a: argparse.Namespace) -> dict[str, str]:
    """The ``units=`` option for the writer: given, and the output is a 3MF file."""
    return {"units": a.units} if a.units is not None and Path(a.output).suffix.lower() == ".3mf" else {}


def write_parts_file(parts: dict, a: argparse.Namespace, options: dict[str, Any]) -> int:
    """Mesh and write a scene file's ``parts`` to ``a.output`` (one object per part); the
    printing checks, when asked for, are printed part by part."""
    from ..mesh.build import mesh
    from ..mesh.parts import parts_of
    from ..mesh.writers import write_parts
    t0 = time.perf_counter()
    meshes = {name: mesh(node, **options) for name, node in parts.items()}
    meshed = parts_of(meshes)
    path = write_parts(meshed, Path(a.output), file_units(a).get("units"))
    sizes = ", ".join(f"{p.name} {len(p.faces)} triangles" for p in meshed)
    print(f"wrote {path}: {len(meshed)} parts ({sizes}), {time.perf_counter() - t0:.2f} s")
    if a.report:
        print("report: --report measures a single scene; it is skipped for a file of parts", file=sys.stderr)
    if print_checks_asked(a):
        for name, m in meshes.items():
            print(f"print {name}: {print_checks(m, a)}")
    sys.stdout.flush()
    return 0
