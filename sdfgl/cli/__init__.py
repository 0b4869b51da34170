"""Command line: ``sdfgl render | shader | view | html | mesh | pbr | bench | animate | batch | studio``
(also ``python -m sdfgl`` and ``python -m sdfgl.cli``).

One module a subcommand, each with ``add_parser(sub, command)`` and ``run(args)``; the
argument, scene and camera code they share is public in :mod:`sdfgl.cli.common`.
"""
from __future__ import annotations

import argparse
import sys
from typing import Sequence

from ..errors import SdfglError
from ..version import __version__
from . import animate, batch, bench, html, mesh, pbr, render, shader, studio, view

SUBCOMMANDS = (render, shader, view, html, mesh, pbr, bench, animate, batch, studio)
"""The subcommand modules, in the order ``sdfgl --help`` lists them."""

__all__ = ["build_parser", "main", "SUBCOMMANDS"]


def build_parser(argv: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The ``sdfgl`` argument parser; given ``argv``, only the chosen subcommand's heavy
    modules are imported (None builds everything)."""
    parser = argparse.ArgumentParser(prog="sdfgl", description="Render signed-distance-function scenes with GLSL.")
    parser.add_argument("--version", action="version", version=f"sdfgl {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    command = next((x for x in argv if not x.startswith("-")), None) if argv is not None else None
    for module in SUBCOMMANDS:
        module.add_parser(sub, command)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line (``sys.argv[1:]`` when ``argv`` is None); returns the exit status."""
    args = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(args)
    a = parser.parse_args(args)
    try:
        return int(a.func(a))
    except SdfglError as exc:
        print(f"sdfgl: error: {exc}", file=sys.stderr)
        return 2
