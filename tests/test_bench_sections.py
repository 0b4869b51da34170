"""The benchmark's big-scene and model sections run end to end at tiny sizes: every row they
promise is there with numbers in it (the full `sdfgl bench` takes minutes; these catch a
section broken by a change in what the frame timer returns)."""
import re

import pytest

pytestmark = pytest.mark.slow

SIZE = (32, 24)


def _rows(md: str, header: str) -> list[list[str]]:
    """The body rows of the markdown table whose header row starts with ``header``."""
    lines = md.splitlines()
    at = next(i for i, line in enumerate(lines) if line.startswith(header))
    rows = []
    for line in lines[at + 2:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip("|").split("|")])
    return rows


def _number(cell: str) -> float:
    m = re.match(r"-?\d+(\.\d+)?", cell)
    assert m, f"not a number: {cell!r}"
    return float(m.group(0))


def test_big_scene_rows_have_their_times():
    from sdfgl.bench_big import run_big, run_phases
    md = run_big(True, SIZE)
    rows = _rows(md, "| scene | objects | build s")
    names = [r[0] for r in rows]
    assert any(n.startswith("smooth union (k 0.1)") for n in names)
    assert any(n.startswith("chain of 2000 unions") for n in names)
    assert any(n.startswith("molecule") for n in names) and any(n.startswith("trees") for n in names)
    for r in rows:
        frame, ratio = _number(r[5]), _number(r[6])
        assert frame > 0 and ratio > 0, r
        assert "union(s) as data" in r[9]
    structures = _rows(md, "| scene | objects | structure")
    assert {r[2] for r in structures} == {"grid", "bvh"}
    md = run_phases(True, SIZE, fresh=300)
    phases = _rows(md, "| scene | build s")
    assert len(phases) == 6 and all(_number(r[8]) > 0 for r in phases)
    assert phases[-1][0] == "chain of 300 unions, left-deep (s = s OR x), in a fresh process"
    whole = float(re.search(r"to its exit it took ([0-9.]+) s", md).group(1))
    assert whole > _number(phases[-1][7])  # the process outlasts its row


def test_model_rows_and_the_hand_written_shader():
    from sdfgl.bench_model import run_model, run_whole
    rows = _rows(run_model(SIZE, 1, 0, (16,), False), "| scene | variant")
    assert len(rows) >= 8 and all(_number(r[2]) > 0 for r in rows)
    whole = run_whole(SIZE, 1, 0)
    assert whole is not None
    variants = {r[1]: r for r in _rows(whole, "| scene | variant")}
    assert set(variants) == {"generated", "generated, no coarse pass", "whole shader written by hand"}
    assert _number(variants["whole shader written by hand"][3]) == 1.0
    assert all(_number(r[4]) < 5 for r in variants.values())  # % of pixels off the generated image


def test_build_rows_against_distforge():
    from sdfgl.bench_build import run_build
    rows = _rows(run_build(True), "| chain | sdfgl")
    assert [r[0] for r in rows] == ["10000 steps of union", "10000 steps of translate"]
    assert all(_number(r[1]) > 0 for r in rows)
