"""``python -m sdfgl.cli``: the same command line as ``sdfgl``."""
import sys

from . import main

sys.exit(main())
