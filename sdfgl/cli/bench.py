"""``sdfgl bench``: benchmark marching methods, frame time beside error."""
from __future__ import annotations

import argparse
from typing import Any

from ..extras import require_extra


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl bench`` (the harness is imported only when it is the command)."""
    b = sub.add_parser("bench", help="benchmark marching methods: frame time beside error")
    if command in (None, "bench"):
        from ..bench import add_arguments
        add_arguments(b)
    b.set_defaults(func=run)


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl bench``; its last step draws a plot, so matplotlib is checked first."""
    require_extra("plots", "matplotlib", purpose="the benchmark's Pareto plot")
    from ..bench import run as run_bench
    run_bench(a.quick, a.size, a.out, not a.no_progress, a.scenes, a.sections)
    return 0
