"""The Ray back end of ``run_batch``: one task per job, files sent back to the driver.

Workers may run on other machines, so each task gets the scene file's bytes (put in the
object store once per file) and returns its PNG / .npz bytes; the driver writes them
atomically, exactly as the local pool does. Retries are counted by the same tracker
(Ray's own task retries are off), so a failing job is reported the same way.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..errors import SdfglError
from .jobfile import Job
from .worker import Outcome, init_worker, run_job

if TYPE_CHECKING:  # pragma: no cover
    from .batch import Tracker


def _task(job: Job, scene_text: bytes, threads: int, timeout: float | None) -> Outcome:
    init_worker(threads)
    return run_job(job, write=False, scene_text=scene_text, timeout=timeout)


def _connect(address: str, workers: int | None) -> Any:
    try:
        import ray
    except ImportError:
        raise SdfglError("batch --ray needs Ray: pip install 'sdfgl[ray]'") from None
    if ray.is_initialized():
        return ray
    kwargs: dict[str, Any] = {"include_dashboard": False, "log_to_driver": False, "configure_logging": False}
    try:
        if address == "local":
            # "local" always starts a fresh cluster: a RAY_ADDRESS variable or the address file
            # a killed cluster leaves in /tmp/ray would otherwise be joined (and num_cpus refused)
            ray.init(address="local", num_cpus=workers, **kwargs)
        else:
            ray.init(address=address, **kwargs)
    except Exception as exc:  # ray raises ConnectionError, RuntimeError, ValueError ...
        raise SdfglError(f"batch: cannot connect to the Ray cluster at '{address}': {exc}") from None
    return ray


def run_ray(jobs: list[Job], address: str, workers: int | None, tracker: "Tracker", timeout: float | None) -> int:
    """Run ``jobs`` as Ray tasks (one CPU each); returns the cluster's CPU count."""
    ray = _connect(address, workers)
    cpus = int(ray.cluster_resources().get("CPU", 1))
    threads = 1  # one llvmpipe thread per task: Ray runs one task per CPU
    task = ray.remote(num_cpus=1, max_retries=0)(_task)
    texts: dict[str, Any] = {}
    for job in jobs:
        if job.scene not in texts:
            p = Path(job.scene)  # a missing file is reported per job by the worker, as locally
            texts[job.scene] = ray.put(p.read_bytes() if p.is_file() else None)
    queue = list(jobs)
    running: dict[Any, Job] = {}
    while queue or running:
        while queue and len(running) < 2 * cpus:
            job = queue.pop(0)
            tracker.started(job)
            running[task.remote(job, texts[job.scene], threads, timeout)] = job
        ready, _ = ray.wait(list(running), num_returns=1)
        for ref in ready:
            job = running.pop(ref)
            try:
                out = ray.get(ref)
            except Exception as exc:  # the worker process died, or Ray lost the task
                out = Outcome(job.index, False, f"Ray task failed: {type(exc).__name__}: {exc}")
            if tracker.result(out):
                queue.append(job)
    return cpus
