"""Batch jobs: the job file, local process pool, resume, failures, Ray."""
import json
import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

import sdfgl as sg
from sdfgl.animate.batch import run_batch
from sdfgl.animate.jobfile import JobFileError, load_jobs, parse_jobs
from sdfgl.cli import main

SCENE = """import sdfgl as sg
r = sg.param(0.8, name="r")
t = sg.time()
scene = sg.union(sg.sphere(r), sg.box(0.9).rotate(30 * t, (0, 1, 0)).translate((1.3, 0, 0)), k=0.1)
camera = sg.OrbitCamera(target=(0.6, 0, 0), distance=4.5)
"""


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "scene.py").write_text(SCENE)
    return tmp_path


def write(folder, doc):
    p = folder / "jobs.json"
    p.write_text(json.dumps(doc))
    return p


def test_the_simplest_job_file_works_as_it_reads(folder, renderer):
    jf = write(folder, {"jobs": [{"scene": "scene.py", "camera": {"yaw": 30, "distance": 4}, "size": [64, 48],
                                  "output": "out/000.png"}]})
    s = run_batch(jf, workers=1)
    assert (s.done, s.skipped, s.failed) == (1, 0, [])
    img = np.asarray(Image.open(folder / "out" / "000.png"))
    ns = {}
    exec(SCENE, ns)  # the same scene in this process: the worker's image is render()'s image
    want = sg.render(ns["scene"], sg.OrbitCamera(yaw=30, distance=4), (64, 48))
    assert img.shape == (48, 64, 3) and np.array_equal(img, want.color)
    assert not [p for p in (folder / "out").iterdir() if p.name.startswith(".")]


def test_sweeps_and_random_cameras_expand_reproducibly(folder):
    doc = {"seed": 7, "defaults": {"scene": "scene.py", "size": [32, 24]},
           "jobs": [{"sweep": {"params.r": [0.5, 0.7], "camera.yaw": [0, 90, 180]}, "camera": {"distance": 4},
                     "output": "sweep/r{params.r}_y{camera.yaw:03d}.png"},
                    {"count": 50, "camera": {"yaw": {"uniform": [0, 360]}, "pitch": {"sphere": [0, 60]},
                                             "distance": {"uniform": [3, 5]}, "target": "auto"},
                     "time": {"uniform": [0, 2]}, "output": "rand/{index:04d}.png", "data": "rand/{index:04d}.npz"}]}
    jobs = parse_jobs(doc, folder)
    assert len(jobs) == 56 and [j.index for j in jobs] == list(range(56))
    assert jobs[0].output.endswith("sweep/r0.5_y000.png") and jobs[5].output.endswith("sweep/r0.7_y180.png")
    assert jobs[5].params == {"r": 0.7} and jobs[5].camera == {"distance": 4.0, "yaw": 180.0}
    rnd = jobs[6:]
    yaws = np.array([j.camera["yaw"] for j in rnd])
    pitches = np.array([j.camera["pitch"] for j in rnd])
    assert yaws.min() >= 0 and yaws.max() <= 360 and np.ptp(yaws) > 180
    assert pitches.min() >= 0 and pitches.max() <= 60 and all(0 <= j.time <= 2 for j in rnd)
    again = parse_jobs(doc, folder)
    assert [j.camera for j in again] == [j.camera for j in jobs]  # a fixed seed: the same data set
    other = parse_jobs({**doc, "seed": 8}, folder)
    assert [j.camera for j in other[6:]] != [j.camera for j in rnd]


@pytest.mark.parametrize("doc, message", [
    ({"jobs": []}, r"jobs: must be a non-empty list"),
    ({"jobs": [{"scene": "s.py"}]}, r"jobs\[0\]: needs 'output'"),
    ({"jobs": [{"scene": "s.py", "output": "a.png", "camera": {"yaw": "x"}}]}, r"jobs\[0\].camera.yaw: must be a finite number"),
    ({"jobs": [{"scene": "s.py", "output": "a.png", "camera": {"zoom": 2}}]}, r"jobs\[0\].camera: unknown camera key"),
    ({"jobs": [{"scene": "s.py", "output": "a.png", "size": [0, 4]}]}, r"jobs\[0\].size: must be \[width, height\]"),
    ({"jobs": [{"scene": "s.py", "output": "a{nope}.png"}]}, r"jobs\[0\].output: unknown field '\{nope\}'"),
    ({"jobs": [{"scene": "s.py", "output": "a.png"}, {"scene": "s.py", "output": "a.png"}]}, r"jobs\[1\]: writes"),
    ({"jobs": [{"scene": "s.py", "output": "a.png", "camera": {"yaw": {"gauss": [0, 1]}}}]},
     r"jobs\[0\].camera.yaw: unknown random value 'gauss'"),
    ({"jobs": [{"scene": "s.py", "output": "a.jpg"}]}, r"jobs\[0\].output: the colour image is written as PNG"),
])
def test_bad_job_files_name_the_json_path(tmp_path, doc, message):
    with pytest.raises(JobFileError, match=message):
        parse_jobs(doc, tmp_path)


def test_unreadable_job_file_names_file_and_line(tmp_path):
    p = tmp_path / "j.json"
    p.write_text('{"jobs": [\n  {"scene": }]}')
    with pytest.raises(JobFileError, match=r"j.json', line 2, column"):
        load_jobs(p)


@pytest.mark.slow
def test_data_outputs_params_time_and_a_broken_scene_reported_while_the_rest_finish(folder, renderer):
    (folder / "broken.py").write_text("import sdfgl as sg\nscene = sg.sphere(-1)\n")
    (folder / "hangs.py").write_text("while True:\n    pass\n")
    jf = write(folder, {"defaults": {"scene": "scene.py", "size": [40, 30], "settings": {"shadows": False}},
                        "jobs": [{"params": {"r": 0.5}, "time": 1.5, "output": "a.png", "data": "a.npz"},
                                 {"scene": "broken.py", "output": "b.png"},
                                 {"params": {"nope": 1}, "output": "c.png"},
                                 {"output": "d.png", "data": "d.npz", "channels": ["depth"]},
                                 {"scene": "hangs.py", "output": "e.png"}]})
    s = run_batch(jf, workers=2, retries=1, timeout=6)  # room for a first job that makes a GL context
    assert s.done == 2 and len(s.failed) == 3 and s.retried == 3
    fails = {f["label"]: f for f in s.failed}
    assert "broken.py', line 2: sphere: parameter 'radius' must be > 0" in fails["jobs[1]"]["error"]
    assert fails["jobs[1]"]["attempts"] == 2
    assert re.search(r"hangs.py', line [12]: the job ran past its time limit of 6 s", fails["jobs[4]"]["error"])
    assert "scene.py' has no parameter named 'nope' (named parameters: r, time)" in fails["jobs[2]"]["error"]
    ns = {}
    exec(SCENE, ns)
    ns["r"].value, ns["t"].value = 0.5, 1.5
    want = sg.render(ns["scene"], ns["camera"], (40, 30), shadows=False, outputs=("color", "depth", "normal", "steps"))
    data = np.load(folder / "a.npz")
    assert sorted(data.files) == ["depth", "normal", "steps"]
    assert np.array_equal(data["depth"], want.depth) and np.array_equal(data["normal"], want.normal)
    assert np.array_equal(data["steps"], want.steps)
    assert np.array_equal(np.asarray(Image.open(folder / "a.png")), want.color)
    assert np.load(folder / "d.npz").files == ["depth"]
    assert not (folder / "b.png").exists()
    # the CLI says the same and exits 1
    assert main(["batch", str(jf), "--workers", "1", "--retries", "0", "--timeout", "1", "--no-progress"]) == 1


def test_a_job_that_kills_its_worker_is_found_and_reported_and_no_other_job_is_charged(folder):
    (folder / "crash.py").write_text("import os\nos._exit(3)\n")
    jf = write(folder, {"defaults": {"scene": "scene.py", "size": [32, 24]},
                        "jobs": [{"count": 3, "output": "ok/{index}.png"}, {"scene": "crash.py", "output": "x.png"},
                                 {"count": 3, "output": "ok/late{index}.png"}]})
    s = run_batch(jf, workers=2, retries=1)
    assert s.done == 6 and len(s.failed) == 1, s.text()
    assert s.failed[0]["label"] == "jobs[1]" and s.failed[0]["attempts"] == 2
    assert "the worker process died while running this job" in s.failed[0]["error"]
    assert len(list((folder / "ok").glob("*.png"))) == 6


@pytest.mark.slow
def test_a_killed_run_resumes_without_redoing_finished_jobs(folder):
    jf = write(folder, {"defaults": {"scene": "scene.py", "size": [160, 120], "settings": {"aa": 2}},
                        "jobs": [{"count": 40, "camera": {"yaw": {"uniform": [0, 360]}, "distance": 4},
                                  "output": "out/{index:03d}.png"}]})
    proc = subprocess.Popen([sys.executable, "-m", "sdfgl.cli", "batch", str(jf), "--workers", "1", "--no-progress"],
                            start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    out = folder / "out"
    deadline = time.time() + 120
    while time.time() < deadline and len(list(out.glob("*.png")) if out.exists() else []) < 5:
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)  # the batch and its worker, mid-run
    proc.wait()
    first = {p.name: p.stat().st_mtime_ns for p in out.glob("*.png")}
    assert 5 <= len(first) < 40, len(first)
    for name in first:
        Image.open(out / name).load()  # every file under a final name is complete
    s = run_batch(jf, workers=2)
    assert s.skipped == len(first) and s.done == 40 - len(first) and not s.failed
    assert all((out / n).stat().st_mtime_ns == m for n, m in first.items())  # finished jobs untouched
    assert len(list(out.glob("*.png"))) == 40
    assert not [p.name for p in out.iterdir() if p.name.startswith(".")]  # the killed run's partial files are gone


@pytest.mark.slow
def test_the_same_job_file_on_a_local_ray_cluster_gives_identical_images(folder):
    import ray
    jf = write(folder, {"seed": 3, "defaults": {"scene": "scene.py", "size": [48, 36]},
                        "jobs": [{"count": 6, "camera": {"yaw": {"uniform": [0, 360]}, "distance": 4.5},
                                  "params": {"r": {"uniform": [0.5, 0.9]}}, "output": "local/{index}.png",
                                  "data": "local/{index}.npz"}]})
    local = run_batch(jf, workers=2)
    assert local.done == 6
    doc = json.loads(jf.read_text())
    doc["jobs"][0]["output"], doc["jobs"][0]["data"] = "ray/{index}.png", "ray/{index}.npz"
    jr = folder / "jobs_ray.json"
    jr.write_text(json.dumps(doc))
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        s = run_batch(jr, ray="auto")
    finally:
        ray.shutdown()
    assert s.done == 6 and not s.failed and s.backend == "ray" and s.workers == 2
    for i in range(6):
        assert (folder / "ray" / f"{i}.png").read_bytes() == (folder / "local" / f"{i}.png").read_bytes()
        a, b = np.load(folder / "ray" / f"{i}.npz"), np.load(folder / "local" / f"{i}.npz")
        assert all(np.array_equal(a[k], b[k]) for k in a.files)
