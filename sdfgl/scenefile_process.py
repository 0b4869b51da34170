"""Scene files loaded in a child process, with a time limit.

A Python scene file is the user's own code: it may loop forever, sleep, or end its process
(``os._exit``). A :class:`SceneFileLoader` runs :func:`sdfgl.scenefile.load_scene_file` in a
fresh interpreter started for the purpose (not forked: the caller's process may hold GL
contexts), so none of that reaches the caller: a load that does not finish within the time
limit is stopped (its process is killed), and a process that ends without an answer is
reported, each as a :class:`~sdfgl.errors.SceneFileError` naming the file. ::

    loader = SceneFileLoader(timeout=30)
    loader.start("scene.py")
    sf = loader.poll()             # None while loading, else the SceneFile (or it raises)
    sf = loader.wait("scene.py")   # start and wait

The scene comes back pickled (nodes and parameters pickle by their constructors, see
:mod:`sdfgl.nodes.record`; a parameter that several nodes share stays shared). The file's
``camera_path`` does not come back. A scene that cannot be pickled (nodes of a class that the
file itself defines exist only in the child) is loaded again in a thread of the caller's
process, once the child has shown that the file loads within the limit.

While :meth:`SceneFileLoader.poll` finds no load running it starts a process ahead for the
next one (it imports sdfgl meanwhile), so a reload costs the file's own time. A child ends
when its parent does.
"""
from __future__ import annotations

import json
import math
import os
import pickle
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any, NoReturn

from .errors import ParameterError, SceneFileError, SdfglError
from .scenefile import SceneFile, load_scene_file

DEFAULT_TIMEOUT_S = 30.0  # a scene file that takes longer to load is stopped
# the child's program: the parent's import path, then main() (argv: the path as JSON, the answer's fd)
_CHILD = ("import json, sys\nsys.path[:] = json.loads(sys.argv[1])\n"
          "from sdfgl.scenefile_process import main\nmain(int(sys.argv[2]))\n")


def _message(exc: BaseException) -> str:
    """The text of a load's error: ours as they are, anything else with its type."""
    return str(exc) if isinstance(exc, SdfglError) else f"{type(exc).__name__}: {exc}"


class _Child:
    """One interpreter waiting for (then running) one load; its answer is read by a thread."""

    def __init__(self) -> None:
        read, write = os.pipe()
        try:  # with this process's import path, so the child imports what this process would
            self.proc = subprocess.Popen([sys.executable, "-c", _CHILD, json.dumps(sys.path), str(write)],
                                         stdin=subprocess.PIPE, pass_fds=(write,),
                                         start_new_session=True)  # Ctrl-C is the parent's to handle
        finally:
            os.close(write)
        self.eof = threading.Event()  # the child's answer is all read (or it closed its end)
        self.answered = threading.Event()  # ... and unpickled here, off the caller's thread
        self.answer: tuple | None = None
        self.unreadable = ""  # why the answer could not be unpickled
        threading.Thread(target=self._read, args=(read,), daemon=True, name="sdfgl-scene-load").start()
        self.path = Path()
        self.started = 0.0

    def _read(self, fd: int) -> None:
        """Read the answer and unpickle it (which rebuilds the nodes: their constructors may take a while)."""
        with os.fdopen(fd, "rb") as f:
            data = f.read()
        self.eof.set()
        if data:
            try:
                self.answer = pickle.loads(data)
            except Exception as exc:  # noqa: BLE001 - a half answer: the child died while writing it
                self.unreadable = _message(exc)
        self.answered.set()

    def request(self, path: Path) -> None:
        """Load ``path`` (in this process's current folder)."""
        self.path, self.started = path, time.monotonic()
        line = json.dumps({"path": str(path), "cwd": os.getcwd()}) + "\n"
        try:
            self.proc.stdin.write(line.encode())
            self.proc.stdin.flush()
        except OSError:  # it died while waiting: result() reports its exit status
            pass

    def result(self, timeout: float) -> tuple | None:
        """The child's answer ("ok", scene, camera, settings) / ("error", text) / ("local",); None while
        it runs. Raises SceneFileError past ``timeout`` (the child is killed) or when it ended unanswered."""
        exited = self.proc.poll() is not None
        if exited and not self.eof.is_set():
            self.eof.wait(0.2)  # what it wrote before ending
        if self.answered.is_set() or (exited and not self.eof.is_set()):
            self.kill()
            if self.answer is not None:
                return self.answer
            if self.unreadable:
                raise SceneFileError(f"scene file '{self.path}': its scene could not be read back from the "
                                     f"process that loaded it ({self.unreadable})")
            self._ended()
        if time.monotonic() - self.started > timeout:
            self.kill()
            raise SceneFileError(f"scene file '{self.path}' did not finish loading within {timeout:g} s "
                                 "(an endless loop?): stopped")
        return None

    def _ended(self) -> NoReturn:
        rc = self.proc.returncode
        if rc is not None and rc < 0 and -rc in signal.valid_signals():
            how, hint = f"was killed by {signal.Signals(-rc).name}", ""
        else:
            how, hint = f"ended with exit status {rc}", " (does the file call os._exit?)"
        raise SceneFileError(f"scene file '{self.path}': the process loading it {how} before the file "
                             f"defined 'scene'{hint}")

    def kill(self) -> None:
        """End the child (it may be running the file) and reap it."""
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        if self.proc.stdin is not None:
            try:
                self.proc.stdin.close()
            except OSError:
                pass


class _ThreadLoad:
    """A load in a thread of this process (for scenes that cannot be pickled)."""

    def __init__(self, path: Path) -> None:
        self.path, self.started = path, time.monotonic()
        self.answer: tuple | None = None
        self.done = threading.Event()
        threading.Thread(target=self._run, daemon=True, name="sdfgl-scene-load").start()

    def _run(self) -> None:
        try:
            sf = load_scene_file(self.path)
            self.answer = ("ok", sf.scene, sf.camera, sf.settings)
        except BaseException as exc:  # noqa: BLE001 - reported by result(), like a child's error
            self.answer = ("error", _message(exc))
        self.done.set()

    def result(self, timeout: float) -> tuple | None:
        if self.done.is_set():
            return self.answer
        if time.monotonic() - self.started > timeout:
            raise SceneFileError(f"scene file '{self.path}' did not finish loading within {timeout:g} s")
        return None

    def kill(self) -> None:
        """A thread cannot be stopped: its answer is dropped."""


class SceneFileLoader:
    """Loads scene files in child processes, each stopped after ``timeout`` seconds; one load at a time."""

    def __init__(self, timeout: float = DEFAULT_TIMEOUT_S) -> None:
        if isinstance(timeout, bool) or not isinstance(timeout, (int, float)) or not (math.isfinite(timeout)
                                                                                     and timeout > 0):
            raise ParameterError(f"scene file load timeout must be a number of seconds > 0, got {timeout!r}")
        self.timeout = float(timeout)
        self._spare: _Child | None = None
        self._load: _Child | _ThreadLoad | None = None
        self._closed = False

    @property
    def loading(self) -> Path | None:
        """The file being loaded, or None."""
        return self._load.path if self._load is not None else None

    def elapsed(self) -> float:
        """Seconds since the load in progress started (0 when none is)."""
        return time.monotonic() - self._load.started if self._load is not None else 0.0

    def start(self, path: str | Path) -> None:
        """Start loading ``path``; a load still in progress is stopped (the newest wins)."""
        self.cancel()
        child, self._spare = self._spare, None
        if child is None or child.proc.poll() is not None:  # none kept, or it died waiting
            if child is not None:
                child.kill()
            child = _Child()
        child.request(Path(path))
        self._load = child

    def poll(self) -> SceneFile | None:
        """The finished load's SceneFile, or None while it runs (or none was started); never blocks.

        Raises SceneFileError when the file failed, ran past the time limit or ended its process.
        While no load runs, a process is started for the next one."""
        try:
            return self._take() if self._load is not None else None
        finally:
            if self._load is None and self._spare is None and not self._closed:
                self._spare = _Child()

    def wait(self, path: str | Path) -> SceneFile:
        """Load ``path`` and wait for it (raises as :meth:`poll`; starts no process for a next load)."""
        self.start(path)
        try:
            while True:
                sf = self._take()
                if sf is not None:
                    return sf
                time.sleep(0.02)
        except BaseException:
            self.cancel()  # Ctrl-C while waiting stops the child too
            raise

    def _take(self) -> SceneFile | None:
        """The load in progress's SceneFile once it is done (it is then no longer in progress), else None."""
        load = self._load
        try:
            answer = load.result(self.timeout)
        except SceneFileError:
            self._load = None
            raise
        if answer is None:
            return None
        if answer[0] == "local":
            self._load = _ThreadLoad(load.path)
            return None
        self._load = None
        if answer[0] == "error":
            raise SceneFileError(answer[1])
        _, scene, camera, settings = answer
        return SceneFile(load.path, scene, camera, settings)

    def cancel(self) -> None:
        """Stop the load in progress, if any."""
        if self._load is not None:
            self._load.kill()
            self._load = None

    def close(self) -> None:
        """Stop the load in progress and the process kept for the next one (polls start no other)."""
        self._closed = True
        self.cancel()
        if self._spare is not None:
            self._spare.kill()
            self._spare = None


def _watch_parent(stdin: Any) -> None:
    """In the child: end when the parent closes the request pipe (it closed or died)."""
    stdin.read()
    os._exit(70)


def main(result_fd: int) -> None:
    """The child: read one request line from stdin, load the file, write the pickled answer to ``result_fd``."""
    line = sys.stdin.buffer.readline()
    if not line:
        return
    req = json.loads(line)
    threading.Thread(target=_watch_parent, args=(sys.stdin.buffer,), daemon=True).start()
    os.chdir(req["cwd"])
    try:
        sf = load_scene_file(req["path"])
        answer: tuple = ("ok", sf.scene, sf.camera, sf.settings)
    except BaseException as exc:  # noqa: BLE001 - a scene file may raise anything: its message goes back
        answer = ("error", _message(exc))
    try:
        data = pickle.dumps(answer)
    except Exception:  # noqa: BLE001 - e.g. nodes of a class the file defines
        data = pickle.dumps(("local",))  # the parent loads it in a thread
    sys.stdout.flush()  # what the file printed, before the parent, answered, ends this process
    sys.stderr.flush()
    with os.fdopen(result_fd, "wb") as out:
        out.write(data)
    os._exit(0)  # the file's atexit handlers and threads are not waited for

