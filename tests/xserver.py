"""A private Xvfb display for window tests, and xdotool helpers."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from sdfgl import xdisplay


def start_xvfb() -> tuple[subprocess.Popen, str]:
    """A private Xvfb display (sdfgl.xdisplay) for the window tests; stop it with stop_xvfb."""
    if shutil.which("Xvfb") is None or shutil.which("xdotool") is None:
        pytest.fail("window tests need Xvfb and xdotool: run ./install.sh --test (apt-get install xvfb xdotool)")
    proc, name = xdisplay.start_xvfb("1600x900x24")
    if proc is None:
        pytest.fail(name)
    return proc, name


class Driver:
    """Real X input events (XTEST through xdotool) into one viewer process."""

    def __init__(self, display: str, state_file: Path) -> None:
        self.env = {**os.environ, "DISPLAY": display}
        self.state_file = state_file
        self.window = ""

    def xdo(self, *args: str) -> str:
        out = subprocess.run(["xdotool", *args], env=self.env, capture_output=True, text=True, timeout=20)
        return out.stdout.strip()

    def find_window(self, timeout: float = 30.0) -> str:
        deadline = time.time() + timeout
        while time.time() < deadline:
            ids = self.xdo("search", "--name", "^sdfgl").split()
            if ids:
                self.window = ids[0]
                self.xdo("windowfocus", "--sync", self.window)
                return self.window
            time.sleep(0.1)
        raise AssertionError("the viewer window never appeared")

    def launch(self, *args: str, timeout: float = 120.0) -> subprocess.Popen:
        """Start ``sdfgl view *args`` writing this driver's state file and wait for its window; say why
        the viewer died if it did (a loaded machine can take long to import and open the window).

        A viewer that could not open the display is started again (up to 3 tries): on the shared test
        machine a connection to a live Xvfb is now and then refused (seen a few times a day, not
        reproduced in 300 connections in a row)."""
        for attempt in range(3):
            proc = subprocess.Popen([sys.executable, "-m", "sdfgl.cli", "view", *args, "--state-file",
                                     str(self.state_file)], env=self.env, stdout=subprocess.PIPE,
                                    stderr=subprocess.PIPE, text=True)
            try:
                self.find_window(timeout)
                return proc
            except AssertionError:
                if proc.poll() is None:
                    proc.kill()
                    proc.wait(10)
                    raise
                err = proc.stderr.read()[-2000:]
                if "Failed to open display" not in err or attempt == 2:
                    raise AssertionError(f"the viewer exited ({proc.returncode}): {err}") from None
                time.sleep(1.0)
        raise AssertionError("unreachable")

    def _read_state(self) -> dict | None:
        """The viewer's state file, or None while it is missing or half written."""
        try:
            return json.loads(self.state_file.read_text())
        except (OSError, ValueError):
            return None

    def state(self) -> dict:
        for _ in range(50):
            st = self._read_state()
            if st is not None:
                return st
            time.sleep(0.05)
        raise AssertionError("no state file")

    def wait_for(self, pred, timeout: float = 20.0, what: str = "condition") -> dict:  # noqa: ANN001
        # a state file not written yet (the first compile on a loaded machine) is "not yet",
        # not a failure, until the deadline
        deadline = time.time() + timeout
        st = {}
        while time.time() < deadline:
            st = self._read_state() or {}
            if st and pred(st):
                return st
            time.sleep(0.05)
        st.pop("frame_log", None)
        raise AssertionError(f"timed out waiting for {what}; state: {st}")

    def drag(self, button: int, x0: int, y0: int, dx: int, dy: int, steps: int = 8) -> None:
        self.xdo("mousemove", "--window", self.window, str(x0), str(y0), "mousedown", str(button))
        for i in range(1, steps + 1):
            self.xdo("mousemove", "--window", self.window, str(x0 + dx * i // steps), str(y0 + dy * i // steps))
            time.sleep(0.02)
        self.xdo("mouseup", str(button))

    def key(self, name: str) -> None:
        self.xdo("key", "--window", self.window, name)

    def scroll(self, up: bool, times: int = 1) -> None:
        for _ in range(times):
            self.xdo("click", "--window", self.window, "4" if up else "5")


class XTest:
    """Pointer motion through libXtst directly (no process per event, unlike xdotool), for timing
    input-to-redraw latency: ``move`` returns once the event is flushed to the X server."""

    def __init__(self, display: str) -> None:
        import ctypes
        self._x11 = ctypes.CDLL("libX11.so.6")
        self._xtst = ctypes.CDLL("libXtst.so.6")
        self._x11.XOpenDisplay.restype = ctypes.c_void_p
        self._x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
        self._x11.XFlush.argtypes = [ctypes.c_void_p]
        self._x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
        self._xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                                    ctypes.c_ulong]
        self._dpy = self._x11.XOpenDisplay(display.encode())
        if not self._dpy:
            raise AssertionError(f"cannot open X display {display}")

    def move(self, x: int, y: int) -> None:
        """Move the pointer to screen position (x, y)."""
        self._xtst.XTestFakeMotionEvent(self._dpy, -1, x, y, 0)
        self._x11.XFlush(self._dpy)

    def close(self) -> None:
        self._x11.XCloseDisplay(self._dpy)


def request_close(display: str, window: str) -> None:
    """Ask ``window`` to close as a window manager does: a WM_PROTOCOLS client message carrying
    WM_DELETE_WINDOW (what a title bar's close button sends), through libX11 directly."""
    import ctypes

    class ClientMessage(ctypes.Structure):
        _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                    ("display", ctypes.c_void_p), ("window", ctypes.c_ulong), ("message_type", ctypes.c_ulong),
                    ("format", ctypes.c_int), ("data", ctypes.c_long * 5)]

    class XEvent(ctypes.Union):
        _fields_ = [("xclient", ClientMessage), ("pad", ctypes.c_long * 24)]

    x11 = ctypes.CDLL("libX11.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XInternAtom.restype = ctypes.c_ulong
    x11.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
    x11.XSendEvent.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_long, ctypes.POINTER(XEvent)]
    x11.XFlush.argtypes = [ctypes.c_void_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    dpy = x11.XOpenDisplay(display.encode())
    if not dpy:
        raise AssertionError(f"cannot open X display {display}")
    try:
        ev = XEvent()
        ev.xclient.type = 33  # ClientMessage
        ev.xclient.window = int(window)
        ev.xclient.message_type = x11.XInternAtom(dpy, b"WM_PROTOCOLS", 0)
        ev.xclient.format = 32
        ev.xclient.data[0] = x11.XInternAtom(dpy, b"WM_DELETE_WINDOW", 0)
        ev.xclient.data[1] = 0  # CurrentTime
        if not x11.XSendEvent(dpy, int(window), 0, 0, ctypes.byref(ev)):
            raise AssertionError("XSendEvent failed")
        x11.XFlush(dpy)
    finally:
        x11.XCloseDisplay(dpy)
