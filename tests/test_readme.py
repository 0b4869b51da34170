"""Every ```python block of README.md and of the user guide runs as pasted: in a fresh namespace
holding only ``sg`` (sdfgl) and ``np`` (numpy), in an empty folder."""
import re
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg

ROOT = Path(__file__).resolve().parents[1]
FENCE = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def blocks(path: Path) -> list[tuple[str, str]]:
    """(id, code) of each python block of a markdown file, numbered from 1."""
    text = path.read_text(encoding="utf-8")
    return [(f"{path.stem}-{i}", code) for i, code in enumerate(FENCE.findall(text), 1)]


README = blocks(ROOT / "README.md")
GUIDE = [b for page in sorted((ROOT / "docs" / "guide").glob("*.md")) for b in blocks(page)]


def run_block(code: str, folder: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(folder)
    exec(compile(code, "<markdown block>", "exec"), {"sg": sg, "np": np, "__name__": "__block__"})


def test_blocks_are_found():
    assert len(README) >= 1 and len(GUIDE) >= 10
    assert FENCE.findall("```python\nx = 1\n```\n") == ["x = 1\n"]


@pytest.mark.parametrize("code", [c for _, c in README], ids=[i for i, _ in README])
def test_readme_block_runs(code, tmp_path, monkeypatch):
    run_block(code, tmp_path, monkeypatch)


@pytest.mark.slow
@pytest.mark.parametrize("code", [c for _, c in GUIDE], ids=[i for i, _ in GUIDE])
def test_guide_block_runs(code, tmp_path, monkeypatch):
    run_block(code, tmp_path, monkeypatch)


def test_a_failing_block_fails(tmp_path, monkeypatch):
    with pytest.raises(NameError):
        run_block("print(undefined_scene)", tmp_path, monkeypatch)
