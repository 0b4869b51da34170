"""Whole-process start-up figures: `import sdfgl` and `sdfgl render` of an 800x600 CSG frame.

    python benchmarks/startup_times.py [runs] [--baseline DIR]

Each variant runs as a fresh process, interleaved with the others ``runs`` times, and the
median wall time is printed (with the load average, since a shared machine skews them),
beside the median CPU time (user + system) of the process: on an oversubscribed machine
the CPU time of a single-threaded start-up is the better estimate of its idle wall time
(rendering on llvmpipe uses several threads, so there CPU time can exceed wall time).
``--baseline DIR`` adds the same rows for another checkout's sdfgl (put first on
PYTHONPATH), to give ratios measured under the same load.

Bytecode is compiled first (``compileall``), as ``pip install`` does: with
PYTHONDONTWRITEBYTECODE=1 (set on this machine) a source checkout would otherwise
recompile every module in every process, about 0.2 s of CPU for sdfgl alone.
"""
from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def variants(baseline: str | None) -> dict[str, tuple[list[str], dict[str, str]]]:
    py = sys.executable
    out = str(Path(tempfile.gettempdir()) / "sdfgl_startup.png")
    render = [py, "-m", "sdfgl", "render", str(ROOT / "examples" / "csg.py"), "-o", out, "--size", "800x600"]
    v = {
        "python -c pass": ([py, "-c", "pass"], {}),
        "python -c 'import numpy'": ([py, "-c", "import numpy"], {}),
        "python -c 'import sdfgl'": ([py, "-c", "import sdfgl"], {}),
        "sdfgl render csg.py 800x600": (render, {}),
    }
    if baseline:
        env = {"PYTHONPATH": baseline}
        v["baseline: import sdfgl"] = ([py, "-c", "import sdfgl"], env)
        v["baseline: sdfgl render"] = ([py, "-m", "sdfgl.cli", *render[3:]], env)
    return v


def main() -> None:
    args = sys.argv[1:]
    baseline = None
    if "--baseline" in args:
        i = args.index("--baseline")
        baseline = args[i + 1]
        del args[i:i + 2]
    runs = int(args[0]) if args else 9
    import compileall
    for tree in [ROOT / "sdfgl"] + ([Path(baseline) / "sdfgl"] if baseline else []):
        compileall.compile_dir(str(tree), quiet=1)
    vs = variants(baseline)
    times: dict[str, list[float]] = {k: [] for k in vs}
    cpu: dict[str, list[float]] = {k: [] for k in vs}
    loads = []
    for _ in range(runs):
        loads.append(os.getloadavg()[0])
        for name, (cmd, env) in vs.items():
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, capture_output=True, env={**os.environ, **env}, cwd=tempfile.gettempdir())
            times[name].append(time.perf_counter() - t0)
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu[name].append(r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
    print(f"{runs} runs each, interleaved; 1-minute load average during the runs: "
          f"{min(loads):.1f} to {max(loads):.1f} on {os.cpu_count()} cores")
    print("| process | wall median s | wall min s | CPU median s |")
    print("|---|---|---|---|")
    for name, ts in times.items():
        print(f"| {name} | {statistics.median(ts):.3f} | {min(ts):.3f} | {statistics.median(cpu[name]):.3f} |")


if __name__ == "__main__":
    main()
