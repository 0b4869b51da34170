"""Mesh export benchmark: sdfgl against fogleman/sdf (PyPI sdf-fork) and DistForge on the same
scene at the same sample count in the same box (fogleman's CSG example; samples as fogleman
counts them; the box is sdfgl's default, given to the peers as their bounds).

Tools run interleaved round by round (the machine is shared: medians and ratios, not single
times); accuracy is |f| of the float64 twin at each tool's vertices, in units and in its own
cells. Peers are optional: a missing one is skipped with a note. DistForge needs an OpenGL
window, so it runs in a subprocess on a private Xvfb display.
Adaptive rows (``tolerance=``, sdfgl.mesh.adaptive) on the CSG part and the demo scene: the
uniform meshes at the same sample count and the adaptive one at a tolerance of 0.05 of their
cell, interleaved too: triangles, the twin's |f| at vertices and face centres, time.
Run: ``python -m sdfgl.mesh.bench [--samples N] [--rounds R]`` or as part of ``sdfgl bench``.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Callable

import numpy as np

from ..extras import installed
from ..nodes.base import Node
from ..xdisplay import start_xvfb, stop_xvfb

FOGLEMAN = """
import time, numpy as np
from sdf import sphere, box, cylinder, X, Y, Z
f = sphere(1) & box(1.5)
c = cylinder(0.5)
f -= c.orient(X) | c.orient(Y) | c.orient(Z)
t, c = time.perf_counter(), time.process_time()
pts = np.asarray(f.generate(samples=SAMPLES, bounds=BOUNDS, verbose=False))
el, cpu = time.perf_counter() - t, time.process_time() - c
np.save(OUT, pts)
print(el, cpu)
"""

DISTFORGE = """
import math, time, numpy as np
import distforge as df
from distforge.api.engine import mesh
f = df.sphere(1) & df.box(1.5)
c = df.cylinder(0.5, 4)  # DistForge's orient() aims a shape's longest side: rotate instead
f = f - (c.rotate(df.Z, math.pi / 2) | c | c.rotate(df.X, math.pi / 2))
mesh.generate(f, bounds=BOUNDS, samples=1 << 12, verbose=False)  # warm-up: shader compile
t, c = time.perf_counter(), time.process_time()
v, faces = mesh.generate(f, bounds=BOUNDS, samples=SAMPLES, verbose=False)
el, cpu = time.perf_counter() - t, time.process_time() - c
np.save(OUT, np.asarray(v, dtype=np.float64)[np.asarray(faces).ravel()])
print(el, cpu)
"""


def csg() -> Node:
    """fogleman/sdf's CSG example in sdfgl (cylinders 4 long reach through the whole part)."""
    from ..nodes import box, cylinder, sphere
    c = cylinder(0.5, 4)
    return (sphere(1) & box(1.5)) - (c.orient((1, 0, 0)) | c | c.orient((0, 0, 1)))


def _peer(code: str, samples: int, bounds: tuple, env: dict | None = None) -> tuple[tuple[float, float], np.ndarray] | str:
    """Run a peer's script; ((wall s, CPU s of all its threads), triangle corners (3M, 3)) or
    why it could not run."""
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "pts.npy"
        box = repr(tuple(tuple(float(x) for x in b) for b in bounds))
        script = code.replace("SAMPLES", str(samples)).replace("OUT", repr(str(out))).replace("BOUNDS", box)
        r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=600,
                           env={**os.environ, **(env or {})})
        if r.returncode != 0:
            last = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
            return f"failed: {last[:160]}"
        wall, cpu = (float(x) for x in r.stdout.strip().splitlines()[-1].split())
        return (wall, cpu), np.load(out)


def _accuracy(scene: Node, corners: np.ndarray) -> dict:
    """Vertices, |f| max and p99 (units and cells of the tool's own lattice), from triangle corners."""
    v = np.unique(np.round(corners, 9), axis=0)
    f = np.abs(scene.distance(v))
    lo, hi = v.min(0), v.max(0)
    # cell size: the median length of the shortest triangle edge is close to it
    tri = corners.reshape(-1, 3, 3)
    e = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2)
    cell = float(np.median(e.max(axis=1))) / np.sqrt(2)
    return {"vertices": len(v), "max_f": float(f.max()), "p99_f": float(np.percentile(f, 99)),
            "cell": cell, "extent": (hi - lo).tolist()}


def run_mesh(samples: int = 2 ** 22, rounds: int = 3, big: int | None = 1024,
             progress: Callable[[str], None] | None = None, adaptive: bool = True) -> tuple[str, dict]:
    """Time and accuracy rows (and, with ``adaptive``, :func:`run_adaptive`'s); returns (markdown, data)."""
    from .build import mesh
    say = progress or (lambda s: None)
    scene = csg()
    from .lattice import make_lattice
    box = make_lattice(scene, samples=samples).box  # every tool samples this box
    tools: dict[str, Callable[[], tuple[float, float] | str]] = {}
    corners: dict[str, np.ndarray] = {}
    times: dict[str, list[tuple[float, float]]] = {}
    notes: list[str] = []

    def timed(name: str, mode: str) -> Callable[[], tuple[float, float]]:
        def run() -> tuple[float, float]:
            t, c = time.perf_counter(), time.process_time()
            m = mesh(scene, samples=samples, mode=mode, progress=False)
            el = (time.perf_counter() - t, time.process_time() - c)
            corners[name] = m.vertices[m.faces].reshape(-1, 3)
            return el
        return run
    mesh(scene, samples=1 << 12, progress=False)  # compile the programs once
    mesh(scene, samples=1 << 12, mode="sharp", progress=False)
    tools["sdfgl"] = timed("sdfgl", "mc")
    tools["sdfgl sharp"] = timed("sdfgl sharp", "sharp")
    def peer(name: str, code: str, env: dict | None = None) -> Callable[[], tuple[float, float] | str]:
        def run() -> tuple[float, float] | str:  # (wall, CPU), keeping the peer's vertices
            r = _peer(code, samples, box, env)
            if isinstance(r, str):
                return r
            corners[name] = r[1]
            return r[0]
        return run

    if installed("sdf"):
        tools["fogleman/sdf"] = peer("fogleman/sdf", FOGLEMAN)
    else:
        notes.append("fogleman/sdf skipped: not installed (pip install sdf-fork)")
    xvfb = None
    if installed("distforge"):
        xvfb, display = start_xvfb()
        if xvfb is None:
            notes.append(f"DistForge skipped: it needs a display and {display}")
        else:
            tools["DistForge"] = peer("DistForge", DISTFORGE, {"DISPLAY": display})
    else:
        notes.append("DistForge skipped: not installed (pip install distforge)")
    try:
        for r in range(rounds):
            for name, fn in tools.items():
                say(f"mesh bench round {r + 1}/{rounds}: {name}")
                out = fn()
                if isinstance(out, str):
                    notes.append(f"{name} {out}")
                    continue
                times.setdefault(name, []).append(out)
    finally:
        if xvfb is not None:
            stop_xvfb(xvfb)
    rows = {}
    for name, ts in times.items():
        rows[name] = {"median_s": statistics.median(t[0] for t in ts), "median_cpu_s": statistics.median(t[1] for t in ts),
                      "times_s": ts, **_accuracy(scene, corners[name])}
    base = rows.get("sdfgl", {})
    lines = ["| tool | median wall (s) | sdfgl / tool (wall) | median CPU (s) | sdfgl / tool (CPU) | vertices "
             "| max abs f at vertices | p99 | max abs f (cells) |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for name, r in rows.items():
        ratio = f"{base['median_s'] / r['median_s']:.2f}" if base else "-"
        cratio = f"{base['median_cpu_s'] / r['median_cpu_s']:.2f}" if base else "-"
        lines.append(f"| {name} | {r['median_s']:.3f} | {ratio} | {r['median_cpu_s']:.3f} | {cratio} | {r['vertices']} | "
                     f"{r['max_f']:.1e} | {r['p99_f']:.1e} | {r['max_f'] / r['cell']:.3f} |")
    data: dict = {"samples": samples, "rounds": rounds, "rows": rows, "notes": notes,
                  "load": os.getloadavg()}
    md = (f"`sdfgl bench --sections mesh`: each tool meshes fogleman/sdf's CSG example (a sphere and a box "
          f"minus three cylinders) with {samples} samples in the same box, {np.round(box[0], 4).tolist()} .. "
          f"{np.round(box[1], 4).tolist()}; the tools take turns, {rounds} times, and the table gives each one's "
          f"median. CPU is the process's CPU time over all its threads (llvmpipe's and numpy's), which other "
          f"work on the machine does not inflate; |f| is the float64 twin's value at the tool's vertices.\n\n"
          + "\n".join(lines))
    if big:
        say(f"mesh bench: {big}^3 effective")
        big_row = run_big(scene, big)
        data["big"] = big_row
        md += (f"\n\n{big}^3 effective lattice ({big_row['lattice_samples']:.3g} samples dense): "
               f"{big_row['time_s']:.1f} s wall, {big_row['cpu_s']:.1f} s CPU, {big_row['sampled']:.3g} samples taken "
               f"({100 * big_row['sampled'] / big_row['lattice_samples']:.1f} %), {big_row['vertices']} vertices, "
               f"peak RSS {big_row['peak_rss_mb']:.0f} MB (process).")
    if adaptive:
        adaptive_md, data["adaptive"] = run_adaptive(samples, rounds, say)
        md += "\n\n" + adaptive_md
    if notes:
        md += "\n\n" + "\n".join(f"- {n}" for n in dict.fromkeys(notes))
    return md, data


ADAPTIVE_SHARE = 0.05  # the adaptive rows' tolerance, in cells of the uniform mesh


def run_adaptive(samples: int = 2 ** 22, rounds: int = 3,
                 progress: Callable[[str], None] | None = None) -> tuple[str, dict]:
    """Adaptive against uniform meshes on fogleman's CSG part and the demo scene; (markdown, data)."""
    from ..demo import demo_scene
    from .build import mesh
    say = progress or (lambda s: None)
    lines = ["| scene | mesh | triangles | share of uniform | max abs f at vertices (cells) "
             "| at face centres (cells) | median wall (s) | time / uniform mc | time / uniform sharp |",
             "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    data: dict = {}
    for name, scene in (("CSG part", csg()), ("demo scene", demo_scene())):
        step = mesh(scene, samples=samples, progress=False).step  # also compiles the programs
        tol = ADAPTIVE_SHARE * step
        mesh(scene, samples=1 << 12, mode="sharp", progress=False)
        runs = {"uniform mc": dict(samples=samples, mode="mc"), "uniform sharp": dict(samples=samples, mode="sharp"),
                f"adaptive, tolerance {ADAPTIVE_SHARE} cell": dict(tolerance=tol)}
        times: dict[str, list[float]] = {k: [] for k in runs}
        got = {}
        for r in range(rounds):
            for kind, kw in runs.items():
                say(f"mesh bench adaptive round {r + 1}/{rounds}: {name}, {kind}")
                t = time.perf_counter()
                got[kind] = mesh(scene, progress=False, **kw)
                times[kind].append(time.perf_counter() - t)
        med = {k: statistics.median(v) for k, v in times.items()}
        base = len(got["uniform mc"].faces)
        rows = {}
        for kind, m in got.items():
            fv = float(np.abs(scene.distance(m.vertices)).max())
            fc = float(np.abs(scene.distance(m.vertices[m.faces].mean(axis=1))).max())
            rows[kind] = {"triangles": len(m.faces), "max_f_vertices": fv, "max_f_face_centres": fc,
                          "median_s": med[kind], "times_s": times[kind]}
            lines.append(f"| {name} | {kind} | {len(m.faces)} | {100 * len(m.faces) / base:.1f} % | {fv / step:.4f} | "
                         f"{fc / step:.4f} | {med[kind]:.3f} | {med[kind] / med['uniform mc']:.2f} | "
                         f"{med[kind] / med['uniform sharp']:.2f} |")
        data[name] = {"step": step, "tolerance": tol, "rows": rows}
    md = (f"Adaptive meshes (`tolerance=`) at {ADAPTIVE_SHARE} of the cell of the uniform mesh of {samples} "
          f"samples, against the uniform meshes; the meshes take turns, {rounds} times, and the table gives "
          f"medians; |f| is the float64 twin's value, in cells of the uniform mesh:\n\n" + "\n".join(lines))
    return md, data


def run_big(scene: Node, resolution: int) -> dict:
    """One large mesh: time, samples and the process's peak RSS."""
    import resource
    from .build import mesh
    t, c = time.perf_counter(), time.process_time()
    m = mesh(scene, resolution=resolution, progress=sys.stderr.isatty())
    el, cpu = time.perf_counter() - t, time.process_time() - c
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    return {"time_s": el, "cpu_s": cpu, "sampled": m.samples, "lattice_samples": m.lattice.samples, "vertices": len(m.vertices),
            "faces": len(m.faces), "peak_rss_mb": rss}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m sdfgl.mesh.bench", description=__doc__.split("\n")[0])
    p.add_argument("--samples", type=int, default=2 ** 22)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--big", type=int, default=1024, help="resolution of the large run (0: skip)")
    p.add_argument("--no-adaptive", action="store_true", help="skip the adaptive rows")
    p.add_argument("--out", type=Path, default=None, help="write mesh_bench.json here")
    a = p.parse_args(argv)
    md, data = run_mesh(a.samples, a.rounds, a.big or None, lambda s: print(s, file=sys.stderr), not a.no_adaptive)
    print(md)
    if a.out:
        a.out.mkdir(parents=True, exist_ok=True)
        (a.out / "mesh_bench.json").write_text(json.dumps(data, indent=1))
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
