"""A one-line progress bar with rate and ETA on stderr, for ``sdfgl animate`` and ``sdfgl batch``."""
from __future__ import annotations

import sys
import time
from typing import TextIO


def _clock(seconds: float) -> str:
    s = int(round(max(seconds, 0.0)))
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}"


class ProgressBar:
    """``update(done)`` redraws ``[#####-----] 12/120 8.3 frame/s ETA 0:00:13``; ``close()`` ends the line.

    On a terminal it redraws in place; otherwise (a log file) it prints a line per tenth.
    """

    def __init__(self, total: int, unit: str = "frame", stream: TextIO | None = None) -> None:
        self.total, self.unit = max(int(total), 1), unit
        self.stream = stream or sys.stderr
        self.tty = self.stream.isatty()
        self.t0 = time.perf_counter()
        self._last_tenth = -1

    def update(self, done: int, note: str = "") -> None:
        frac = min(done / self.total, 1.0)
        elapsed = time.perf_counter() - self.t0
        rate = done / elapsed if elapsed > 0 else 0.0
        eta = (self.total - done) / rate if rate > 0 else 0.0
        bar = "#" * int(24 * frac) + "-" * (24 - int(24 * frac))
        line = f"[{bar}] {done}/{self.total} {rate:.2f} {self.unit}/s ETA {_clock(eta)} {note}"
        if self.tty:
            self.stream.write("\r" + line[:110].ljust(110))
        elif int(frac * 10) != self._last_tenth:
            self._last_tenth = int(frac * 10)
            self.stream.write(line + "\n")
        self.stream.flush()

    def close(self) -> None:
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()
