"""Run a job file: skip finished outputs, render the rest on a local process pool or a Ray
cluster, retry failures, and report (done, skipped, failed, throughput).

    summary = run_batch("jobs.json", workers=2)        # local processes, one GL context each
    summary = run_batch("jobs.json", ray="auto")       # a running Ray cluster (sdfgl[ray])
"""
from __future__ import annotations

import json
import multiprocessing
import os
import time
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Iterable

from ..errors import ParameterError
from .jobfile import Job, load_jobs
from .progress import ProgressBar
from .worker import Outcome, init_worker, run_job, write_atomic


@dataclass
class BatchSummary:
    """The end of a batch run."""

    total: int
    done: int = 0
    skipped: int = 0
    failed: list[dict] = field(default_factory=list)   # {"job", "label", "error", "attempts"}
    retried: int = 0
    seconds: float = 0.0
    workers: int = 1
    backend: str = "local"

    @property
    def throughput(self) -> float:
        """Jobs rendered per second of wall time (skipped jobs not counted)."""
        return self.done / self.seconds if self.seconds > 0 else 0.0

    def text(self) -> str:
        lines = [f"batch: {self.total} jobs: {self.done} done, {self.skipped} skipped (already there), "
                 f"{len(self.failed)} failed; {self.seconds:.1f} s, {self.throughput:.2f} jobs/s "
                 f"({self.backend}, {self.workers} worker{'s' if self.workers != 1 else ''}"
                 f"{f', {self.retried} retries' if self.retried else ''})"]
        lines += [f"  failed {f['label']} after {f['attempts']} attempt(s): {f['error']}" for f in self.failed]
        return "\n".join(lines)

    def to_json(self) -> dict:
        return {**asdict(self), "failed_count": len(self.failed), "throughput": self.throughput}


def clear_partial(job: Job) -> None:
    """Remove temporary files a killed earlier run left beside the job's outputs."""
    for out in job.outputs:
        p = Path(out)
        if p.parent.is_dir():
            for tmp in p.parent.glob(f".{p.name}.tmp-*"):
                tmp.unlink(missing_ok=True)


def finished(job: Job) -> bool:
    """All of the job's files exist (they are written atomically, so existing means complete)."""
    return all(os.path.exists(p) for p in job.outputs)


class Tracker:
    """Attempts, retries and the summary, shared by the local and Ray back ends."""

    def __init__(self, summary: BatchSummary, jobs: list[Job], retries: int, bar: ProgressBar | None) -> None:
        self.summary, self.retries, self.bar = summary, retries, bar
        self.jobs = {j.index: j for j in jobs}
        self.attempts = {j.index: 0 for j in jobs}
        self.closed = 0

    def started(self, job: Job) -> None:
        self.attempts[job.index] += 1

    def result(self, out: Outcome) -> bool:
        """Record an attempt's outcome; True if the job should be tried again."""
        job = self.jobs[out.index]
        if out.ok:
            for path, data in out.blobs.items():
                write_atomic(path, data)
            self.summary.done += 1
        elif self.attempts[job.index] <= self.retries:
            self.summary.retried += 1
            return True
        else:
            self.summary.failed.append({"job": job.index, "label": job.label, "error": out.error,
                                        "attempts": self.attempts[job.index]})
        self.closed += 1
        if self.bar:
            self.bar.update(self.closed, f"{len(self.summary.failed)} failed" if self.summary.failed else "")
        return False


def _run_local(jobs: list[Job], workers: int, tracker: Tracker, timeout: float | None) -> None:
    """Run ``jobs`` on a spawn process pool. When a worker dies, the pool is made anew and the jobs
    that were in flight run again one at a time, so only the job that kills its worker is charged."""
    threads = max(1, (os.cpu_count() or 1) // workers)
    queue, suspects = list(jobs), []
    while queue or suspects:
        ctx = multiprocessing.get_context("spawn")  # a fresh interpreter: never the parent's GL context
        with ProcessPoolExecutor(workers, mp_context=ctx, initializer=init_worker, initargs=(threads,)) as pool:
            running: dict[Future, Job] = {}
            broken = False
            while (queue or suspects or running) and not broken:
                while (suspects and not running) or (not suspects and queue and len(running) < 2 * workers):
                    job = suspects.pop(0) if suspects else queue.pop(0)  # suspects alone: a death is theirs
                    tracker.started(job)
                    running[pool.submit(run_job, job, True, None, timeout)] = job
                done, _ = wait(running, return_when=FIRST_COMPLETED)
                alone = len(running) == 1
                for fut in done:
                    try:
                        out = fut.result()
                    except BrokenProcessPool:  # a worker died (a crash in a driver, killed by the OS)
                        broken = True
                        continue
                    if tracker.result(out):
                        queue.append(running[fut])
                    del running[fut]
            for fut, job in list(running.items()):  # finished well before the pool broke
                if fut.done() and not fut.cancelled() and fut.exception() is None:
                    if tracker.result(fut.result()):
                        queue.append(job)
                    del running[fut]
            for job in running.values():
                if alone:  # it ran by itself: it killed the worker
                    if tracker.result(Outcome(job.index, False, "the worker process died while running this job")):
                        suspects.append(job)
                else:  # one of these killed the pool: run each alone, this attempt uncounted
                    tracker.attempts[job.index] -= 1
                    suspects.append(job)


def run_batch(jobs: str | Path | Iterable[Job], workers: int | None = None, ray: str | None = None,
              retries: int = 1, force: bool = False, progress: bool = False,
              timeout: float | None = 600.0) -> BatchSummary:
    """Render every unfinished job; return the summary. Never stops at a failing job.

    ``jobs``: a job file path (docs/batch-format.md) or Job objects. ``workers``: local
    processes (default: the CPU count). ``ray``: a Ray cluster address ("auto" for the
    running one, "local" to start one here with ``workers`` CPUs); needs ``sdfgl[ray]``.
    ``retries``: extra attempts for a failing job. ``force``: redo finished jobs too.
    ``timeout``: seconds one attempt may take (None: no limit); a job past it fails and is retried.
    """
    all_jobs = load_jobs(jobs) if isinstance(jobs, (str, Path)) else list(jobs)
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ParameterError(f"batch: 'workers' must be a positive integer, got {workers!r}")
    if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
        raise ParameterError(f"batch: 'retries' must be a non-negative integer, got {retries!r}")
    if timeout is not None and not (isinstance(timeout, (int, float)) and timeout > 0):
        raise ParameterError(f"batch: 'timeout' must be a positive number of seconds or None, got {timeout!r}")
    pending = [j for j in all_jobs if force or not finished(j)]
    for j in pending:
        clear_partial(j)
    n_workers = workers or os.cpu_count() or 1
    summary = BatchSummary(total=len(all_jobs), skipped=len(all_jobs) - len(pending),
                           workers=min(n_workers, max(len(pending), 1)), backend="ray" if ray else "local")
    t0 = time.perf_counter()
    bar = ProgressBar(len(pending), "job") if progress and pending else None
    tracker = Tracker(summary, pending, retries, bar)
    if pending:
        if ray:
            from .raypool import run_ray
            summary.workers = run_ray(pending, ray, workers, tracker, timeout)
        else:
            _run_local(pending, summary.workers, tracker, timeout)
    if bar:
        bar.close()
    summary.seconds = time.perf_counter() - t0
    return summary


def write_report(summary: BatchSummary, path: str | Path) -> None:
    """The summary as JSON (written atomically)."""
    write_atomic(str(path), json.dumps(summary.to_json(), indent=2).encode())
