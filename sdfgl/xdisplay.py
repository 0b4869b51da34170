"""A private Xvfb display, for what needs X without a screen: DistForge in the mesh
benchmark, and the window tests.

Machines that share /tmp between sessions (and PID namespaces) collect X sockets and lock
files of servers that are gone or that run where this process cannot see them. Xvfb takes
a lock whose process it cannot see for a stale one and starts on a display another server
owns, so the display is chosen here: one with neither a socket nor a lock, from a start
that depends on the process id (concurrent runs look in different places), and kept only
if the server is still alive once its socket appears. Stop it with :func:`stop_xvfb`
(SIGTERM: the server removes its socket and lock; SIGKILL leaves both behind)."""
from __future__ import annotations

import os
import shutil
import subprocess
import time
from pathlib import Path

TRIES = 50  # display numbers tried


def start_xvfb(screen: str = "640x480x24") -> tuple[subprocess.Popen | None, str]:
    """Start Xvfb on a free display: (process, ":n"), or (None, why it could not)."""
    if shutil.which("Xvfb") is None:
        return None, "Xvfb is not installed"
    first = 300 + (os.getpid() * 7) % 600
    for n in range(first, first + TRIES):
        if Path(f"/tmp/.X11-unix/X{n}").exists() or Path(f"/tmp/.X{n}-lock").exists():
            continue
        proc = subprocess.Popen(["Xvfb", f":{n}", "-screen", "0", screen, "-nolisten", "tcp"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for _ in range(100):
            if proc.poll() is not None:  # lost the race for :n to another Xvfb (whose socket we'd use)
                break
            if Path(f"/tmp/.X11-unix/X{n}").exists():
                time.sleep(0.2)
                if proc.poll() is None:
                    return proc, f":{n}"
                break
            time.sleep(0.05)
        stop_xvfb(proc)
    return None, f"Xvfb did not start on any free display :{first}..:{first + TRIES - 1}"


def stop_xvfb(proc: subprocess.Popen) -> None:
    """Stop a server from :func:`start_xvfb` so that it removes its socket and lock file."""
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
    proc.wait()
