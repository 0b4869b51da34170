"""The frametime benchmark script: speed against error for every marching method.

    python demos/bench.py --quick        # under a minute
    python demos/bench.py                # the full run (tables in README.md)
"""
import sys

from sdfgl.bench import main

if __name__ == "__main__":
    sys.exit(main())
