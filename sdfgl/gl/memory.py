"""Keeping the process's memory flat while many shaders are compiled.

llvmpipe compiles every program on its own threads, and glibc gives each thread that
allocates its own malloc arena. Memory freed when a program is released then stays in
those arenas, fragmented, and the resident size grows by some 10 to 20 KB for every
distinct shader ever drawn, whatever the program cache keeps. With at most two arenas the
freed memory is reused and the growth is gone (``benchmarks`` has the soak that measures
it). A ``MALLOC_ARENA_MAX`` set in the environment is left as it is.
"""
from __future__ import annotations

import ctypes
import os
import sys

M_ARENA_MAX = -8  # glibc's mallopt parameter number
ARENAS = 2

_done = False


def limit_malloc_arenas() -> bool:
    """Cap glibc's malloc arenas at :data:`ARENAS` (once per process, before GL threads start);
    True if the cap is in force. Does nothing off glibc or when ``MALLOC_ARENA_MAX`` is set."""
    global _done
    if _done:
        return True
    if not sys.platform.startswith("linux") or "MALLOC_ARENA_MAX" in os.environ:
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt  # the process's own symbols: libc's, without a library search
    except (OSError, AttributeError):  # not glibc
        return False
    _done = bool(mallopt(M_ARENA_MAX, ARENAS))
    return _done
