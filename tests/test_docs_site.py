"""The documentation site builds offline in strict mode (no broken link, no warning), its gallery
is rendered from every example at build time, its tables come from the results files, and no
page of it or of the README narrates the project's development."""
import os
import re
import runpy
import subprocess
import sys
from pathlib import Path

import pytest

import sdfgl as sg

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").rglob("*.py"))
NARRATION = re.compile(r"\b(session|issue \d+|issues? #?\d+|engineers?|work period|load average)s?\b"
                       r"|\bseed thes[ie]s|\bthe seeds?\b|\b[0-9a-f]{7,40}\b(?<![0-9]{7})", re.I)


def product_texts() -> list[Path]:
    docs = [p for p in (ROOT / "docs").rglob("*") if p.suffix in (".md", ".py") and "bench" not in p.parts]
    return [ROOT / "README.md", ROOT / "CHANGELOG.md", ROOT / "mkdocs.yml", *docs]


@pytest.mark.parametrize("path", product_texts(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_docs_do_not_narrate_the_development(path):
    hits = [m.group(0) for m in NARRATION.finditer(path.read_text(encoding="utf-8"))]
    assert not hits, f"{path.relative_to(ROOT)}: {hits[:5]}"


def test_narration_pattern_catches_what_it_should():
    assert NARRATION.search("measured in session 8") and NARRATION.search("before 18c68e5")
    assert NARRATION.search("as issue 12 asks") and NARRATION.search("the seed thesis")
    assert not NARRATION.search("1024 spheres in 12345678 cells")


def test_history_is_out_of_the_docs():
    assert not (ROOT / "docs" / "notes").exists()
    assert (ROOT / "CHANGELOG.md").read_text().startswith("# Changelog")
    assert len((ROOT / "README.md").read_text().splitlines()) <= 300


@pytest.mark.slow
def test_site_builds_strict_with_gallery_api_and_tables(tmp_path):
    pytest.importorskip("mkdocs")
    pytest.importorskip("mkdocstrings")
    site = tmp_path / "site"
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(ROOT / "mkdocs.yml"),
                        "-d", str(site)], capture_output=True, text=True, timeout=1800, cwd=ROOT,
                       env={**os.environ, "NO_MKDOCS_2_WARNING": "1"})
    assert r.returncode == 0, r.stderr[-4000:]
    assert not re.search(r"^(WARNING|ERROR)\b", r.stderr, re.M), r.stderr[-4000:]
    # The gallery: one picture per example, rendered by this build, each beside its script.
    gallery = (site / "gallery" / "index.html").read_text()
    for path in EXAMPLES:
        name = "-".join(path.relative_to(ROOT / "examples").with_suffix("").parts)
        png = site / "gallery" / f"{name}.png"
        assert png.is_file() and png.stat().st_size > 1000, f"{path.name}: no picture"
        assert f"{name}.png" in gallery and path.relative_to(ROOT).as_posix() in gallery
    # The API reference: every public name from the docstrings.
    api = (site / "reference" / "api" / "index.html").read_text()
    target = runpy.run_path(str(ROOT / "docs" / "hooks" / "api.py"))["target"]
    for name in sg.__all__:
        path = target(name, getattr(sg, name))
        assert path is None or f'id="{path}"' in api, f"sg.{name} ({path}) missing from the API reference"
    assert 'id="sdfgl.render.render"' in api and 'id="sdfgl.mesh.mesh"' in api
    # The tables: included from the files `sdfgl bench` and `sdfgl.hardcases --doc` wrote.
    bench_md = (ROOT / "docs" / "bench" / "bench.md").read_text()
    first_row = next(line for line in bench_md.splitlines() if line.startswith("| rounded_box"))
    bench = (site / "reference" / "benchmarks" / "index.html").read_text()
    assert first_row.split("|")[3].strip() in bench and "Machine:" in bench
    assert "grazing_sphere" in (site / "hardcases" / "index.html").read_text()
    assert "Keep a Changelog" in (site / "changelog" / "index.html").read_text()
