"""What the cyclic garbage collector costs while a loop builds a 10^5-node union chain.

    python benchmarks/chain_build_gc.py [n] [runs]

``s = s | sg.sphere(0.02).translate(...)`` ``n`` times (bench_big's chain), in a fresh
process per variant, variants interleaved ``runs`` times: Python's default collector, with
``gc.freeze()`` before the loop, with the youngest generation's threshold raised to 10^5, and
with the collector off. Prints median wall and process CPU seconds of the loop and the
share of the default's time that goes to collection (default minus off).
"""
import statistics
import subprocess
import sys

SETUP = {
    "default collector": "",
    "gc.freeze() before the loop": "gc.freeze()",
    "gc.set_threshold(100000, 10, 10)": "gc.set_threshold(100000, 10, 10)",
    "collector off": "gc.disable()",
}

LOOP = """
import gc, math, time
from sdfgl import bench_big
{setup}
w, c = time.perf_counter(), time.process_time()
bench_big.chain("union", {n})
print(time.perf_counter() - w, time.process_time() - c)
"""


def main(n: int = 10 ** 5, runs: int = 3) -> None:
    wall = {k: [] for k in SETUP}
    cpu = {k: [] for k in SETUP}
    for _ in range(runs):
        for name, setup in SETUP.items():
            out = subprocess.run([sys.executable, "-c", LOOP.format(setup=setup, n=n)], check=True,
                                 capture_output=True, text=True).stdout.split()
            wall[name].append(float(out[0]))
            cpu[name].append(float(out[1]))
    base = statistics.median(cpu["default collector"])
    print(f"| building a chain of {n} unions | wall s (median) | CPU s (median) | CPU vs default |")
    print("|---|---|---|---|")
    for name in SETUP:
        c = statistics.median(cpu[name])
        print(f"| {name} | {statistics.median(wall[name]):.2f} | {c:.2f} | {c / base:.2f}x |")


if __name__ == "__main__":
    main(*(int(x) for x in sys.argv[1:3]))
