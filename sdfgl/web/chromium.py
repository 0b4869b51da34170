"""Headless Chromium driven over the DevTools protocol on a pipe (no port, no extra packages).

Used by the browser tests and the README screenshot: load a page, run JavaScript in it,
take a screenshot. WebGL2 runs on SwiftShader (software), so no GPU is needed.

    with Chromium(size=(800, 600)) as b:
        b.goto(Path("part.html").resolve().as_uri())
        b.wait_for("document.querySelector('#sdfgl-root').dataset.still === '1'")
        png = b.screenshot()
"""
from __future__ import annotations

import base64
import fcntl
import io
import json
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import SdfglError

EXECUTABLES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
# software WebGL2 (SwiftShader through ANGLE): works headless, without a GPU or display
FLAGS = ("--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
         "--force-device-scale-factor=1", "--force-color-profile=srgb", "--hide-scrollbars", "--no-first-run",
         "--no-default-browser-check", "--disable-extensions", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--mute-audio", "--remote-debugging-pipe")


def _high(fd: int) -> int:
    """``fd`` moved to a descriptor number >= 10."""
    new = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
    os.close(fd)
    return new


def find_chromium() -> str | None:
    """Path of a Chromium (or Chrome) executable on PATH, or None."""
    for name in EXECUTABLES:
        path = shutil.which(name)
        if path:
            return path
    return None


class Chromium:
    """One headless Chromium with one page, controlled over --remote-debugging-pipe."""

    def __init__(self, size: tuple[int, int] = (800, 600), executable: str | None = None,
                 timeout: float = 60.0) -> None:
        exe = executable or find_chromium()
        if exe is None:
            raise SdfglError("no Chromium found on PATH (Debian: apt-get install chromium)")
        self.timeout = timeout
        self._profile = tempfile.TemporaryDirectory(prefix="sdfgl-chromium-")
        to_child, self._write = os.pipe()    # the browser reads commands on its fd 3
        self._read, from_child = os.pipe()   # and writes replies on its fd 4
        # moved above 9 so that neither end already is fd 3 or 4 when bash renumbers them
        to_child, from_child = (_high(fd) for fd in (to_child, from_child))
        args = [*FLAGS, f"--user-data-dir={self._profile.name}", f"--window-size={size[0]},{size[1]}", "about:blank"]
        # bash moves the pipe ends to fds 3 and 4, where Chromium expects them
        script = f'exec "$0" "$@" 3<&{to_child} 4>&{from_child} {to_child}<&- {from_child}>&-'
        # the browser's log goes to a file: a pipe nobody reads could fill up and stall it
        self._log = open(Path(self._profile.name) / "stderr.log", "w+b")  # noqa: SIM115 - closed in close()
        self.proc = subprocess.Popen(["bash", "-c", script, exe, *args], pass_fds=(to_child, from_child),
                                     stdout=subprocess.DEVNULL, stderr=self._log)
        os.close(to_child)
        os.close(from_child)
        self._buffer = b""
        self._next_id = 0
        self.console: list[str] = []
        try:
            targets = self.send("Target.getTargets")["targetInfos"]
            page = next(t for t in targets if t["type"] == "page")
            self.session = self.send("Target.attachToTarget", {"targetId": page["targetId"], "flatten": True})["sessionId"]
            for domain in ("Page.enable", "Runtime.enable"):
                self.send(domain, session=True)
            # the window size includes the (invisible) browser frame; fix the page's own size
            self.send("Emulation.setDeviceMetricsOverride", {"width": size[0], "height": size[1],
                                                             "deviceScaleFactor": 1, "mobile": False}, session=True)
        except BaseException:
            self.close()
            raise

    # -- protocol ------------------------------------------------------------------------
    def _message(self, deadline: float) -> dict[str, Any]:
        while b"\0" not in self._buffer:
            if time.monotonic() > deadline:
                raise SdfglError("Chromium did not answer in time")
            chunk = os.read(self._read, 1 << 20)
            if not chunk:
                raise self._exited()
            self._buffer += chunk
        raw, _, self._buffer = self._buffer.partition(b"\0")
        return json.loads(raw)

    def _exited(self) -> SdfglError:
        """The error for a browser that has gone: its exit status and the end of its log."""
        self._log.seek(0)
        log = self._log.read().decode(errors="replace")[-2000:]
        return SdfglError(f"Chromium exited (status {self.proc.wait()}): {log}")

    def send(self, method: str, params: dict[str, Any] | None = None, session: bool = False) -> dict[str, Any]:
        """Call a DevTools method (on the page's session if ``session``) and return its result."""
        self._next_id += 1
        msg: dict[str, Any] = {"id": self._next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = self.session
        try:
            os.write(self._write, json.dumps(msg).encode() + b"\0")
        except BrokenPipeError:
            raise self._exited() from None
        deadline = time.monotonic() + self.timeout
        while True:
            reply = self._message(deadline)
            if reply.get("method") == "Runtime.consoleAPICalled":
                self.console.append(" ".join(str(a.get("value", a.get("description", "")))
                                             for a in reply["params"]["args"]))
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise SdfglError(f"Chromium: {method} failed: {reply['error'].get('message')}")
                return reply.get("result", {})

    # -- the page ------------------------------------------------------------------------
    def goto(self, url: str) -> None:
        """Load ``url`` and wait until its load event."""
        self.send("Page.navigate", {"url": url}, session=True)
        self.wait_for("document.readyState === 'complete'")

    def evaluate(self, expression: str) -> Any:
        """Value of a JavaScript expression in the page (promises are awaited)."""
        res = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True, "awaitPromise": True},
                        session=True)
        if "exceptionDetails" in res:
            details = res["exceptionDetails"]
            raise SdfglError(f"JavaScript error: {details.get('exception', {}).get('description', details.get('text'))}")
        return res["result"].get("value")

    def wait_for(self, expression: str, timeout: float | None = None) -> None:
        """Poll until a JavaScript expression is true."""
        deadline = time.monotonic() + (timeout or self.timeout)
        while not self.evaluate(f"Boolean({expression})"):
            if time.monotonic() > deadline:
                raise SdfglError(f"timed out waiting for {expression}")
            time.sleep(0.05)

    def screenshot(self, clip: tuple[float, float, float, float] | None = None) -> np.ndarray:
        """The page (or the CSS-pixel rectangle x, y, width, height of it) as uint8 RGB (H, W, 3)."""
        from PIL import Image
        params: dict[str, Any] = {"format": "png"}
        if clip is not None:
            x, y, w, h = clip
            params["clip"] = {"x": x, "y": y, "width": w, "height": h, "scale": 1}
        data = base64.b64decode(self.send("Page.captureScreenshot", params, session=True)["data"])
        return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))

    def close(self) -> None:
        """Quit the browser and remove its profile."""
        if self.proc.poll() is None:
            try:
                os.write(self._write, json.dumps({"id": 0, "method": "Browser.close"}).encode() + b"\0")
                self.proc.wait(timeout=10)
            except (OSError, subprocess.TimeoutExpired):
                self.proc.kill()
                self.proc.wait()
        for fd in (self._read, self._write):
            try:
                os.close(fd)
            except OSError:
                pass
        self._log.close()
        self._profile.cleanup()

    def __enter__(self) -> "Chromium":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def file_url(path: str | Path) -> str:
    """The file:// URL of a local file."""
    return Path(path).resolve().as_uri()
