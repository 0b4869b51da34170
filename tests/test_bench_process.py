"""Benchmark runs in a fresh process (sdfgl.bench_process): wall time, output, failures."""
import sys

from sdfgl.bench_process import fresh_process, last_json, python_module


def test_a_run_gives_its_wall_time_and_its_last_json_line():
    got = fresh_process([sys.executable, "-c", "import time; print('x'); time.sleep(0.2); print('{\"a\": 1}')"])
    assert not isinstance(got, str)
    wall, stdout = got
    assert wall >= 0.2 and last_json(stdout) == {"a": 1}


def test_a_failed_run_says_its_last_error_line():
    got = fresh_process([sys.executable, "-c", "raise SystemExit('no such scene')"])
    assert got == "failed: no such scene"
    assert fresh_process([sys.executable, "-c", "import os"], env={"X": "1"}, timeout=60)[1] == ""


def test_python_module_runs_this_interpreter():
    assert python_module("sdfgl.bench_big", 10, 32, 24) == [sys.executable, "-m", "sdfgl.bench_big", "10", "32", "24"]
