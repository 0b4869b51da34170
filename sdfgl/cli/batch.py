"""``sdfgl batch``: run a job file (docs/batch-format.md) on local processes or a Ray cluster."""
from __future__ import annotations

import argparse
from typing import Any

from ..extras import require_extra


def add_parser(sub: Any, command: str | None) -> None:
    """Register ``sdfgl batch``."""
    p = sub.add_parser("batch", help="render the jobs of a JSON job file (local processes or Ray); resumable",
                       description="Render every job of JOBFILE whose outputs do not exist yet. A failing job is "
                                   "retried, then reported; the others go on. Exit status 1 if any job failed.")
    p.add_argument("jobfile", help="JSON job file (see docs/batch-format.md)")
    p.add_argument("--workers", type=int, help="local worker processes, one GL context each (default: CPU count)")
    p.add_argument("--ray", metavar="ADDRESS",
                   help="run on a Ray cluster: 'auto' (the running one), HOST:PORT, ray://..., or 'local' "
                        "(start one here with --workers CPUs); needs sdfgl[ray]")
    p.add_argument("--retries", type=int, default=1, help="extra attempts for a failing job (default 1)")
    p.add_argument("--timeout", type=float, default=600.0,
                   help="seconds one attempt at a job may take, 0 for no limit (default 600)")
    p.add_argument("--force", action="store_true", help="render finished jobs again")
    p.add_argument("--allow-outside", action="store_true",
                   help="let jobs write outside the job file's folder (absolute or ../ output paths)")
    p.add_argument("--report", help="also write the summary as JSON to this file")
    p.add_argument("--list", action="store_true", help="print the expanded jobs and exit")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(a: argparse.Namespace) -> int:
    """Run ``sdfgl batch``; exit status 1 if any job failed."""
    from ..animate.batch import run_batch, write_report
    from ..animate.jobfile import load_jobs
    jobs = load_jobs(a.jobfile, allow_outside=a.allow_outside)
    if a.list:
        for j in jobs:
            cam = j.camera if j.camera is not None else "(scene's camera)"
            print(f"{j.index}\t{j.label}\t{j.scene}\t{j.size[0]}x{j.size[1]}\t{cam}\t{', '.join(j.outputs)}")
        return 0
    if a.ray:
        require_extra("ray", "ray", purpose="sdfgl batch --ray")
    summary = run_batch(jobs, workers=a.workers, ray=a.ray, retries=a.retries, force=a.force,
                        progress=not a.no_progress, timeout=a.timeout or None)
    print(summary.text())
    if a.report:
        write_report(summary, a.report)
    return 1 if summary.failed else 0
