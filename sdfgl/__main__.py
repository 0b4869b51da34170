"""``python -m sdfgl``: the same command line as ``sdfgl``."""
import sys

from .cli import main

sys.exit(main())
