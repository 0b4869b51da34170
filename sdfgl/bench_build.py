"""Benchmark rows of building a chain in Python, sdfgl against DistForge, each run in a fresh process.

The loop is the one a user writes (``s = s | sphere(r).translate(p)``, ``s = s.translate(d)``):
sdfgl's is :func:`sdfgl.bench_big.chain`, DistForge's :mod:`sdfgl.peers.distforge_chain`.
Runs interleave the two libraries round by round; the rows report medians and the ratio.
DistForge is a peer, not a dependency: where it is not installed its column is empty, with a note.

    python -m sdfgl.bench_build KIND N     # one sdfgl build: prints {"seconds": ...}
"""
from __future__ import annotations

import json
import statistics
import sys
import time

from .bench_process import fresh_process, last_json, python_module
from .extras import installed

KINDS = ("union", "translate")
TIMEOUT_S = 600


def _seconds(module: str, kind: str, n: int) -> float | str:
    """The build time one fresh process of ``module`` reports, or why it failed."""
    got = fresh_process(python_module(module, kind, n), timeout=TIMEOUT_S)
    return got if isinstance(got, str) else float(last_json(got[1])["seconds"])


def run_build(quick: bool) -> str:
    """The markdown table: per chain, sdfgl's and DistForge's median build seconds and the ratio."""
    n, rounds = (10 ** 4, 1) if quick else (10 ** 5, 5)
    libraries = {"sdfgl": "sdfgl.bench_build"}
    notes = []
    if installed("distforge"):
        libraries["DistForge"] = "sdfgl.peers.distforge_chain"
    else:
        notes.append("DistForge skipped: not installed (pip install distforge)")
    runs: dict[tuple[str, str], list[float]] = {}
    for _ in range(rounds):
        for kind in KINDS:
            for name, module in libraries.items():
                got = _seconds(module, kind, n)
                if isinstance(got, str):
                    notes.append(f"{name} {kind}: {got}")
                else:
                    runs.setdefault((name, kind), []).append(got)
    lines = ["| chain | sdfgl (s) | DistForge (s) | sdfgl / DistForge |", "|---|---:|---:|---:|"]
    for kind in KINDS:
        ours, theirs = (statistics.median(runs[(lib, kind)]) if (lib, kind) in runs else None
                        for lib in ("sdfgl", "DistForge"))
        cells = [f"{x:.3f}" if x is not None else "-" for x in (ours, theirs)]
        ratio = f"{ours / theirs:.2f}" if ours is not None and theirs is not None else "-"
        lines.append(f"| {n} steps of {kind} | {cells[0]} | {cells[1]} | {ratio} |")
    head = (f"Building a chain of {n} steps in a Python loop, each build in a fresh process, {rounds} interleaved "
            f"round(s), medians (the loops: sdfgl.bench_big.chain and sdfgl.peers.distforge_chain).")
    return "\n\n".join([head, "\n".join(lines)] + (["Notes: " + "; ".join(notes)] if notes else []))


def main() -> None:
    from .bench_big import chain
    kind, n = sys.argv[1], int(sys.argv[2])
    t0 = time.perf_counter()
    chain(kind, n)
    print(json.dumps({"seconds": time.perf_counter() - t0}))


if __name__ == "__main__":
    main()
