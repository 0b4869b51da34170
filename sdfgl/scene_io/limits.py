"""The limits every scene document is held to (stated in docs/scene-format.md)."""
from __future__ import annotations

FORMAT = "sdfgl-scene"
VERSION = 1

MAX_BYTES = 32 * 1024 * 1024   # size of a document file or string
MAX_NESTING = 256              # JSON nesting of objects and arrays
MAX_NODES = 200_000            # node objects in one document
MAX_ARRAY = 100_000            # items in one array
MAX_PARAMS = 10_000            # live parameters
INLINE_HEIGHT = 32             # deeper subtrees are written to the "nodes" table, so nesting stays bounded
MAX_INLINE_TRIANGLES = 250_000  # a mesh node without a file, saved with its triangles in the document (~32 bytes each)
