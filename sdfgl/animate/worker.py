"""Running one batch job in a worker process: one GL context per process, scenes loaded once.

The pool starts workers with the ``spawn`` method, so a worker never inherits the
parent's GL context. ``LP_NUM_THREADS`` (llvmpipe's rasteriser threads) is set per worker
before its context exists, so N workers share the cores instead of each taking all.
"""
from __future__ import annotations

import contextlib
import hashlib
import io
import os
import signal
import tempfile
import threading
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image

from ..camera import Camera, OrbitCamera
from ..errors import ParameterError, SdfglError
from ..params import Param, Time
from ..render import Renderer
from ..scenefile import SceneFile, load_scene_file
from .jobfile import Job

_renderer: Renderer | None = None
_scenes: dict[tuple, tuple[SceneFile, dict[Param, Any]]] = {}


@dataclass
class Outcome:
    """What became of one attempt at a job."""

    index: int
    ok: bool
    error: str = ""
    seconds: float = 0.0
    blobs: dict[str, bytes] = field(default_factory=dict)  # path -> file bytes, when the driver writes


def init_worker(threads: int | None) -> None:
    """Process-pool initializer: llvmpipe threads for this worker (before any GL context exists)."""
    if threads:
        os.environ["LP_NUM_THREADS"] = str(threads)


def renderer() -> Renderer:
    """This process's renderer (its one GL context), made on first use."""
    global _renderer
    if _renderer is None:
        _renderer = Renderer()
    return _renderer


def scene_for(path: str, text: bytes | None = None) -> tuple[SceneFile, dict[Param, Any]]:
    """The scene at ``path`` (loaded once per process and file version) and its params' initial values.

    ``text``, when given, is the file's content shipped from the driver: a worker on another
    machine, where ``path`` does not exist or differs, loads that copy instead.
    """
    p = Path(path)
    if text is not None and (not p.is_file() or p.read_bytes() != text):
        digest = hashlib.sha1(text).hexdigest()[:16]
        local = Path(tempfile.gettempdir()) / "sdfgl-batch-scenes" / digest / p.name
        if not local.is_file():
            local.parent.mkdir(parents=True, exist_ok=True)
            local.write_bytes(text)
        key: tuple = ("shipped", digest)
    else:
        local = p
        try:
            st = p.stat()
            key = (str(p), st.st_mtime_ns, st.st_size)
        except OSError:
            key = (str(p), 0, 0)
    if key not in _scenes:
        try:
            sf = load_scene_file(local)
        except SdfglError as exc:
            raise SdfglError(str(exc).replace(str(local), path)) from None
        _scenes[key] = (sf, {prm: prm.value for prm in sf.scene.live_params()})
    return _scenes[key]


def _camera(job: Job, sf: SceneFile) -> Camera:
    if job.camera is None:
        return sf.camera if sf.camera is not None else OrbitCamera.framing(*sf.scene.bounds)
    spec = dict(job.camera)
    if "eye" in spec:
        return Camera(spec["eye"], spec.get("target", (0.0, 0.0, 0.0)), spec.get("up", (0.0, 1.0, 0.0)),
                      spec.get("fov", 45.0))
    if spec.get("target") == "auto" or spec.get("distance") == "auto":
        frame = OrbitCamera.framing(*sf.scene.bounds, fov=spec.get("fov", 45.0))
        if spec.get("target") == "auto":
            spec["target"] = frame.target
        if spec.get("distance") == "auto":
            spec["distance"] = frame.distance
    return OrbitCamera(**spec)


def _apply_params(job: Job, sf: SceneFile, initial: dict[Param, Any]) -> None:
    for prm, val in initial.items():  # a job sees the file's values, whatever ran before it here
        prm.value = val
    named = {prm.name: prm for prm in initial if prm.name}
    for name, val in job.params.items():
        if name not in named:
            known = ", ".join(sorted(named)) or "none"
            raise ParameterError(f"scene '{job.scene}' has no parameter named '{name}' (named parameters: {known})")
        named[name].value = val
    if job.time is not None:
        for prm in initial:
            if isinstance(prm, Time):
                prm.value = job.time


def render_job(job: Job, scene_text: bytes | None = None) -> dict[str, bytes]:
    """Render ``job`` and return the bytes of each of its files (PNG, .npz) by path."""
    sf, initial = scene_for(job.scene, scene_text)
    _apply_params(job, sf, initial)
    outputs = ("color",) + (job.channels if job.data else ())
    settings = {**sf.settings, **job.settings, "outputs": outputs}
    res = renderer().render(sf.scene, _camera(job, sf), job.size, **settings)
    files: dict[str, bytes] = {}
    if job.data:
        buf = io.BytesIO()
        np.savez_compressed(buf, **{c: getattr(res, c) for c in job.channels})
        files[job.data] = buf.getvalue()
    if job.output:
        buf = io.BytesIO()
        Image.fromarray(res.color).save(buf, format="PNG")
        files[job.output] = buf.getvalue()
    return files


def write_atomic(path: str, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and a rename."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    tmp = p.with_name(f".{p.name}.tmp-{os.getpid()}")
    try:
        tmp.write_bytes(data)
        os.replace(tmp, p)
    finally:
        tmp.unlink(missing_ok=True)


class JobTimeout(SdfglError):
    """A job ran past its time limit."""


@contextlib.contextmanager
def time_limit(seconds: float | None):
    """Raise JobTimeout in this (main) thread after ``seconds``: stops a scene file that loops forever.
    A single GL draw in progress is not interrupted; the limit fires when it returns."""
    if not seconds or threading.current_thread() is not threading.main_thread():
        yield
        return

    def expire(_sig: int, _frame: object) -> None:
        raise JobTimeout(f"the job ran past its time limit of {seconds:g} s")
    old = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def run_job(job: Job, write: bool = True, scene_text: bytes | None = None, timeout: float | None = None) -> Outcome:
    """One attempt at ``job``; never raises. ``write``: write the files here (same file system as the
    driver), else return their bytes for the driver to write. ``timeout``: seconds for the attempt."""
    t0 = time.perf_counter()
    try:
        with time_limit(timeout):
            files = render_job(job, scene_text)
        if write:
            for path, data in files.items():
                write_atomic(path, data)
            files = {}
        return Outcome(job.index, True, seconds=time.perf_counter() - t0, blobs=files)
    except SdfglError as exc:
        return Outcome(job.index, False, str(exc), time.perf_counter() - t0)
    except Exception as exc:  # a job's failure is reported, the worker lives on
        last = traceback.extract_tb(exc.__traceback__)[-1]
        return Outcome(job.index, False, f"{type(exc).__name__}: {exc} ({Path(last.filename).name}:{last.lineno})",
                       time.perf_counter() - t0)
