"""Optional extras (``pip install 'sdfgl[NAME]'``): check for them before long work starts.

    require_extra("plots", "matplotlib")      # raises MissingExtraError naming the pip line

The check only looks the top-level package up (no import), so it costs next to nothing and
can run before a command spends minutes on work whose last step needs the package.
"""
from __future__ import annotations

import importlib.util

from .errors import SdfglError

EXTRAS: dict[str, tuple[str, ...]] = {
    "implicit": ("sympy",),
    "plots": ("matplotlib",),
    "docs": ("mkdocs", "mkdocstrings"),
    "web": ("anywidget",),
    "mesh": ("trimesh", "scipy", "lxml", "networkx", "pyfqmr", "meshoptimizer"),
    "video": ("imageio_ffmpeg",),
    "ray": ("ray",),
    "pbr": ("mitsuba",),
    "panel": ("imgui_bundle", "OpenGL"),
    "live": ("mido", "rtmidi", "pythonosc"),
    "fast": ("isal",),
    "text": ("fontTools",),
    "meshin": ("igl", "trimesh"),
    "studio": ("tornado",),
}
"""Each extra of pyproject.toml and the modules (import names) it installs (``all`` is every
feature extra together, so it has no entry of its own)."""


class MissingExtraError(SdfglError):
    """A feature needs a package of an optional extra that is not installed."""


def installed(module: str) -> bool:
    """Whether the top-level package of ``module`` (an import name) can be imported here."""
    try:
        return importlib.util.find_spec(module.split(".")[0]) is not None
    except (ImportError, ValueError):
        return False


def require_extra(extra: str, *modules: str, purpose: str = "") -> None:
    """Raise :class:`MissingExtraError` unless every one of ``modules`` is installed.

    Args:
        extra: the extra's name in pyproject.toml (a key of :data:`EXTRAS`).
        modules: the import names needed (default: all of the extra's).
        purpose: what needs them, for the message, e.g. ``"the benchmark's plot"``.

    The message names the missing packages and the one ``pip install`` line.
    """
    if extra not in EXTRAS:
        raise ValueError(f"require_extra: unknown extra {extra!r}; known: {', '.join(EXTRAS)}")
    missing = [m for m in (modules or EXTRAS[extra]) if not installed(m)]
    if missing:
        what = purpose or "this command"
        raise MissingExtraError(f"{what} needs {', '.join(missing)}, which is not installed: "
                                f"pip install 'sdfgl[{extra}]'")
