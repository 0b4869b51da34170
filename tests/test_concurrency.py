"""Rendering from any thread, and after fork (os.fork, multiprocessing fork and spawn)."""
from __future__ import annotations

import multiprocessing as mp
import os
import pickle
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import sdfgl as sg

SIZE = (40, 30)
TIMEOUT_S = 120  # a regression (a hang in GL after fork) fails here instead of hanging CI
FRESH = "SDFGL_TEST_FRESH_PROCESS"


@pytest.fixture
def in_fresh_process(request) -> bool:
    """True in the test runner, after the test has passed in a fresh interpreter (pytest in a
    subprocess, this test alone); False in that interpreter, where the body runs. A fork copies
    only the forking thread: in a test-runner process with threads of its own (pytest-xdist's
    I/O thread, servers left by other files) the child can inherit a lock held by one of them,
    which is the runner's hazard, not the one these tests check."""
    if os.environ.get(FRESH) == request.node.nodeid:
        return False
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:xdist", "-p", "no:cacheprovider",
                        request.node.nodeid], env={**os.environ, FRESH: request.node.nodeid},
                       cwd=request.config.rootpath, capture_output=True, text=True, timeout=3 * TIMEOUT_S)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    return True


def scene(i: int) -> sg.Node:
    """Distinct small scenes (each its own shader source)."""
    return (sg.sphere(0.8 + 0.01 * i) & sg.box(1.2 + 0.003 * (i % 7))).color(0.9, 0.3 + 0.001 * (i % 500), 0.2)


def image(i: int) -> bytes:
    """Colour and depth of scene i, as bytes (picklable across processes)."""
    res = sg.render(scene(i), size=SIZE, shadows=False, ao=False, outputs=("color", "depth"))
    return res.color.tobytes() + res.depth.tobytes()


def points(n: int = 500) -> np.ndarray:
    return np.random.default_rng(1).uniform(-1.5, 1.5, (n, 3))


def test_main_thread_first_then_a_worker_renders_cached_and_new_scenes():
    a0, b0 = image(0), image(1)  # the main thread renders first
    out: dict[str, bytes] = {}

    def worker() -> None:
        out["cached"] = image(0)
        out["new"] = image(200)

    t = threading.Thread(target=worker)
    t.start()
    t.join(TIMEOUT_S)
    assert out["cached"] == a0
    assert out["new"] == image(200)
    assert image(1) == b0


@pytest.mark.slow
def test_six_threads_render_concurrently_identical_to_serial():
    jobs = [(t, i) for t in range(6) for i in (t + 1, t + 2, 100 + t, 0)]  # shared, cached and new scenes
    got: dict[tuple[int, int], bytes] = {}
    errors: list[BaseException] = []
    start = threading.Barrier(6)

    def worker(t: int) -> None:
        try:
            start.wait()
            for tt, i in jobs:
                if tt == t:
                    got[(t, i)] = image(i)
        except BaseException as exc:  # noqa: BLE001 - reported below
            errors.append(exc)

    threads = [threading.Thread(target=worker, args=(t,)) for t in range(6)]
    for th in threads:
        th.start()
    for th in threads:
        th.join(TIMEOUT_S)
    assert not errors, errors
    assert len(got) == len(jobs)
    for (t, i), img in got.items():
        assert img == image(i), f"thread {t}, scene {i}"


def test_evaluate_from_threads_matches_serial():
    s = sg.sphere(1) | sg.torus(1.2, 0.2)
    pts = points()
    serial = sg.evaluate(s, pts)
    got: list[np.ndarray] = []
    threads = [threading.Thread(target=lambda: got.append(sg.evaluate(s, pts))) for _ in range(4)]
    for th in threads:
        th.start()
    for th in threads:
        th.join(TIMEOUT_S)
    assert len(got) == 4 and all(np.array_equal(g, serial) for g in got)


def _wait_child(pid: int) -> int:
    deadline = time.time() + TIMEOUT_S
    while time.time() < deadline:
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            return os.waitstatus_to_exitcode(status)
        time.sleep(0.05)
    os.kill(pid, 9)
    os.waitpid(pid, 0)
    pytest.fail("the forked child hung (killed after the timeout)")


def test_os_fork_child_renders_with_its_own_context(tmp_path, in_fresh_process):
    if in_fresh_process:
        return
    cached = image(0)
    out = tmp_path / "child.pkl"
    pid = os.fork()
    if pid == 0:  # child: render a scene the parent has cached, and a new one
        code = 1
        try:
            out.write_bytes(pickle.dumps((image(0), image(300), os.getpid())))
            code = 0
        finally:
            os._exit(code)
    assert _wait_child(pid) == 0
    child_cached, child_new, child_pid = pickle.loads(out.read_bytes())
    assert child_pid != os.getpid()
    assert child_cached == cached
    assert child_new == image(300)
    assert image(0) == cached  # the parent renders on after the fork


@pytest.mark.parametrize("method", ["fork", "spawn"])
def test_multiprocessing_pool_renders_identical_to_serial(method, in_fresh_process):
    if in_fresh_process:
        return
    image(0)  # the parent holds a live context when the pool starts
    ids = [0, 1, 2, 3, 400, 401]
    with mp.get_context(method).Pool(2) as pool:
        got = pool.map_async(image, ids).get(TIMEOUT_S)
    assert got == [image(i) for i in ids]


def test_fork_while_another_thread_renders(tmp_path, in_fresh_process):
    """The at-fork handler waits for GL work in flight; both sides render on afterwards."""
    if in_fresh_process:
        return
    expected = {i: image(i) for i in (0, 1)}
    stop = threading.Event()
    seen: list[bool] = []

    def busy() -> None:
        while not stop.is_set():
            seen.append(image(len(seen) % 2) == expected[len(seen) % 2])

    th = threading.Thread(target=busy)
    th.start()
    try:
        while not seen:
            time.sleep(0.01)
        out = tmp_path / "child.pkl"
        pid = os.fork()
        if pid == 0:
            code = 1
            try:
                out.write_bytes(pickle.dumps(image(1)))
                code = 0
            finally:
                os._exit(code)
        assert _wait_child(pid) == 0
        assert pickle.loads(out.read_bytes()) == expected[1]
        n = len(seen)
        deadline = time.time() + TIMEOUT_S
        while len(seen) < n + 2 and time.time() < deadline:
            time.sleep(0.01)
    finally:
        stop.set()
        th.join(TIMEOUT_S)
    assert len(seen) >= n + 2 and all(seen)
