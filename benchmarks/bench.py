"""The frametime benchmark script: speed against error for every marching method.

    python benchmarks/bench.py --quick        # the quick tier
    python benchmarks/bench.py                # the full run (the tables of the documentation)
"""
import sys

from sdfgl.bench import main

if __name__ == "__main__":
    sys.exit(main())
