"""griffe extension for the API reference: sdfgl's docstrings head their doctests "Example:",
which the Google style reads as an admonition; read it as the "Examples" section, so the
``>>>`` lines render as code (mkdocs.yml loads this through mkdocstrings' ``extensions``)."""
from __future__ import annotations

import re
from typing import Any

import griffe

HEADING = re.compile(r"^(\s*)Example:\s*$", re.MULTILINE)


class DoctestExamples(griffe.Extension):
    """Rename each docstring's "Example:" heading to "Examples:" before it is parsed."""

    def on_instance(self, *, obj: griffe.Object, **kwargs: Any) -> None:
        """Called by griffe for every object it loads."""
        if obj.docstring is not None:
            obj.docstring.value = HEADING.sub(r"\1Examples:", obj.docstring.value)
