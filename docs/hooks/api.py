"""mkdocs hook (mkdocs.yml `hooks:`): the API reference page lists everything in ``sg.__all__``.

Each public name is looked up where it is defined *now* (its ``__module__``), so the page
follows the package when modules move, and is rendered by mkdocstrings from its docstring.
Names are grouped by the part of sdfgl that defines them; constants get a table.
"""
from __future__ import annotations

import types
from typing import Any

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.structure.files import Files
from mkdocs.structure.pages import Page

PAGE = "reference/api.md"
NAMES = {  # wrappers that sdfgl/__init__.py itself defines, by the guide page they belong to
    "show": "web", "widget": "web", "save_html": "web", "set_preview": "web",
    "render_pbr": "pbr", "to_mitsuba": "pbr",
}
GROUPS = [  # (title, module prefixes under sdfgl), in page order
    ("Rendering", ("render", "raster", "compiler", "evaluate", "gl", "settings")),
    ("Cameras", ("camera",)),
    ("The look", ("look",)),
    ("Modelling", ("nodes",)),
    ("Live parameters and animation", ("params", "functions", "animate")),
    ("Meshes", ("mesh",)),
    ("The viewer, notebooks and HTML", ("web", "viewer")),
    ("Live control (MIDI and OSC)", ("live",)),
    ("Physically based renders", ("pbr",)),
    ("Scenes as data", ("scene_io",)),
    ("Errors", ("errors",)),
]


def target(name: str, obj: Any) -> str | None:
    """The dotted path mkdocstrings should render for ``sg.<name>``, or None for a constant."""
    if isinstance(obj, types.ModuleType):  # sdfgl.mesh is a callable package: its function
        return f"{obj.__name__}.{name}" if callable(getattr(obj, name, None)) else None
    if not (callable(obj) and getattr(obj, "__module__", None) and getattr(obj, "__qualname__", None)):
        return None
    return f"{obj.__module__}.{obj.__qualname__}"


def group_of(name: str, path: str) -> str:
    """The group title for a public name defined at ``path``."""
    part = NAMES.get(name) or path.split(".")[1]
    return next((title for title, prefixes in GROUPS if part in prefixes), "More")


def reference() -> str:
    """The generated markdown: constants, then one section per group."""
    import sdfgl as sg
    grouped: dict[str, list[tuple[str, str]]] = {}
    constants = []
    for name in sg.__all__:
        obj = getattr(sg, name)
        path = target(name, obj)
        if path is None:
            constants.append(f"| `sg.{name}` | `{obj!r}` |".replace("\n", " "))
        else:
            grouped.setdefault(group_of(name, path), []).append((name, path))
    lines = ["## Constants", "", "| name | value |", "|---|---|", *constants, ""]
    for title in [t for t, _ in GROUPS] + ["More"]:
        if title not in grouped:
            continue
        lines += [f"## {title}", ""]
        for name, path in grouped[title]:
            lines += [f"::: {path}", "    options:", "      heading_level: 3", f'      toc_label: "sg.{name}"', ""]
    return "\n".join(lines)


def on_page_markdown(markdown: str, page: Page, config: MkDocsConfig, files: Files) -> str:
    """Append the generated reference to the API page."""
    return markdown + "\n" + reference() if page.file.src_uri == PAGE else markdown
