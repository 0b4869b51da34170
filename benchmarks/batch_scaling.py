"""Batch throughput with 1 and 2 (or more) local workers on 200 small jobs, interleaved.

    python benchmarks/batch_scaling.py [--jobs 200] [--size 160x120] [--workers 1 2] [--rounds 2]

Each round renders the same job file once per worker count into a fresh folder
(random views of the demo scene, colour PNG + depth/normal/steps .npz). Wall time includes
starting the worker processes (spawn, import, GL context, first compile).
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import tempfile
from pathlib import Path

from sdfgl.animate.batch import run_batch

SCENE = "from sdfgl.demo import demo_scene, demo_camera\nscene = demo_scene()\ncamera = demo_camera()\n" \
        "settings = {'ground': True, 'shadows': 'soft', 'ao': True}\n"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--jobs", type=int, default=200)
    ap.add_argument("--size", default="160x120")
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--rounds", type=int, default=2)
    a = ap.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    root = Path(tempfile.mkdtemp(prefix="sdfgl-batch-scaling-"))
    (root / "scene.py").write_text(SCENE)
    (root / "jobs.json").write_text(json.dumps({"seed": 1, "jobs": [{
        "scene": "scene.py", "count": a.jobs, "size": [w, h],
        "camera": {"target": [0, 0.4, 0], "distance": {"uniform": [6, 9]}, "yaw": {"uniform": [0, 360]},
                   "pitch": {"sphere": [10, 60]}},
        "output": "out/{index:04d}.png", "data": "out/{index:04d}.npz"}]}))
    times: dict[int, list[float]] = {n: [] for n in a.workers}
    try:
        for r in range(a.rounds):
            for n in a.workers:
                shutil.rmtree(root / "out", ignore_errors=True)
                s = run_batch(root / "jobs.json", workers=n)
                assert s.done == a.jobs and not s.failed, s.text()
                times[n].append(s.seconds)
                print(f"round {r + 1}: {n} worker(s): {s.seconds:.1f} s, {s.throughput:.1f} jobs/s "
                      f"(load {os.getloadavg()[0]:.1f})", flush=True)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    med = {n: statistics.median(t) for n, t in times.items()}
    base = med[a.workers[0]]
    print(json.dumps({"jobs": a.jobs, "size": [w, h], "median_s": med,
                      "speedup": {n: base / m for n, m in med.items()}, "rounds": times,
                      "cpus": os.cpu_count()}, indent=2))


if __name__ == "__main__":
    main()
