"""Benchmark runs in a fresh process: the wall time from its start to its exit and what it
printed (the benchmarks whose figures must not inherit the benchmark process's heap, caches
or GL context: PNG writing, chain building, the 10^6-step chain)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from typing import Any, Sequence

TIMEOUT_S = 900


def fresh_process(cmd: Sequence[str], env: dict[str, str] | None = None,
                  timeout: float = TIMEOUT_S) -> tuple[float, str] | str:
    """(wall seconds from start to exit, stdout) of ``cmd`` (``env`` added to this process's
    environment), or why it failed: "failed: " and the last line of its stderr."""
    t0 = time.perf_counter()
    r = subprocess.run(list(cmd), capture_output=True, text=True, timeout=timeout, env={**os.environ, **(env or {})})
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        last = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
        return f"failed: {last[:160]}"
    return wall, r.stdout


def python_module(module: str, *args: object) -> list[str]:
    """The command that runs ``python -m module args...`` with this interpreter."""
    return [sys.executable, "-m", module, *map(str, args)]


def last_json(stdout: str) -> dict[str, Any]:
    """The JSON object on the last line of a run's stdout."""
    return json.loads(stdout.strip().splitlines()[-1])
