"""Build the API reference (HTML) from the docstrings with pdoc.

    python docs/make_api.py [OUT]        # default: docs/api (not tracked; rebuilt on demand)

pdoc was chosen over Sphinx because it needs no configuration tree: it reads the live
package, renders the Google-style docstrings used here, follows ``__all__`` and links
names, so the reference cannot drift from the code; the test suite builds it
(tests/test_docs.py) so a broken docstring or import fails CI.
"""
from __future__ import annotations

import sys
from pathlib import Path

# the public surface: the package (its __all__) and the modules users and node authors call
MODULES = ["sdfgl", "sdfgl.settings", "sdfgl.scene_io", "sdfgl.expr", "sdfgl.nodes.record", "sdfgl.outputs",
           "sdfgl.cli.common", "sdfgl.errors"]


def build(out: Path) -> list[Path]:
    """Write the HTML reference into ``out``; returns the pages written."""
    try:
        import pdoc
        import pdoc.render
    except ImportError:
        raise SystemExit("docs/make_api.py needs pdoc: pip install 'sdfgl[docs]'") from None
    pdoc.render.configure(docformat="google", footer_text="sdfgl API reference", search=True)
    pdoc.pdoc(*MODULES, output_directory=out)
    return sorted(out.rglob("*.html"))


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "api"
    pages = build(target)
    print(f"wrote {len(pages)} pages to {target}")
