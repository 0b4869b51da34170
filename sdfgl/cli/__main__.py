"""``python -m sdfgl.cli``: the same command line as ``sdfgl``."""
import sys

from . import main

if __name__ == "__main__":  # importing this module (e.g. to collect docs) runs nothing
    sys.exit(main())
