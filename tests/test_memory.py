"""Bounded memory: LRU caches within a settable budget, weakly held parameter checks, a soak run."""
from __future__ import annotations

import gc
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import sdfgl as sg
from sdfgl.compiler.source import ShaderSource
from sdfgl.gl.buffer_texture import BufferTexture
from sdfgl.gl.cache import LRU

ROOT = Path(__file__).resolve().parents[1]


def released(obj) -> bool:  # noqa: ANN001 - a moderngl object, or a buffer texture (its buffer)
    if isinstance(obj, BufferTexture):
        return obj.glo == 0 and released(obj.buffer)
    return type(obj.mglo).__name__ == "InvalidObject"


def test_lru_evicts_least_recently_used_within_count_and_bytes():
    gone: list[str] = []
    lru: LRU[str] = LRU(gone.append)
    for k in "abc":
        lru.put(k, k.upper(), 10)
    assert lru.get("a") == "A"  # a is now the most recent
    lru.trim(max_items=2)
    assert gone == ["B"] and "a" in lru and "c" in lru
    lru.put("d", "D", 25)
    lru.trim(max_bytes=30)
    assert gone == ["B", "C", "A"] and len(lru) == 1 and lru.bytes == 25
    lru.trim(max_bytes=1)  # the newest always stays
    assert len(lru) == 1


def test_program_cache_releases_the_least_recently_used():
    r = sg.Renderer(budget=sg.CacheBudget(programs=3))
    scenes = [sg.sphere(0.5 + 0.01 * i).translate((0.1, 0, 0)) for i in range(5)]
    progs = []
    for s in scenes:
        res = r.render(s, size=(8, 8), shadows=False, ao=False)
        progs.append(r.programs.get(res.source))
    assert len(r.programs) == 3 and r.programs.evictions == 2 and r.programs.compiles == 5
    assert released(progs[0]) and released(progs[1]) and not released(progs[4])
    c = r.programs.compiles
    r.render(scenes[4], size=(8, 8), shadows=False, ao=False)
    assert r.programs.compiles == c  # still cached
    r.render(scenes[0], size=(8, 8), shadows=False, ao=False)
    assert r.programs.compiles == c + 1  # evicted earlier: compiled again


def test_cache_budget_is_settable_and_validated():
    before = sg.cache_budget()
    try:
        assert sg.cache_budget(programs=5).programs == 5
        r = sg.Renderer()
        for i in range(7):
            r.render(sg.box(1 + 0.01 * i), size=(8, 8), shadows=False, ao=False)
        assert len(r.programs) == 5
    finally:
        sg.cache_budget(**vars(before))
    with pytest.raises(sg.ParameterError, match="programs"):
        sg.cache_budget(programs=0)
    with pytest.raises(sg.ParameterError, match="unknown limit"):
        sg.cache_budget(shaders=3)
    with pytest.raises(sg.ParameterError, match="targets_mb"):
        sg.CacheBudget(targets_mb=float("inf"))


def test_render_targets_are_bounded_by_bytes():
    r = sg.Renderer(budget=sg.CacheBudget(targets_mb=1))
    s = sg.sphere(1)
    for size in ((300, 300), (500, 500), (64, 64), (300, 300)):
        res = r.render(s, size=size, shadows=False, ao=False)
        assert res.color.shape == (size[1], size[0], 3)
    assert len(r.targets) == 2 and r.targets._lru.bytes <= 2**20  # 300x300 and 64x64 RGBA8
    big = r.render(s, size=(600, 600), shadows=False, ao=False, outputs=("color", "depth"))  # over budget: works
    assert big.depth.shape == (600, 600) and len(r.targets) == 1


def test_data_textures_are_bounded_by_bytes():
    r = sg.Renderer(budget=sg.CacheBudget(data_mb=10))

    def source(i: int) -> ShaderSource:
        return ShaderSource(f"#version 330 core\n// {i}", (), data=(("uData", np.full((512, 512, 4), i, np.float32)),))  # 4 MB

    sources = [source(i) for i in range(4)]
    texs = [r.run(r.data.textures, r.ctx, s)[0] for s in sources]
    assert len(r.data) == 2 and r.data.bytes == 8 * 2**20
    assert released(texs[0]) and released(texs[1]) and not released(texs[3])
    again = r.run(r.data.textures, r.ctx, sources[3])[0]
    assert again is texs[3]  # cached: not uploaded again


def test_desktop_tables_are_buffer_textures_and_webgl2_tables_2d_textures():
    import moderngl
    r = sg.Renderer()
    rows = np.arange(2 * 1024 * 4, dtype=np.float32).reshape(2, 1024, 4)
    desk, web = (ShaderSource(f"{v}\n// t", (), data=(("uData", rows),)) for v in ("#version 330 core", "#version 300 es"))
    assert isinstance(r.run(r.data.textures, r.ctx, desk)[0], BufferTexture)
    assert isinstance(r.run(r.data.textures, r.ctx, web)[0], moderngl.Texture)
    # the buffer's texel i is the table's flat texel i (what dataFetch(i) reads)
    tex = r.run(r.data.textures, r.ctx, desk)[0]
    got = np.frombuffer(r.run(tex.buffer.read), np.float32).reshape(-1, 4)
    assert np.array_equal(got[1500], rows.reshape(-1, 4)[1500])


@pytest.mark.slow
def test_dead_nodes_do_not_check_live_values():
    p = sg.param(0.3)
    o = sg.rounded_box(1, p)  # radius at most half the edge: 0.5
    with pytest.raises(sg.ParameterError):
        p.value = 2
    del o
    gc.collect()
    keep = sg.rounded_box(10, p)
    p.value = 2  # only the live node (edge 10) checks it
    with pytest.raises(sg.ParameterError, match="rounded_box"):
        p.value = 6
    assert p.value == 2 and keep is not None


def test_rebuilt_nodes_do_not_pile_up_checks():
    p = sg.param(0.2)
    live = [sg.rounded_box(2, p) for _ in range(3)]
    for _ in range(20000):
        sg.rounded_box(2, p)  # rebuilt and discarded, as an animation loop would
    assert p.checks == len(p._checks) == 2 * len(live)  # radius and half-edge checks of the live nodes
    p.value = 0.5


def test_soak_rss_stays_bounded():
    """Distinct scenes and baked turntable frames with a small program budget: RSS must stay flat."""
    code = ("import sys, json; sys.path.insert(0, 'benchmarks'); import soak, sdfgl as sg\n"
            "sg.cache_budget(programs=4)\n"
            "warm = soak.run(8, 0, (24, 16))\n"
            "res = soak.run(24, 24, (24, 16))\n"
            "print(json.dumps(res))\n")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    res = json.loads(out.stdout.strip().splitlines()[-1])
    assert res["compiles"] >= 48 and res["cached_programs"] == 4
    # unbounded, each compiled program stays resident (about 2 MB here): 48 of them would add ~90 MB
    assert res["growth_mb"] < 40, res


def test_a_dropped_or_released_renderer_frees_its_gl_objects():
    from sdfgl.gl.context import gl_thread
    r = sg.Renderer()
    res = r.render(sg.sphere(0.77), size=(8, 8), shadows=False, ao=False)
    prog = r.programs.get(res.source)
    r.release()
    assert released(prog) and len(r.programs) == 0 and len(r.targets) == 0
    res = r.render(sg.sphere(0.77), size=(8, 8), shadows=False, ao=False)  # rebuilt on demand
    prog = r.programs.get(res.source)
    del r, res
    gc.collect()
    gl_thread().call(lambda: None)  # the release was queued before this
    assert released(prog)
