"""mkdocs hook (mkdocs.yml `hooks:`): the gallery, rendered from the example scripts at build time.

Every ``examples/**/*.py`` is rendered by ``sdfgl render`` (a fresh process each, exactly as a
user runs it) into a temporary folder; the pictures and the generated ``gallery.md`` (title from
the script's docstring, the picture, the command and the script itself) are added to the build as
generated files, so nothing rendered is committed and a script that fails stops the build.
"""
from __future__ import annotations

import ast
import subprocess
import sys
import tempfile
from pathlib import Path

from mkdocs.config.defaults import MkDocsConfig
from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File, Files

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
SIZE = "480x320"


def examples() -> list[Path]:
    """The example scripts, in gallery order (the top-level ones first, then examples/gallery/)."""
    return sorted(EXAMPLES.rglob("*.py"), key=lambda p: (len(p.relative_to(EXAMPLES).parts), p.as_posix()))


def slug(path: Path) -> str:
    """A file name for an example's picture: examples/gallery/tree.py -> gallery-tree."""
    return "-".join(path.relative_to(EXAMPLES).with_suffix("").parts)


def title(path: Path) -> str:
    """The first line of the script's docstring (or its name)."""
    doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8")))
    return doc.strip().splitlines()[0].rstrip(".") if doc else path.stem


def render(path: Path, out: Path) -> None:
    """Render one example with the command line, at the gallery size and the script's own settings."""
    cmd = [sys.executable, "-m", "sdfgl", "render", str(path), "-o", str(out), "--size", SIZE]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=900, cwd=ROOT)
    if r.returncode != 0 or not out.is_file():
        raise PluginError(f"gallery: {path.relative_to(ROOT)} did not render: {(r.stderr or r.stdout).strip()}")


def page(entries: list[tuple[Path, str]]) -> str:
    """The gallery's markdown: one section per example."""
    lines = ["# Gallery", "",
             f"Every picture on this page was rendered from the script below it when this site was built "
             f"(`sdfgl render SCRIPT -o PICTURE --size {SIZE}`, with the script's own camera and settings). "
             "The scripts live in `examples/` of the source tree; the test suite runs every one.", ""]
    for path, name in entries:
        rel = path.relative_to(ROOT).as_posix()
        lines += [f"## {title(path)}", "", f"![{path.stem}](gallery/{name}.png)", "",
                  f"    sdfgl render {rel} -o {path.stem}.png", "",
                  "```python", path.read_text(encoding="utf-8").rstrip(), "```", ""]
    return "\n".join(lines)


def on_files(files: Files, config: MkDocsConfig) -> Files:
    """Render every example and add the pictures and the gallery page to the build."""
    out = Path(tempfile.mkdtemp(prefix="sdfgl-gallery-"))
    entries = []
    for path in examples():
        name = slug(path)
        render(path, out / f"{name}.png")
        files.append(File.generated(config, f"gallery/{name}.png", abs_src_path=str(out / f"{name}.png")))
        entries.append((path, name))
    files.append(File.generated(config, "gallery.md", content=page(entries)))
    return files
