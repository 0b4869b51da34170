"""The chains of sdfgl.bench_build built with DistForge, the loop a user writes.

    python -m sdfgl.peers.distforge_chain KIND N     # prints {"seconds": ...}
"""
from __future__ import annotations

import json
import math
import sys
import time


def build(kind: str, n: int) -> float:
    """Seconds to build the chain ``kind`` ("union" or "translate") of ``n`` steps."""
    import distforge as df
    t0 = time.perf_counter()
    s = df.sphere(0.5)
    if kind == "union":
        for i in range(n):
            s = s | df.sphere(0.02).translate((math.cos(i * 0.01) * 2, (i / n) * 2 - 1, math.sin(i * 0.01) * 2))
    elif kind == "translate":
        for _ in range(n):
            s = s.translate((1e-5, 0, 0))
    else:
        raise ValueError(kind)
    return time.perf_counter() - t0


if __name__ == "__main__":
    print(json.dumps({"seconds": build(sys.argv[1], int(sys.argv[2]))}))
